// io/hold_servos.h: `--hold` (and a model's `hold: true`): servos that hold a robot where it starts
// (private to io/).
//
// Every coordinate of the robot's joints that has no actuator of the scene's gets a position servo
// whose target is its starting position (Joint::initialPosition in the file's convention). Gains:
// a critically damped servo of natural frequency cHoldFrequency on the inertia the coordinate
// moves, I (core::coordinateInertia: the composite rigid body of the joint's child side at the
// start pose, the joint-space inertia's diagonal), kp = I w^2, kd = 2 I w; but at least so stiff
// that it reaches the joint's effort limit (URDF <limit effort>) at an error of cHoldError, kp =
// limit / cHoldError, with kd = 2 sqrt(kp I) (still critically damped on I). The coordinate's
// inertia alone underrates a leg that carries the robot's weight; the effort limit says how hard
// the joint may push, and the servo pushes that hard before it gives way by cHoldError. The
// servo's effort is bounded by that limit (a joint without one has none).
#pragma once

#include "core/model.h"

namespace frontier::io::detail
{

inline constexpr double cHoldFrequency = 10.0; // Hz
inline constexpr double cHoldError = 0.05;     // rad or m: where a servo reaches its effort limit

// Joints [firstJoint, endJoint) of `model`.
void addHoldServos(core::Model& model, int firstJoint, int endJoint);

} // namespace frontier::io::detail
