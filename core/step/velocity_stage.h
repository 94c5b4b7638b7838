// core/step/velocity_stage.h: the pieces of a velocity stage (docs/method.md §4): the free
// velocities' gravity kick and the momentum right-hand side of the joint-impulse solve.
#pragma once

#include "core/actuation.h"
#include "core/impulse_solver.h"
#include "core/model.h"
#include "core/state.h"

#include <vector>

namespace frontier::core
{

// v += h g for every moving body (h in s).
void kickByGravity(const Model& model, State& state, double h);

// p = M u* for the joint-impulse solve M u' - J^T lambda = M u*, J u' + E lambda = c, M from
// `rows`: c = 0 but for the rows of servos and motors in their joints' blocks (targets at tEnd,
// s; driveStep the duration of the solve, s).
void setMomentumRhs(const Model& model, const RowSystem& rows, const State& state, double tEnd,
                    double driveStep, const Actuation& actuation, BlockVector& rhs);

// The bodies of `state` are exactly at `pose` (positions and orientations bit for bit).
bool samePose(const Model& model, const State& state, const std::vector<BodyState>& pose);

} // namespace frontier::core
