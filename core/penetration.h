// core/penetration.h: what keeps the position projection of overlaps and limit overruns
// (core/step/penetration_projection.h) bounded.
//
// The projection displaces bodies by d = H^-1 J_x^T mu (through the joints, mu >= 0) so that the
// predicted overlap of every row goes. Two things can make that displacement huge:
// * a row the joints hold (a body on a vertical hinge sunk into the floor: no motion the hinge
//   allows lifts it). Its Delassus diagonal G_ii = J_i H^-1 J_i^T is then round-off, even
//   negative, so mu = overlap / G_ii is anything. Such a row is compared with what it would be
//   for free bodies, J_i M^-1 J_i^T: far below it, the projection leaves the row alone.
// * a deep overlap or limit overrun asks for a large motion in one step, and the projection is
//   linear in the rotation: its joints come apart at second order, its contact points follow
//   arcs instead of lines. Each step's displacement is scaled down to at most a translation and
//   a rotation per body; the rest is removed in the following steps (and the joints' second-order
//   gap is closed by displacement, PenetrationProjection::restoreJoints).
#pragma once

#include "core/free_rotation.h"
#include "core/impulse_solver.h"

#include <vector>

namespace frontier::core
{

// True when the joints hold the block's first row: its Delassus diagonal `delassus` (G_ii) is
// below `ratio` times J M^-1 J^T, the value it would have if its bodies were free (no joints).
// `principal` (per body, moments ascending) gives a cheap upper bound of that,
// |J_v|^2 / m + |J_w|^2 / (least moment), which clears most rows without the exact value.
bool heldByJoints(const ExtraBlock& block, double delassus, const RowSystem& rows,
                  const std::vector<PrincipalAxes>& principal, double ratio);

// Largest factor s in (0, 1] such that s times the displacement (per moving body: translation
// (m), rotation vector (rad)) moves no body by more than maxTranslation (m) and turns none by more
// than maxRotation (rad).
double displacementScale(const Model& model, const BlockVector& displacement, double maxTranslation,
                         double maxRotation);

// Largest rotation (rad) of a moving body in a displacement.
double largestRotation(const Model& model, const BlockVector& displacement);

} // namespace frontier::core
