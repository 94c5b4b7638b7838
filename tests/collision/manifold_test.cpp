// tests/collision/manifold_test.cpp: contacts between two shapes (FCL plus our manifolds),
// the A->B convention, contact points, and determinism.
#include "test_models.h"

#include <gtest/gtest.h>
#include <numbers>

namespace frontier::collision::test
{
namespace
{

using std::numbers::pi;

// Every contact's normal points from A's centre side towards B's.
void expectNormalsFromAToB(const core::Model& model, const std::vector<Contact>& contacts)
{
    for (const Contact& c : contacts)
    {
        const Vec3 ab = model.bodies[static_cast<std::size_t>(c.bodyB)].position_W -
                        model.bodies[static_cast<std::size_t>(c.bodyA)].position_W;
        EXPECT_GT(c.normal_W.dot(ab), 0.0);
        EXPECT_NEAR(c.normal_W.norm(), 1.0, 1e-9);
    }
}

TEST(PairContacts, BoxOnBoxGivesFour)
{
    core::Model model;
    model.bodies.push_back(fixed("table", box(1.0, 1.0, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("box", box(0.2, 0.2, 0.2), Vec3(0.1, 0, 0.3 - 0.002)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
    {
        EXPECT_EQ(c.bodyA, 1); // the moving box
        EXPECT_EQ(c.bodyB, 0);
        EXPECT_NEAR(c.normal_W.z(), -1.0, 1e-6);
        EXPECT_NEAR(c.depth, 0.002, 1e-6);
        // Between the surfaces: the table's top is z = 0.2, the box's bottom z = 0.198.
        EXPECT_GE(c.point_W.z(), 0.198 - 1e-6);
        EXPECT_LE(c.point_W.z(), 0.2 + 1e-6);
    }
}

TEST(PairContacts, NormalFollowsTheBodyIndexOrder)
{
    // Two moving boxes, stacked; bodyA is the lower index whichever is on top.
    for (const bool upperFirst : {false, true})
    {
        core::Model model;
        const core::Body lower = moving("lower", box(0.4, 0.4, 0.2), Vec3(0, 0, 0.1));
        const core::Body upper = moving("upper", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.299));
        model.bodies.push_back(upperFirst ? upper : lower);
        model.bodies.push_back(upperFirst ? lower : upper);
        const auto contacts = detectAll(model);
        ASSERT_EQ(contacts.size(), 4u);
        for (const Contact& c : contacts)
        {
            EXPECT_EQ(c.bodyA, 0);
            EXPECT_EQ(c.bodyB, 1);
            EXPECT_NEAR(c.normal_W.z(), upperFirst ? -1.0 : 1.0, 1e-6);
        }
        expectNormalsFromAToB(model, contacts);
    }
}

TEST(PairContacts, SphereSpherePointBetweenTheSurfaces)
{
    core::Model model;
    model.bodies.push_back(moving("a", sphere(0.1), Vec3(0, 0, 1)));
    model.bodies.push_back(moving("b", sphere(0.1), Vec3(0.19, 0, 1)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 1u);
    const Contact& c = contacts[0];
    EXPECT_NEAR(c.depth, 0.01, 1e-6);
    EXPECT_NEAR((c.normal_W - Vec3::UnitX()).norm(), 0.0, 1e-6);
    // b's surface is at x = 0.09, a's at x = 0.1: the middle is 0.095.
    EXPECT_NEAR(c.point_W.x(), 0.095, 1e-6);
    EXPECT_NEAR(c.point_W.z(), 1.0, 1e-6);
}

TEST(PairContacts, CapsuleLyingOnABoxGivesBothEnds)
{
    core::Model model;
    model.bodies.push_back(fixed("table", box(1.0, 1.0, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("capsule", capsule(0.05, 0.4), Vec3(0, 0.1, 0.2 + 0.05 - 0.001),
                                  rotation(pi / 2, Vec3::UnitY())));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    EXPECT_NEAR(std::abs(contacts[0].point_W.x()), 0.2, 1e-6);
    EXPECT_NEAR(std::abs(contacts[1].point_W.x()), 0.2, 1e-6);
    for (const Contact& c : contacts)
    {
        EXPECT_EQ(c.bodyA, 1);
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
        EXPECT_NEAR(c.normal_W.z(), -1.0, 1e-6);
        EXPECT_NEAR(c.point_W.z(), 0.2 - 0.0005, 1e-6);
    }
}

TEST(PairContacts, CylinderStandingOnABoxGivesAPatch)
{
    core::Model model;
    model.bodies.push_back(fixed("table", box(1.0, 1.0, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("can", cylinder(0.1, 0.3), Vec3(0, 0, 0.2 + 0.15 - 0.001)));
    const auto contacts = detectAll(model);
    ASSERT_GE(contacts.size(), 3u);
    ASSERT_LE(contacts.size(), 4u);
    const Vec3 a = contacts[1].point_W - contacts[0].point_W;
    const Vec3 b = contacts[2].point_W - contacts[0].point_W;
    EXPECT_GT(a.cross(b).norm(), 1e-4);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
        EXPECT_NEAR(c.normal_W.z(), -1.0, 1e-6);
    }
}

TEST(PairContacts, BoxOnACylinderCapGivesItsCorners)
{
    core::Model model;
    model.bodies.push_back(fixed("post", cylinder(0.3, 0.4), Vec3(0, 0, 0.2)));
    model.bodies.push_back(moving("box", box(0.2, 0.2, 0.1), Vec3(0, 0, 0.4 + 0.05 - 0.001)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
        EXPECT_NEAR(c.normal_W.z(), -1.0, 1e-6);
        EXPECT_NEAR(std::abs(c.point_W.x()), 0.1, 1e-6);
    }
}

TEST(PairContacts, CrossedCapsulesGiveOne)
{
    core::Model model;
    model.bodies.push_back(moving("a", capsule(0.05, 0.6), Vec3(0, 0, 0), rotation(pi / 2, Vec3::UnitY())));
    model.bodies.push_back(
        moving("b", capsule(0.05, 0.6), Vec3(0, 0, 0.099), rotation(pi / 2, Vec3::UnitX())));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].depth, 0.001, 1e-5);
    EXPECT_NEAR(contacts[0].normal_W.z(), 1.0, 1e-4);
}

TEST(PairContacts, ParallelCapsulesGiveTwo)
{
    core::Model model;
    model.bodies.push_back(moving("a", capsule(0.05, 0.6), Vec3(0, 0, 0), rotation(pi / 2, Vec3::UnitY())));
    model.bodies.push_back(
        moving("b", capsule(0.05, 0.6), Vec3(0, 0, 0.099), rotation(pi / 2, Vec3::UnitY())));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
        EXPECT_NEAR(c.normal_W.z(), 1.0, 1e-6);
        EXPECT_NEAR(std::abs(c.point_W.x()), 0.3, 1e-6);
    }
}

TEST(PairContacts, MeshCubeOnABox)
{
    core::Model model;
    model.bodies.push_back(moving("cube", cubeMesh(0.2), Vec3(0, 0, 0.3 - 0.002)));
    model.bodies.push_back(fixed("table", box(1.0, 1.0, 0.2), Vec3(0, 0, 0.1)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u); // its bottom corners, not FCL's per-triangle points
    for (const Contact& c : contacts)
    {
        EXPECT_EQ(c.bodyA, 0);
        EXPECT_NEAR(c.depth, 0.002, 1e-6);
        EXPECT_NEAR(c.normal_W.z(), -1.0, 1e-6); // from the cube down into the table
        EXPECT_NEAR(std::abs(c.point_W.x()), 0.1, 1e-6);
        EXPECT_NEAR(std::abs(c.point_W.y()), 0.1, 1e-6);
    }
}

TEST(PairContacts, CapsuleAcrossANarrowBoxIsHeldAtTheBoxEdges)
{
    // The capsule's ends hang over the sides; it rests on the top face between x = -0.1 and 0.1.
    core::Model model;
    model.bodies.push_back(fixed("beam", box(0.2, 1.0, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("capsule", capsule(0.05, 0.6), Vec3(0, 0, 0.2 + 0.05 - 0.001),
                                  rotation(pi / 2, Vec3::UnitY())));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(std::abs(c.point_W.x()), 0.1, 1e-6);
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
        EXPECT_NEAR(c.normal_W.z(), -1.0, 1e-6);
    }
}

TEST(PairContacts, LyingCylinderAcrossANarrowBox)
{
    core::Model model;
    model.bodies.push_back(fixed("beam", box(0.2, 1.0, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("log", cylinder(0.05, 0.6), Vec3(0, 0, 0.2 + 0.05 - 0.001),
                                  rotation(pi / 2, Vec3::UnitY()) * rotation(0.2, Vec3::UnitZ())));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(std::abs(c.point_W.x()), 0.1, 1e-6);
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
    }
}

TEST(PairContacts, StackedCylindersOfOneRadiusHaveVerticalNormals)
{
    // The upper rim lies exactly on the lower rim's edge, where the distance gradient is
    // ambiguous; the normals must still be the pair's (vertical).
    core::Model model;
    model.bodies.push_back(moving("lower", cylinder(0.1, 0.2), Vec3(0, 0, 0.1)));
    model.bodies.push_back(moving("upper", cylinder(0.1, 0.2), Vec3(0, 0, 0.299)));
    const auto contacts = detectAll(model);
    ASSERT_GE(contacts.size(), 3u);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.normal_W.z(), 1.0, 1e-6);
        EXPECT_NEAR(c.depth, 0.001, 1e-6);
    }
}

TEST(PairContacts, SeparatedBodiesGiveNothing)
{
    core::Model model;
    model.bodies.push_back(moving("a", box(0.2, 0.2, 0.2), Vec3(0, 0, 1)));
    model.bodies.push_back(moving("b", capsule(0.05, 0.3), Vec3(0.5, 0, 1)));
    model.bodies.push_back(moving("c", cylinder(0.1, 0.2), Vec3(0, 0.5, 1)));
    model.bodies.push_back(moving("d", sphere(0.1), Vec3(0, 0, 1.5)));
    EXPECT_TRUE(detectAll(model).empty());
}

// A pile of mixed, overlapping shapes on a floor.
core::Model pile()
{
    core::Model model;
    model.bodies.push_back(floorBody());
    const core::Shape shapes[] = {box(0.2, 0.3, 0.1), sphere(0.1), capsule(0.05, 0.3), cylinder(0.08, 0.2),
                                  cubeMesh(0.15)};
    int k = 0;
    for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 4; ++y)
            for (int z = 0; z < 2; ++z, ++k)
            {
                const Vec3 p(0.17 * x, 0.17 * y, 0.06 + 0.15 * z);
                model.bodies.push_back(moving("b" + std::to_string(k), shapes[k % 5], p,
                                              rotation(0.37 * k, Vec3(1, 0.3 * k, 0.5))));
            }
    return model;
}

TEST(PairContacts, DeterministicAcrossCallsAndDetectors)
{
    const core::Model model = pile();
    const core::State state = core::initialState(model);
    ContactDetector first(model);
    ContactDetector second(model);
    std::vector<Contact> a, b, c;
    first.detect(state, a);
    first.detect(state, b);
    second.detect(state, c);
    ASSERT_GT(a.size(), 20u);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
        for (const auto* other : {&b, &c})
        {
            const Contact& o = (*other)[i];
            EXPECT_EQ(a[i].bodyA, o.bodyA);
            EXPECT_EQ(a[i].bodyB, o.bodyB);
            EXPECT_EQ(a[i].point_W, o.point_W);
            EXPECT_EQ(a[i].normal_W, o.normal_W);
            EXPECT_EQ(a[i].depth, o.depth);
        }
    }
    for (const Contact& ct : a)
    {
        EXPECT_FALSE(model.bodies[static_cast<std::size_t>(ct.bodyA)].isStatic);
        EXPECT_NE(ct.bodyA, ct.bodyB);
        EXPECT_NEAR(ct.normal_W.norm(), 1.0, 1e-9);
    }
}

TEST(PairContacts, MovingBodiesAreTrackedAcrossSteps)
{
    core::Model model;
    model.bodies.push_back(moving("a", box(0.2, 0.2, 0.2), Vec3(0, 0, 1)));
    model.bodies.push_back(moving("b", box(0.2, 0.2, 0.2), Vec3(1, 0, 1)));
    ContactDetector detector(model);
    core::State state = core::initialState(model);
    std::vector<Contact> contacts;
    detector.detect(state, contacts);
    EXPECT_TRUE(contacts.empty());
    state.bodies[1].position_W = Vec3(0, 0, 1.199); // now resting on a
    detector.detect(state, contacts);
    EXPECT_EQ(contacts.size(), 4u);
    state.bodies[1].position_W = Vec3(0, 0, 2.0);
    detector.detect(state, contacts);
    EXPECT_TRUE(contacts.empty());
    EXPECT_EQ(detector.stats().detectCalls, 3);
}

} // namespace
} // namespace frontier::collision::test
