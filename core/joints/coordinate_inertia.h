// core/joints/coordinate_inertia.h: the inertia a joint coordinate moves (what servo gains are
// chosen from, io's --hold).
//
// With every other joint locked, the bodies on the joint's child side (those its child reaches
// through the other joints without passing its parent, the world or a static body) move as one
// rigid body, the composite rigid body of the subtree. Turning the joint moves it about the joint
// axis k through the anchor p: I = sum_b (k . I_b k + m_b |k x (x_b - p)|^2) (kg m^2); sliding moves
// it along k: I = sum_b m_b (kg). This is the joint's diagonal entry of the joint-space inertia
// matrix of a fixed-base tree (the composite-rigid-body algorithm's diagonal), at the model's
// initial pose.
#pragma once

#include "core/model.h"

namespace frontier::core
{

double coordinateInertia(const Model& model, int jointIndex, JointCoordinate coordinate);

} // namespace frontier::core
