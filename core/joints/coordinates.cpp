// core/joints/coordinates.cpp: joint angles and slides, their velocity rows, and the continuous angle.
#include "core/joints/coordinates.h"

#include "core/joints/joint_types.h"

#include <array>
#include <cmath>
#include <numbers>

namespace frontier::core
{

std::span<const JointCoordinate> jointCoordinates(JointType type)
{
    return jointTypeInfo(type).coordinates;
}

int coordinateIndex(JointType type, JointCoordinate coordinate)
{
    const std::span<const JointCoordinate> all = jointCoordinates(type);
    for (std::size_t k = 0; k < all.size(); ++k)
    {
        if (all[k] == coordinate)
        {
            return static_cast<int>(k);
        }
    }
    return -1;
}

bool hasJointAngle(JointType type)
{
    return coordinateIndex(type, JointCoordinate::Rotation) >= 0;
}

JointPose jointPose(const State& state, const Joint& joint)
{
    JointPose pose;
    if (joint.parent != cWorld)
    {
        const BodyState& a = state.bodies[static_cast<std::size_t>(joint.parent)];
        pose.x_a = a.position_W;
        pose.q_a = a.orientation_WB;
    }
    const BodyState& b = state.bodies[static_cast<std::size_t>(joint.child)];
    pose.x_b = b.position_W;
    pose.q_b = b.orientation_WB;
    return pose;
}

CoordinateRow coordinateRow(const Joint& joint, const detail::JointGeometry& g, JointCoordinate coordinate)
{
    const Vec3 k = g.R_a * joint.axisParent;
    CoordinateRow row;
    if (coordinate == JointCoordinate::Rotation)
    {
        row.J_a.tail<3>() = -k;
        row.J_b.tail<3>() = k;
    }
    else
    {
        row.J_a.head<3>() = -k;
        row.J_a.tail<3>() = -(g.p_b - g.x_a).cross(k);
        row.J_b.head<3>() = k;
        row.J_b.tail<3>() = g.r_b.cross(k);
    }
    return row;
}

double wrappedJointAngle(const Joint& joint, const Mat3& R_a, const Mat3& R_b)
{
    const Vec3 ic = R_b * joint.perpChild1;
    return std::atan2(ic.dot(R_a * joint.perpParent2), ic.dot(R_a * joint.perpParent1));
}

double wrappedJointAngle(const Joint& joint, const detail::JointGeometry& g)
{
    return wrappedJointAngle(joint, g.R_a, g.R_b);
}

double jointSlide(const Joint& joint, const detail::JointGeometry& g)
{
    return (g.R_a * joint.axisParent).dot(g.p_b - g.p_a);
}

double continuedAngle(double wrapped, double reference)
{
    constexpr double cTurn = 2.0 * std::numbers::pi;
    const double turns = std::round((reference - wrapped) / cTurn);
    return turns == 0.0 ? wrapped : wrapped + turns * cTurn;
}

namespace
{
double referenceAngle(const State& state, int jointIndex)
{
    const std::size_t k = static_cast<std::size_t>(jointIndex);
    return k < state.jointAngles.size() ? state.jointAngles[k] : 0.0;
}
} // namespace

double jointCoordinate(const Model& model, const State& state, int jointIndex, JointCoordinate coordinate)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    const detail::JointGeometry g = detail::jointGeometry(joint, jointPose(state, joint));
    if (coordinate == JointCoordinate::Slide)
    {
        return jointSlide(joint, g);
    }
    return continuedAngle(wrappedJointAngle(joint, g), referenceAngle(state, jointIndex));
}

double jointCoordinate(const Model& model, const State& state, int jointIndex)
{
    const JointType type = model.joints[static_cast<std::size_t>(jointIndex)].type;
    return jointCoordinate(model, state, jointIndex,
                           jointTypeInfo(type).limitCoordinate.value_or(JointCoordinate::Slide));
}

double fileCoordinate(const Model& model, const State& state, int jointIndex, JointCoordinate coordinate)
{
    return model.joints[static_cast<std::size_t>(jointIndex)].initialPosition +
           jointCoordinate(model, state, jointIndex, coordinate);
}

double jointCoordinateVelocity(const Model& model, const State& state, int jointIndex,
                               JointCoordinate coordinate)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    const CoordinateRow row =
        coordinateRow(joint, detail::jointGeometry(joint, jointPose(state, joint)), coordinate);
    auto velocity = [&](int body)
    {
        const BodyState& s = state.bodies[static_cast<std::size_t>(body)];
        return (Vec6() << s.velocity_W, s.angularVelocity_W).finished();
    };
    double rate = row.J_b.dot(velocity(joint.child));
    if (isMovingBody(model, joint.parent))
    {
        rate += row.J_a.dot(velocity(joint.parent));
    }
    return rate;
}

void trackJointAngles(const Model& model, State& state)
{
    // Every step, for every hinge: only the two rotations the angle needs (no JointGeometry).
    state.jointAngles.resize(model.joints.size(), 0.0);
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const Joint& joint = model.joints[k];
        if (!hasJointAngle(joint.type))
        {
            continue;
        }
        const Mat3 R_a = jointPose(state, joint).q_a.toRotationMatrix();
        const Mat3 R_b =
            state.bodies[static_cast<std::size_t>(joint.child)].orientation_WB.toRotationMatrix();
        state.jointAngles[k] = continuedAngle(wrappedJointAngle(joint, R_a, R_b), state.jointAngles[k]);
    }
}

} // namespace frontier::core
