// core/step/positions.h: the position update of a step (docs/method.md §4) and the moves of
// positions and angular velocities that go with it.
#pragma once

#include "core/free_rotation.h"
#include "core/impulse_solver.h"
#include "core/model.h"
#include "core/state.h"

#include <cstdint>
#include <vector>

namespace frontier::core
{

// Which rotation update each body takes this step (docs/method.md §4, eq. (8a)), from the
// velocities of `state` after the step's impulses: freeRotation[i] = 1 for the free rigid-body
// rotation (core/free_rotation.h) at the world angular momentum L = I_W(R_n) w (I_W from `rows`,
// the start-of-step rows), always for rattle, and for euler when L turns relative to the body by
// more than a microradian in the step, h |w x L| > 1e-6 |L| (h = dt, s), unless a joint holds the
// body's rotation (core::holdsRotation) and it turns by more than a quarter radian, h |w| > 0.25;
// 0 for R_{n+1} = exp(h w) R_n, which holds w fixed in the body and is exact when w x L = 0 (a
// spin about a principal axis).
// Chosen once a step, so that the drift correction's iterations move every body by one map.
// heldInRotation: bodiesHeldInRotation(model).
void chooseRotationUpdates(const Model& model, const std::vector<std::uint8_t>& heldInRotation,
                           const RowSystem& rows, const State& state, double dt, bool rattle,
                           std::vector<std::uint8_t>& freeRotation);

// Per body, 1 when one of its joints holds (some of) its rotation relative to another body or the
// world (core::holdsRotation), else 0: fixed by the model, computed once.
std::vector<std::uint8_t> bodiesHeldInRotation(const Model& model);

// x_{n+1} = x_n + h v_{n+1} from the start-of-step pose `start`, h = dt (s); each rotation by the
// update chooseRotationUpdates() chose, at L = I_W(R_n) w (I_W from `rows`).
void integratePositions(const Model& model, const std::vector<BodyState>& start,
                        const std::vector<PrincipalAxes>& principal, const RowSystem& rows,
                        const std::vector<std::uint8_t>& freeRotation, double dt, State& state);

// Moves the positions of `state` and of the start-of-step pose `start` by a displacement (m, rad)
// without touching velocities.
void displacePositions(const Model& model, const BlockVector& displacement, State& state,
                       std::vector<BodyState>& start);

// The angular momentum I_W(R_n) w that the step gave each body (I_W from `rows`, the start-of-step
// rows) is kept through the rotation: w_{n+1} = I_W(R_{n+1})^-1 I_W(R_n) w.
void carryAngularMomentum(const Model& model, const std::vector<PrincipalAxes>& principal,
                          const RowSystem& rows, State& state);

} // namespace frontier::core
