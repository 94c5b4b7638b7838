// core/step/positions.h: the position update of a step (docs/method.md §4) and the moves of
// positions and angular velocities that go with it.
#pragma once

#include "core/free_rotation.h"
#include "core/impulse_solver.h"
#include "core/model.h"
#include "core/state.h"

#include <vector>

namespace frontier::core
{

// x_{n+1} = x_n + h v_{n+1} from the start-of-step pose `start`, h = dt (s). Rotation: euler
// R_{n+1} = exp(h w) R_n; rattle the free rigid-body rotation (core/free_rotation.h) at the world
// angular momentum L = I_W(R_n) w (I_W from `rows`, the start-of-step rows).
void integratePositions(const Model& model, const std::vector<BodyState>& start,
                        const std::vector<PrincipalAxes>& principal, const RowSystem& rows, double dt,
                        bool rattle, State& state);

// Moves the positions of `state` and of the start-of-step pose `start` by a displacement (m, rad)
// without touching velocities.
void displacePositions(const Model& model, const BlockVector& displacement, State& state,
                       std::vector<BodyState>& start);

// The angular momentum I_W(R_n) w that the step gave each body (I_W from `rows`, the start-of-step
// rows) is kept through the rotation: w_{n+1} = I_W(R_{n+1})^-1 I_W(R_n) w.
void carryAngularMomentum(const Model& model, const std::vector<PrincipalAxes>& principal,
                          const RowSystem& rows, State& state);

} // namespace frontier::core
