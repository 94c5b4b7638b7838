// core/joints/coordinates.h: the coordinates of a joint, what a limit bounds and a drive moves:
// the rotation of revolute and cylindrical joints about their axis (rad) and the slide of
// prismatic and cylindrical joints along it (m), and the velocity row of each.
//
//   rotation  theta = atan2(i_c . d_j, i_c . d_i), i_c the child's copy of d_i (0 at the model's
//             initial pose); d theta/dt = (w_b - w_a) . k with k = d_k fixed in the parent.
//   slide     s = k . (p_b - p_a); d s/dt = k . (v_b + w_b x r_b - v_a - w_a x (p_b - x_a)), the
//             lever arm of a at p_b (docs/method.md §2), exact also while k turns with a.
//
// atan2 gives theta only up to whole turns. A joint that turns past +-pi (a limit at 4.5 rad, a
// wheel) needs the continuous angle: State::jointAngles keeps it, continued at the end of every
// step by the whole turns that make it nearest to the angle of the step before. A step turns a
// joint by far less than pi, so the count of turns is exact; the slide needs no such care.
#pragma once

#include "core/joints/joint_rows.h"
#include "core/state.h"

#include <span>

namespace frontier::core
{

// The coordinates of a joint type, in the order of its drive rows: revolute {Rotation}, prismatic
// {Slide}, cylindrical {Slide, Rotation}; none for the other types.
std::span<const JointCoordinate> jointCoordinates(JointType type);

// The position of a coordinate in jointCoordinates(type) (its drive row after the joint's
// conditions), or -1 when the type has no such coordinate.
int coordinateIndex(JointType type, JointCoordinate coordinate);

// True for the types with a rotation coordinate (State::jointAngles is kept for them).
bool hasJointAngle(JointType type);

// The two bodies' poses for a joint: the world or a static parent at its fixed pose.
JointPose jointPose(const State& state, const Joint& joint);

// The velocity row of one coordinate: dq/dt = J_a . u_a + J_b . u_b (u = [v; w], world frame).
// J_a is meaningful only for a moving parent (callers zero it otherwise, as for joint rows).
struct CoordinateRow
{
    Vec6 J_a = Vec6::Zero();
    Vec6 J_b = Vec6::Zero();
};
CoordinateRow coordinateRow(const Joint& joint, const detail::JointGeometry& g, JointCoordinate coordinate);

// theta in [-pi, pi] (rad) and s (m) at a pose (R_a, R_b: the bodies' rotations, body to world).
double wrappedJointAngle(const Joint& joint, const Mat3& R_a, const Mat3& R_b);
double wrappedJointAngle(const Joint& joint, const detail::JointGeometry& g);
double jointSlide(const Joint& joint, const detail::JointGeometry& g);

// wrapped + 2 pi k for the whole k that is nearest `reference` (rad); exactly `wrapped` for k = 0.
double continuedAngle(double wrapped, double reference);

// A coordinate at a state: the slide, or the rotation continued from State::jointAngles (rad or m).
double jointCoordinate(const Model& model, const State& state, int jointIndex, JointCoordinate coordinate);
// The coordinate a limit bounds: rotation of a revolute joint, slide of a prismatic one.
double jointCoordinate(const Model& model, const State& state, int jointIndex);
// The coordinate as the model file counts it (a URDF joint's position, rad or m):
// Joint::initialPosition + jointCoordinate, which counts from the initial pose.
double fileCoordinate(const Model& model, const State& state, int jointIndex, JointCoordinate coordinate);

// The rate of a coordinate at a state, dq/dt from its velocity row (rad/s or m/s).
double jointCoordinateVelocity(const Model& model, const State& state, int jointIndex,
                               JointCoordinate coordinate);

// Continues State::jointAngles to the state's pose (once per step, at its end); sizes the vector
// for a state that was not made by initialState.
void trackJointAngles(const Model& model, State& state);

} // namespace frontier::core
