// core/step/geometric_stiffness.h: the geometric stiffness of joints under large tension
// (docs/method.md §7a).
//
// A light body held between joints that pull on it with a force F turns stiffly: turning it by dθ
// swings each anchor (lever arm ρ) against F, a restoring torque of about (F . ρ) dθ per joint. The
// first-order step takes the joints' directions at the start of the step, so that stiffness acts
// explicitly, and once h^2 k / I is large (a 1 g link under a 1 000 kg load at dt = 1 ms: about
// 1e4) the body's sideways mode grows from step to step and the chain comes apart. A body past
// cStiffRatio gets h^2 k = h sum (Λ . ρ) (Λ its joints' linear impulses, N s) added to each diagonal
// entry of its rotational inertia in the step's factorization: the implicit (backward Euler)
// treatment of that stiffness, which damps the mode instead of letting it grow. Bodies below it,
// the whole of most scenes, step exactly as without it.
#pragma once

#include "core/impulse_solver.h"

#include <vector>

namespace frontier::core
{

// h^2 k / I of a body (k = the sum of F . ρ over its joints' tensile ends, I the mean of its
// principal moments) from which its geometric stiffness joins the step: where the explicit step
// nears its limit, so that scenes that hold without it step as they did.
inline constexpr double cStiffRatio = 8.0;
// A load falls to this fraction of itself per step unless a larger one replaces it: a body
// stiffened by a tension stays so while the tension lasts, instead of every other step (its
// stiffened step carries a smaller impulse, which alone would switch it off again).
inline constexpr double cLoadDecay = 0.9;

// Per joint k, the tension moments Λ . ρ (N s m; 0 where the joint pushes) at its parent's end
// (loads[2k]) and its child's (loads[2k + 1]): Λ the linear impulse its condition rows gave that
// body in the solve `solution` of `rows`, ρ the anchor's lever arm. Each is the larger of that and
// cLoadDecay times the value `loads` held (the last step's).
void measureJointLoads(const Model& model, const RowSystem& rows, const BlockVector& solution,
                       std::vector<double>& loads);

// h^2 k of every body for a step of dt (s), eq. (11c): h sum (Λ . ρ) over its joints' ends (kg m^2;
// zeros when `loads` is empty).
void geometricInertias(const Model& model, const std::vector<double>& loads, double dt,
                       LargeVector<double>& out);

// Sets rows.geometricInertia for a step of dt (s) from the joints' loads (measureJointLoads; empty:
// none): h sum (Λ . ρ) (kg m^2) on the bodies past cStiffRatio, left empty when there are none.
// Returns how many bodies it stiffened.
int stiffenLoadedBodies(const Model& model, const std::vector<double>& loads, double dt, RowSystem& rows);

} // namespace frontier::core
