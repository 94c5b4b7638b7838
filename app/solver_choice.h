// app/solver_choice.h: a solver named on the command line, `linear`, `dense`, `pgs` or `pgs:K`
// (K Gauss-Seidel sweeps), shared by `frontier sweep` and `frontier stability`.
#pragma once

#include "core/model.h"

#include <optional>
#include <string>

namespace frontier::app
{

inline constexpr int cMaxPgsIterations = 1000000;

struct SolverChoice
{
    core::SolverKind solver = core::SolverKind::Linear;
    int pgsIterations = 20; // sweeps of pgs (ignored by the other solvers)
};

// nullopt for anything but linear, dense, pgs (with defaultPgsIterations) or pgs:K,
// 1 <= K <= cMaxPgsIterations.
std::optional<SolverChoice> parseSolverChoice(const std::string& entry, int defaultPgsIterations);

} // namespace frontier::app
