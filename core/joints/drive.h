// core/joints/drive.h: drive rows, the forces a joint applies along its own coordinates (viscous
// damping, and the position servos and velocity motors of core/actuation.h), as rows of the same
// impulse problem.
//
// A drive row acts on one coordinate q of a joint (core/joints/coordinates.h) through the row J of
// dq/dt between the joint's two bodies, and is compliant:
//     J u + E lambda = c      lambda: the row's impulse (N s or N m s), E >= 0: its compliance,
//                             c: a velocity target (m/s or rad/s)
// Being between the same two bodies as the joint, it sits in the joint's block of the tree
// factorization, after the condition rows: eliminating the block's child node leaves the pivot
// -D = J D_child^-1 J^T + diag(0, E), which stays positive definite (docs/method.md §3, "Pivots"), so the
// solve stays exact and O(n). In KKT form the row's diagonal entry is -E. A loop-closing joint
// takes its drive rows into its loop block (ExtraBlock::compliance).
//
// A spring-damper of stiffness k and damping d over a solve of duration h, implicit (backward
// Euler: the spring at the end of the solve, q + h J u'), with a force f0 = d_a v* - k (q - q*)
// (targets q*, v*; d_a the part of d that damps towards v*):
//     lambda = h (f0 - (h k + d) J u')   <=>   E = 1 / (h (h k + d)),  c = f0 / (h k + d).
// Viscous damping alone is k = 0, f0 = 0: a body spinning at w_n on a damped hinge leaves the step
// at w_n / (1 + d h / I). Stable for any k, d and h. A rigid row (a velocity motor without damping
// gain) is E = 0, c = v*. Joint damping and an actuator on one coordinate share its row (their k
// and d add), so a block never exceeds 6 rows; the right-hand side c is the actuator's
// (core::Actuation), the projections (drift correction, penetration) give drive rows c = 0.
// Over no time (h = 0: an instantaneous collision, as tests/support/collision_response.h computes one) a
// drive gives no impulse. E is then infinite; the row is written divided by E (J = 0, E = 1, c = 0), its
// limit as E grows, so lambda = 0 exactly and the block keeps its size. A row with k = d = 0 is the same.
//
// A row whose impulse is bounded, |lambda| <= b, is one-sided like a contact (Coulomb joint friction:
// b = f h, target 0; an actuator at its effort limit: b = limit h): it is an extra row
// (ExtraBlock::Kind::Drive, core/extra_rows.h), solved with contacts and limits on top of the
// factorization.
#pragma once

#include "core/joints/joint_rows.h"

#include <array>
#include <cstdint>
#include <vector>

namespace frontier::core
{

// The spring and damper of one coordinate's drive row in a solve.
struct DriveGains
{
    double stiffness = 0.0; // k (N m/rad or N/m)
    double damping = 0.0;   // d (N m s/rad or N s/m)
    bool rigid = false;     // J u = c exactly (E = 0)
};
// Per coordinate of a joint, in jointCoordinates order.
using JointDriveGains = std::array<DriveGains, 2>;

// E and c of a drive row over a solve of duration h (s) with force f0 (N or N m) and, for a rigid
// row, its speed; inactive: E infinite (no time, or k = d = 0), the row gives no impulse.
struct DriveRow
{
    double compliance = 0.0; // E
    double target = 0.0;     // c (m/s or rad/s)
    bool active = false;
};
DriveRow driveRow(const DriveGains& gains, double h, double force, double rigidSpeed = 0.0);

// The gains of a joint's damping alone.
JointDriveGains dampingGains(const Joint& joint);

// Per joint: 1 when a position or velocity actuator drives one of its coordinates (such an
// actuator sits in the joint's block below its effort limit; core/actuation.h).
std::vector<std::uint8_t> actuatedJoints(const Model& model);

// Compliant drive rows in a joint's block: one per coordinate of a joint with damping or an
// actuator in its block, else none.
int blockDriveRows(const Joint& joint, bool actuated = false);

// Rows of a joint's block: its conditions (jointRowCount), then its drive rows; at most 6.
int jointBlockRows(const Joint& joint, bool actuated = false);

// Appends the joint's drive rows to `out`, which evaluateJoint filled at the pose of g, for a solve
// of duration h (s), with the gains of each coordinate. parentMoves as for evaluateJoint. A joint
// with no drive rows in its block (blockDriveRows) gets none.
// `Rows`: JointRows or JointRowsSlot.
template <class Rows>
void writeDriveRows(const Joint& joint, int driveRows, const JointDriveGains& gains,
                    const detail::JointGeometry& g, bool parentMoves, double h, Rows& out);

} // namespace frontier::core
