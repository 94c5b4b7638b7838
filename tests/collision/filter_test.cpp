// tests/collision/filter_test.cpp: which pairs may collide (docs/method.md §10).
#include "collision/filter.h"
#include "test_models.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <malloc.h>

namespace frontier::collision::test
{
namespace
{

// Two overlapping moving boxes (0 and 1) and a floor (2).
core::Model overlappingPair()
{
    core::Model model;
    model.bodies.push_back(moving("a", box(0.2, 0.2, 0.2), Vec3(0, 0, 1.0)));
    model.bodies.push_back(moving("b", box(0.2, 0.2, 0.2), Vec3(0, 0, 1.15)));
    model.bodies.push_back(floorBody());
    return model;
}

bool hasPair(const std::vector<Contact>& contacts, int a, int b)
{
    return std::any_of(contacts.begin(), contacts.end(),
                       [&](const Contact& c) { return c.bodyA == a && c.bodyB == b; });
}

bool hasCandidate(const ContactDetector& detector, int a, int b)
{
    const auto& pairs = detector.candidatePairs();
    return std::find(pairs.begin(), pairs.end(), std::pair{a, b}) != pairs.end();
}

TEST(Filter, UnrelatedBodiesCollide)
{
    const core::Model model = overlappingPair();
    EXPECT_TRUE(hasPair(detectAll(model), 0, 1));
    ContactDetector detector(model);
    EXPECT_EQ(detector.candidatePairs(), (std::vector<std::pair<int, int>>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(Filter, JoinedBodiesDoNotCollide)
{
    core::Model model = overlappingPair();
    model.joints.push_back(ballJoint(0, 1));
    EXPECT_TRUE(detectAll(model).empty());
    ContactDetector detector(model);
    EXPECT_FALSE(hasCandidate(detector, 0, 1));
    EXPECT_TRUE(hasCandidate(detector, 0, 2));
}

TEST(Filter, CollideConnectedJointsDo)
{
    core::Model model = overlappingPair();
    model.joints.push_back(ballJoint(0, 1, true));
    EXPECT_TRUE(hasPair(detectAll(model), 0, 1));
}

TEST(Filter, JointToTheWorldChangesNothing)
{
    core::Model model = overlappingPair();
    model.joints.push_back(ballJoint(core::cWorld, 1));
    EXPECT_TRUE(hasPair(detectAll(model), 0, 1));
}

TEST(Filter, JointToAStaticBodyExcludesThatPair)
{
    core::Model model;
    model.bodies.push_back(fixed("base", box(1, 1, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("arm", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.29)));
    EXPECT_FALSE(detectAll(model).empty());
    model.joints.push_back(ballJoint(0, 1));
    EXPECT_TRUE(detectAll(model).empty());
}

TEST(Filter, OneGroupNeverCollides)
{
    core::Model model = overlappingPair();
    model.bodies[0].group = "doll";
    model.bodies[1].group = "doll";
    EXPECT_TRUE(detectAll(model).empty());
    model.bodies[1].group = "other";
    EXPECT_TRUE(hasPair(detectAll(model), 0, 1));
    model.bodies[1].group.clear(); // an empty group is no group
    model.bodies[0].group.clear();
    EXPECT_TRUE(hasPair(detectAll(model), 0, 1));
}

TEST(Filter, GroupMembersStillHitTheFloor)
{
    core::Model model;
    model.bodies.push_back(moving("a", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.099)));
    model.bodies.push_back(moving("b", box(0.2, 0.2, 0.2), Vec3(0.1, 0, 0.099)));
    model.bodies.push_back(floorBody());
    model.bodies[0].group = "doll";
    model.bodies[1].group = "doll";
    const auto contacts = detectAll(model);
    EXPECT_EQ(contacts.size(), 8u);
    EXPECT_FALSE(hasPair(contacts, 0, 1));
}

TEST(Filter, IgnoredPairsNeverCollide)
{
    core::Model model = overlappingPair();
    model.contact.ignore.push_back({1, 0});
    EXPECT_TRUE(detectAll(model).empty());
    ContactDetector detector(model);
    EXPECT_FALSE(hasCandidate(detector, 0, 1));
}

TEST(Filter, IgnoredFloorPair)
{
    core::Model model;
    model.bodies.push_back(moving("a", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.099)));
    model.bodies.push_back(floorBody());
    model.contact.ignore.push_back({0, 1});
    EXPECT_TRUE(detectAll(model).empty());
}

TEST(Filter, StaticBodiesNeverCollideWithEachOther)
{
    core::Model model;
    model.bodies.push_back(fixed("a", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.05)));
    model.bodies.push_back(fixed("b", sphere(0.2), Vec3(0.1, 0, 0.1)));
    model.bodies.push_back(floorBody());
    EXPECT_TRUE(detectAll(model).empty());
    ContactDetector detector(model);
    EXPECT_TRUE(detector.candidatePairs().empty());
}

TEST(Filter, BodiesWithoutShapesAreNoCandidates)
{
    core::Model model = overlappingPair();
    core::Body ghost = moving("ghost", box(1, 1, 1), Vec3(0, 0, 1));
    ghost.shapes.clear();
    model.bodies.push_back(ghost);
    ContactDetector detector(model);
    EXPECT_FALSE(hasCandidate(detector, 0, 3));
    EXPECT_FALSE(hasCandidate(detector, 2, 3));
}

} // namespace
// The pair count (what `frontier info` prints for a large scene) is the length of the list, with
// every rule at once: static pairs, groups holding static and moving bodies, joints and ignore
// entries that repeat a group or each other, a joint to the world, collideConnected, a body
// without shapes.
TEST(Filter, PairCountIsTheListsLength)
{
    core::Model model;
    for (int i = 0; i < 8; ++i)
        model.bodies.push_back(moving("m" + std::to_string(i), box(0.1, 0.1, 0.1), Vec3(i, 0, 1)));
    model.bodies.push_back(fixed("s8", box(0.1, 0.1, 0.1), Vec3(0, 2, 0)));
    model.bodies.push_back(fixed("s9", sphere(0.1), Vec3(1, 2, 0)));
    model.bodies.push_back(floorBody()); // 10
    core::Body ghost = moving("ghost", box(1, 1, 1), Vec3(0, 0, 3));
    ghost.shapes.clear();
    model.bodies.push_back(ghost); // 11
    for (const int b : {1, 2, 8, 9})
        model.bodies[static_cast<std::size_t>(b)].group = "g";
    model.bodies[3].group = "h";
    model.bodies[4].group = "h";
    model.joints.push_back(ballJoint(core::cWorld, 0));
    model.joints.push_back(ballJoint(0, 1));
    model.joints.push_back(ballJoint(1, 2));       // in group g already
    model.joints.push_back(ballJoint(4, 5, true)); // collides
    model.joints.push_back(ballJoint(6, 8));       // to a static body
    model.joints.push_back(ballJoint(7, 11));      // to the body without shapes
    model.contact.ignore = {{1, 0}, {0, 1}, {9, 8}, {10, 8}, {5, 6}, {3, 4}};
    ContactDetector detector(model);
    const auto& pairs = detector.candidatePairs();
    EXPECT_EQ(detector.candidatePairCount(), static_cast<long long>(pairs.size()));
    // 11 bodies with shapes: 55 pairs, less 3 static pairs, 6 in g (less s8-s9 counted as
    // static), 1 in h, and 0-1, 6-8, 5-6 (10-8 is static already).
    EXPECT_EQ(pairs.size(), 55u - 3u - 5u - 1u - 3u);
    EXPECT_TRUE(hasCandidate(detector, 4, 5));
    EXPECT_FALSE(hasCandidate(detector, 7, 11));
    // Which bodies have a partner at all (the broadphase takes only those), against the list.
    std::vector<char> among(model.bodies.size(), 1);
    among[11] = 0;
    model.contact.ignore.push_back({9, 0}); // s9's last partners: 0, ..., 7
    for (int k = 2; k < 8; ++k)
        model.contact.ignore.push_back({9, k});
    const PairFilter filter(model);
    const std::vector<char> partner = filter.hasAllowedPartner(among);
    for (int b = 0; b < 12; ++b)
    {
        bool listed = false;
        for (int c = 0; c < 12; ++c)
            listed = listed || (b != c && among[static_cast<std::size_t>(b)] &&
                                among[static_cast<std::size_t>(c)] && filter.allowed(b, c));
        EXPECT_EQ(partner[static_cast<std::size_t>(b)] != 0, listed) << "body " << b;
    }
    EXPECT_FALSE(partner[9]);
    EXPECT_TRUE(partner[8]);
}

// Set-up that scales (docs/benchmarks.md, "Start-up"): the detector of a 20 000-box chain laid
// along a line builds with its memory (the heap's own counter, not timing) linear in the bodies,
// and counts its O(n^2) candidate pairs without listing them.
TEST(Filter, LargeChainSetUpIsLinearInMemory)
{
    constexpr int n = 20000;
    core::Model model;
    model.bodies.reserve(n);
    for (int i = 0; i < n; ++i)
        model.bodies.push_back(
            moving("link" + std::to_string(i), box(0.08, 0.02, 0.02), Vec3(0.1 * i, 0, 2)));
    for (int i = 0; i < n; ++i)
        model.joints.push_back(ballJoint(i == 0 ? core::cWorld : i - 1, i));
    const std::size_t before = mallinfo2().uordblks; // bytes in use on the heap
    ContactDetector detector(model, 2e-3);
    const long long count = detector.candidatePairCount();
    const std::size_t after = mallinfo2().uordblks;
    EXPECT_EQ(count, static_cast<long long>(n) * (n - 1) / 2 - (n - 1)); // all but the joined pairs
    if (after == before)
        GTEST_SKIP() << "this allocator does not report its heap in use (a sanitizer's)";
    EXPECT_LT(static_cast<double>(after - before) / n, 2048.0) << "bytes per body";
    std::vector<Contact> contacts;
    detector.detect(core::initialState(model), contacts);
    EXPECT_TRUE(contacts.empty()); // 2 cm gaps, no floor
}

} // namespace frontier::collision::test
