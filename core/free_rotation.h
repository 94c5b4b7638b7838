// core/free_rotation.h: the rotation of a free rigid body over a time step at constant world
// angular momentum, for the second-order (`rattle`) integrator's drift.
#pragma once

#include "core/model.h"

namespace frontier::core
{

// A body's principal axes: inertia_B = R_BP diag(moments) R_BP^T.
struct PrincipalAxes
{
    Quat rotation_BP = Quat::Identity(); // principal frame to body frame
    Vec3 moments = Vec3::Ones();         // kg m^2, ascending
};

PrincipalAxes principalAxes(const Mat3& inertia_B);

// Orientation after a time h (s) of torque-free motion with world angular momentum L_W (N m s),
// by the symmetric splitting of the rotational kinetic energy over the principal axes
// (Dullweber, Leimkuhler and McLachlan 1997): rotations about axis 1 for h/2, axis 2 for h/2,
// axis 3 for h, axis 2 for h/2, axis 1 for h/2, each exact. The map is symplectic, time-reversible
// and second order, keeps L_W exactly and the orientation a unit quaternion (a Lie-group update).
Quat rotateFreely(const Quat& orientation_WB, const PrincipalAxes& axes, const Vec3& angularMomentum_W,
                  double h);

} // namespace frontier::core
