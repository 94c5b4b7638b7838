// tests/collision/contacts_test.cpp: contacts against the ground plane (self-made manifolds).
#include "test_models.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::collision::test
{
namespace
{

constexpr double cTol = 1e-9;

TEST(PlaneContacts, BoxRestingGivesFourBottomCorners)
{
    core::Model model;
    model.bodies.push_back(moving("box", box(0.4, 0.2, 0.1), Vec3(1.0, 2.0, 0.05 - 0.001)));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
    {
        EXPECT_EQ(c.bodyA, 0);
        EXPECT_EQ(c.bodyB, 1);
        EXPECT_NEAR((c.normal_W - Vec3(0, 0, -1)).norm(), 0.0, cTol); // box -> floor
        EXPECT_NEAR(c.depth, 0.001, cTol);
        EXPECT_NEAR(std::abs(c.point_W.x() - 1.0), 0.2, cTol);
        EXPECT_NEAR(std::abs(c.point_W.y() - 2.0), 0.1, cTol);
        EXPECT_NEAR(c.point_W.z(), -0.0005, cTol); // middle of the overlap
    }
}

TEST(PlaneContacts, FloorFirstStillPutsTheMovingBodyFirst)
{
    core::Model model;
    model.bodies.push_back(floorBody());
    model.bodies.push_back(moving("box", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.099)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
    {
        EXPECT_EQ(c.bodyA, 1);
        EXPECT_EQ(c.bodyB, 0);
        EXPECT_NEAR(c.normal_W.z(), -1.0, cTol);
    }
}

TEST(PlaneContacts, TiltedBoxOnAnEdgeGivesTwo)
{
    const double angle = 0.3; // rad about x: the bottom edge along x touches
    const double lowest = 0.1 * std::cos(angle) + 0.1 * std::sin(angle); // half extent 0.1
    core::Model model;
    model.bodies.push_back(
        moving("box", box(0.2, 0.2, 0.2), Vec3(0, 0, lowest - 0.001), rotation(angle, Vec3::UnitX())));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    EXPECT_NEAR(std::abs(contacts[0].point_W.x() - contacts[1].point_W.x()), 0.2, 1e-9);
    for (const Contact& c : contacts)
        EXPECT_NEAR(c.depth, 0.001, 1e-9);
}

TEST(PlaneContacts, TiltedBoxOnACornerGivesOne)
{
    const Quat q = rotation(0.4, Vec3::UnitX()) * rotation(0.3, Vec3::UnitY());
    const core::Mat3 rot = q.toRotationMatrix();
    double lowest = 0.0;
    for (int k = 0; k < 8; ++k)
    {
        const Vec3 corner((k & 1) ? 0.1 : -0.1, (k & 2) ? 0.1 : -0.1, (k & 4) ? 0.1 : -0.1);
        lowest = std::min(lowest, (rot * corner).z());
    }
    core::Model model;
    model.bodies.push_back(moving("box", box(0.2, 0.2, 0.2), Vec3(0, 0, -lowest - 0.001), q));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].depth, 0.001, 1e-9);
}

TEST(PlaneContacts, SphereDepthAndPoint)
{
    core::Model model;
    model.bodies.push_back(floorBody());
    model.bodies.push_back(moving("ball", sphere(0.1), Vec3(0.3, -0.2, 0.098)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 1u);
    const Contact& c = contacts[0];
    EXPECT_EQ(c.bodyA, 1);
    EXPECT_EQ(c.bodyB, 0);
    EXPECT_NEAR(c.depth, 0.002, cTol);
    EXPECT_NEAR((c.point_W - Vec3(0.3, -0.2, -0.001)).norm(), 0.0, cTol);
    EXPECT_NEAR((c.normal_W - Vec3(0, 0, -1)).norm(), 0.0, cTol);
}

TEST(PlaneContacts, CapsuleLyingGivesTwoEndContacts)
{
    core::Model model;
    model.bodies.push_back(moving("capsule", capsule(0.05, 0.4), Vec3(0, 0, 0.049),
                                  rotation(std::numbers::pi / 2, Vec3::UnitY()))); // axis along x
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    EXPECT_NEAR(std::abs(contacts[0].point_W.x()), 0.2, 1e-9);
    EXPECT_NEAR(std::abs(contacts[1].point_W.x()), 0.2, 1e-9);
    EXPECT_LT(contacts[0].point_W.x() * contacts[1].point_W.x(), 0.0);
    for (const Contact& c : contacts)
        EXPECT_NEAR(c.depth, 0.001, 1e-9);
}

bool nonCollinear(const std::vector<Contact>& contacts)
{
    for (std::size_t i = 0; i < contacts.size(); ++i)
        for (std::size_t j = i + 1; j < contacts.size(); ++j)
            for (std::size_t k = j + 1; k < contacts.size(); ++k)
            {
                const Vec3 a = contacts[j].point_W - contacts[i].point_W;
                const Vec3 b = contacts[k].point_W - contacts[i].point_W;
                if (a.cross(b).norm() > 1e-4)
                    return true;
            }
    return false;
}

TEST(PlaneContacts, StandingCylinderGivesAPatch)
{
    core::Model model;
    model.bodies.push_back(moving("can", cylinder(0.1, 0.3), Vec3(0, 0, 0.149)));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_GE(contacts.size(), 3u);
    EXPECT_LE(contacts.size(), 4u);
    EXPECT_TRUE(nonCollinear(contacts));
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, 1e-9);
        EXPECT_NEAR(std::hypot(c.point_W.x(), c.point_W.y()), 0.1, 1e-9); // on the rim
    }
}

TEST(PlaneContacts, LyingCylinderGivesTwoAtTheRims)
{
    core::Model model;
    // Axis along y, turned about it by an odd angle so no rim sample sits at the bottom.
    model.bodies.push_back(
        moving("log", cylinder(0.1, 0.5), Vec3(0, 0, 0.099),
               rotation(std::numbers::pi / 2, Vec3::UnitX()) * rotation(0.3, Vec3::UnitZ())));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 2u);
    EXPECT_NEAR(std::abs(contacts[0].point_W.y()), 0.25, 1e-9);
    EXPECT_NEAR(std::abs(contacts[1].point_W.y()), 0.25, 1e-9);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, 1e-9);
        EXPECT_NEAR(c.point_W.x(), 0.0, 1e-9);
    }
}

TEST(PlaneContacts, MeshCubeGivesItsFourBottomCorners)
{
    core::Model model;
    model.bodies.push_back(moving("cube", cubeMesh(0.2), Vec3(0, 0, 0.099)));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, cTol);
        EXPECT_NEAR(std::abs(c.point_W.x()), 0.1, cTol);
        EXPECT_NEAR(std::abs(c.point_W.y()), 0.1, cTol);
        EXPECT_NEAR(c.normal_W.z(), -1.0, cTol);
    }
}

TEST(PlaneContacts, GapBelowTheMarginIsReportedWithNegativeDepth)
{
    core::Model model;
    model.bodies.push_back(moving("box", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.1005)));
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model, 1e-3);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
        EXPECT_NEAR(c.depth, -0.0005, cTol);
}

TEST(PlaneContacts, SeparatedGivesNothing)
{
    core::Model model;
    model.bodies.push_back(moving("box", box(0.2, 0.2, 0.2), Vec3(0, 0, 0.11)));
    model.bodies.push_back(moving("ball", sphere(0.1), Vec3(1, 0, 0.2)));
    model.bodies.push_back(floorBody());
    EXPECT_TRUE(detectAll(model).empty());
}

TEST(PlaneContacts, ShapeOffsetInTheBodyFrameIsApplied)
{
    core::Model model;
    core::Body body =
        moving("arm", box(0.1, 0.1, 0.1), Vec3(0, 0, 0.5), rotation(std::numbers::pi / 2, Vec3::UnitX()));
    body.shapes[0].position_BS = Vec3(0, -0.451, 0); // body y is world z: centre at z 0.049
    model.bodies.push_back(body);
    model.bodies.push_back(floorBody());
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 4u);
    for (const Contact& c : contacts)
        EXPECT_NEAR(c.depth, 0.001, 1e-9);
}

TEST(PlaneContacts, TiltedPlaneWithOffset)
{
    core::Model model;
    core::Body ground = floorBody();
    ground.shapes[0].normal = Vec3(0, 1, 1).normalized();
    ground.shapes[0].offset = 0.5; // n . x <= 0.5
    model.bodies.push_back(ground);
    const Vec3 n = ground.shapes[0].normal;
    model.bodies.push_back(moving("ball", sphere(0.1), n * (0.5 + 0.1 - 0.003)));
    const auto contacts = detectAll(model);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_NEAR(contacts[0].depth, 0.003, 1e-9);
    EXPECT_NEAR((contacts[0].normal_W + n).norm(), 0.0, 1e-9);
    EXPECT_NEAR(n.dot(contacts[0].point_W), 0.5 - 0.0015, 1e-9);
}

} // namespace
} // namespace frontier::collision::test
