// tests/core/coordinates_test.cpp: joint coordinates (core/joints/coordinates.cpp). The continued
// angle picks the whole turn nearest its reference and leaves a wrapped angle alone when no turn is
// needed; each coordinate's row is its time derivative (finite differences on random poses and
// velocities, moving parents); trackJointAngles counts turns a child makes about its hinge; a
// coordinate's velocity at a state is the relative spin or slide along the axis (closed forms).
#include "core/joints/coordinates.h"
#include "random_model.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::test
{
namespace
{

constexpr double cPi = std::numbers::pi;

TEST(JointCoordinates, ContinuedAngleTakesTheNearestTurn)
{
    EXPECT_EQ(core::continuedAngle(0.3, 0.0), 0.3);
    EXPECT_EQ(core::continuedAngle(-3.1, 0.0), -3.1) << "within half a turn: the wrapped angle itself";
    EXPECT_NEAR(core::continuedAngle(-3.0, 3.2), -3.0 + 2.0 * cPi, 1e-15);
    EXPECT_NEAR(core::continuedAngle(3.0, -9.5), 3.0 - 4.0 * cPi, 1e-14);
    EXPECT_NEAR(core::continuedAngle(0.1, 100.0 * cPi + 0.05), 0.1 + 100.0 * cPi, 1e-12);
}

// Advances a pose by a small time dt at body velocities u_a, u_b (positions straight, rotations by
// the exact exponential).
core::JointPose advance(const core::JointPose& pose, const Vec6& u_a, const Vec6& u_b, double dt)
{
    auto turn = [dt](const Quat& q, const Vec3& w)
    {
        const double angle = w.norm() * dt;
        return (Quat(Eigen::AngleAxisd(angle, w.normalized())) * q).normalized();
    };
    core::JointPose out = pose;
    out.x_a += dt * u_a.head<3>();
    out.x_b += dt * u_b.head<3>();
    out.q_a = turn(pose.q_a, u_a.tail<3>());
    out.q_b = turn(pose.q_b, u_b.tail<3>());
    return out;
}

double coordinateAt(const core::Joint& joint, const core::JointPose& pose, core::JointCoordinate coordinate,
                    double reference)
{
    const core::detail::JointGeometry g = core::detail::jointGeometry(joint, pose);
    return coordinate == core::JointCoordinate::Slide
               ? core::jointSlide(joint, g)
               : core::continuedAngle(core::wrappedJointAngle(joint, g), reference);
}

TEST(JointCoordinates, RowsAreTheDerivativeOfTheCoordinates)
{
    Rng rng(5);
    for (const core::JointType type :
         {core::JointType::Revolute, core::JointType::Prismatic, core::JointType::Cylindrical})
    {
        for (int trial = 0; trial < 20; ++trial)
        {
            core::Model model;
            // One draw per statement (argument order is the compiler's), in the order g++ took them.
            const Quat qa = rng.rotation();
            model.bodies.push_back(boxBody("a", 1.0, Vec3(0.3, 0.2, 0.1), rng.gaussianVec(), qa));
            const Quat qb = rng.rotation();
            model.bodies.push_back(boxBody("b", 1.0, Vec3(0.3, 0.2, 0.1), rng.gaussianVec(), qb));
            const Vec3 axis = rng.unitVec();
            addJoint(model, "j", type, 0, 1, rng.gaussianVec(), axis);
            const core::Joint& joint = model.joints[0];
            // A pose away from the start: the child turned about the axis and slid along it, then
            // both moved together, so the joint's conditions hold.
            core::JointPose pose;
            pose.x_a = model.bodies[0].position_W;
            pose.q_a = model.bodies[0].orientation_WB;
            pose.x_b = model.bodies[1].position_W;
            pose.q_b = model.bodies[1].orientation_WB;
            const Vec3 k = pose.q_a * joint.axisParent;
            const Vec3 anchor = pose.x_a + pose.q_a * joint.anchorParent;
            if (core::hasJointAngle(type))
            {
                const Quat turn(Eigen::AngleAxisd(rng.uniform(-3.0, 3.0), k));
                pose.q_b = turn * pose.q_b;
                pose.x_b = anchor + turn * (pose.x_b - anchor);
            }
            if (type != core::JointType::Revolute)
            {
                pose.x_b += rng.uniform(-1.0, 1.0) * k;
            }
            const Vec6 u_a = (Vec6() << rng.gaussianVec(), rng.gaussianVec()).finished();
            const Vec6 u_b = (Vec6() << rng.gaussianVec(), rng.gaussianVec()).finished();
            const core::detail::JointGeometry g = core::detail::jointGeometry(joint, pose);
            for (const core::JointCoordinate coordinate : core::jointCoordinates(type))
            {
                const core::CoordinateRow row = core::coordinateRow(joint, g, coordinate);
                const double rate = row.J_a.dot(u_a) + row.J_b.dot(u_b);
                const double dt = 1e-6;
                const double q0 = coordinateAt(joint, pose, coordinate, 0.0);
                const double plus = coordinateAt(joint, advance(pose, u_a, u_b, dt), coordinate, q0);
                const double minus = coordinateAt(joint, advance(pose, u_a, u_b, -dt), coordinate, q0);
                EXPECT_NEAR((plus - minus) / (2.0 * dt), rate, 1e-6 * (1.0 + std::abs(rate)))
                    << core::jointTypeName(type) << ", trial " << trial;
            }
        }
    }
}

// A child turned about its hinge in steps of 0.3 rad, 40 of them (12 rad, almost two turns), and
// back: the tracked angle follows to round-off, past +-pi both ways.
TEST(JointCoordinates, TrackedAngleCountsTurnsBothWays)
{
    core::Model model;
    model.bodies.push_back(boxBody("wheel", 1.0, Vec3(0.3, 0.2, 0.1), Vec3(0.0, 0.0, 1.0)));
    const Vec3 axis = Vec3(1.0, 2.0, 2.0) / 3.0;
    addJoint(model, "hinge", core::JointType::Revolute, core::cWorld, 0, Vec3(0.1, 0.0, 1.0), axis);
    core::State state = core::initialState(model);
    const Quat start = state.bodies[0].orientation_WB;
    double expected = 0.0;
    for (int k = 0; k < 80; ++k)
    {
        expected += k < 40 ? 0.3 : -0.3;
        state.bodies[0].orientation_WB = Quat(Eigen::AngleAxisd(expected, axis)) * start;
        core::trackJointAngles(model, state);
        ASSERT_NEAR(state.jointAngles[0], expected, 1e-12) << "turn " << k;
    }
    EXPECT_NEAR(state.jointAngles[0], 0.0, 1e-12);
}

TEST(JointCoordinates, StateWithoutAnglesIsSizedAndOtherTypesStayZero)
{
    core::Model model;
    model.bodies.push_back(boxBody("a", 1.0, Vec3(0.3, 0.2, 0.1), Vec3::Zero()));
    model.bodies.push_back(boxBody("b", 1.0, Vec3(0.3, 0.2, 0.1), Vec3(1.0, 0.0, 0.0)));
    addJoint(model, "ball", core::JointType::Ball, 0, 1, Vec3(0.5, 0.0, 0.0), Vec3::UnitZ());
    addJoint(model, "nail", core::JointType::Nail, core::cWorld, 0, Vec3::Zero(), Vec3::UnitZ());
    core::State state = core::initialState(model);
    state.jointAngles.clear();
    state.bodies[1].orientation_WB = Quat(Eigen::AngleAxisd(2.0, Vec3::UnitZ()));
    core::trackJointAngles(model, state);
    ASSERT_EQ(state.jointAngles.size(), 2u);
    EXPECT_EQ(state.jointAngles[0], 0.0);
    EXPECT_EQ(state.jointAngles[1], 0.0);
}

// A cylindrical joint between two moving bodies: the parent spins about the axis through the
// anchor at 0.7 rad/s and the child, carried along, spins 1.5 rad/s faster about the axis and
// slides along it at 0.4 m/s: the angle's rate is 1.5 rad/s, the slide's 0.4 m/s. The same
// motion of both bodies together (the child at rest relative to the parent) gives 0 and 0.
TEST(JointCoordinates, VelocityIsTheRelativeSpinAndSlideAlongTheAxis)
{
    core::Model model;
    const Vec3 axis = Vec3(2.0, -1.0, 2.0) / 3.0;
    const Vec3 anchor(0.3, -0.2, 1.0);
    model.bodies.push_back(boxBody("a", 1.0, Vec3(0.3, 0.2, 0.1), anchor + Vec3(0.2, 0.1, 0.0)));
    model.bodies.push_back(boxBody("b", 1.0, Vec3(0.3, 0.2, 0.1), anchor + Vec3(-0.1, 0.3, 0.2)));
    addJoint(model, "j", core::JointType::Cylindrical, 0, 1, anchor, axis);
    core::State state = core::initialState(model);
    const double spin = 0.7; // rad/s of the parent about the axis through the anchor
    for (int both = 0; both < 2; ++both)
    {
        const double relativeSpin = both == 0 ? 1.5 : 0.0; // rad/s
        const double slide = both == 0 ? 0.4 : 0.0;        // m/s
        for (std::size_t i = 0; i < 2; ++i)
        {
            const double w = spin + (i == 1 ? relativeSpin : 0.0);
            core::BodyState& s = state.bodies[i];
            s.angularVelocity_W = w * axis;
            s.velocity_W = s.angularVelocity_W.cross(s.position_W - anchor) + (i == 1 ? slide : 0.0) * axis;
        }
        EXPECT_NEAR(core::jointCoordinateVelocity(model, state, 0, core::JointCoordinate::Rotation),
                    relativeSpin, 1e-14);
        EXPECT_NEAR(core::jointCoordinateVelocity(model, state, 0, core::JointCoordinate::Slide), slide,
                    1e-14);
    }
}

} // namespace
} // namespace frontier::test
