// tests/collision/filter_test.cpp: which pairs may collide (docs/method.md §10).
#include "test_models.h"

#include <algorithm>
#include <gtest/gtest.h>

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
} // namespace frontier::collision::test
