// core/joints/drive.h: drive rows, the forces a joint applies along its own coordinates (viscous
// damping now), as rows of the same impulse problem.
//
// A drive row acts on one coordinate q of a joint (core/joints/coordinates.h) through the row J of
// dq/dt between the joint's two bodies, and is compliant:
//     J u + E lambda = c      lambda: the row's impulse (N s or N m s), E >= 0: its compliance,
//                             c: a velocity target (m/s or rad/s)
// Being between the same two bodies as the joint, it sits in the joint's block of the tree
// factorization, after the condition rows: eliminating the block's child node leaves the pivot
// -D = J D_child^-1 J^T + diag(0, E), which stays positive definite (PAPER.md §3 "Pivots"), so the
// solve stays exact and O(n). In KKT form the row's diagonal entry is -E. A loop-closing joint
// takes its drive rows into its loop block (ExtraBlock::compliance).
//
// Viscous damping d (N m s/rad or N s/m) over a solve of duration h, implicit (backward Euler):
// lambda = -d h (J u') with u' the velocities the solve gives, i.e. E = 1 / (d h), c = 0. Stable for
// any d and h: a body spinning at w_n on a damped hinge leaves the step at w_n / (1 + d h / I).
// An implicit spring-damper (stiffness k, damping d, targets q*, v*) is the same row with
//     E = 1 / (h (h k + d)),  c = (d v* - k (q_n - q*)) / (h k + d).
// Over no time (h = 0: an instantaneous collision, core::respondToCollision) a drive gives no
// impulse. E is then infinite; the row is written divided by E (J = 0, E = 1, c = 0), its limit as
// E grows, so lambda = 0 exactly and the block keeps its size.
//
// A row whose impulse is bounded, |lambda| <= b, is one-sided like a contact (Coulomb joint friction:
// b = f h, target 0): it is an extra row (ExtraBlock::Kind::Drive, core/extra_rows.h), solved with
// contacts and limits on top of the factorization.
#pragma once

#include "core/joints/joint_rows.h"

namespace frontier::core
{

// Compliant drive rows in a joint's block: one per coordinate of a joint with damping, else none.
int blockDriveRows(const Joint& joint);

// Rows of a joint's block: its conditions (jointRowCount), then its drive rows; at most 6.
int jointBlockRows(const Joint& joint);

// Appends the joint's drive rows to `out`, which evaluateJoint filled at the pose of g, for a solve
// of duration h (s). parentMoves as for evaluateJoint.
void writeDriveRows(const Joint& joint, const detail::JointGeometry& g, bool parentMoves, double h,
                    JointRows& out);

} // namespace frontier::core
