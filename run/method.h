// run/method.h: a simulation method, the integrator with the solver and its options, as `frontier
// run`, `check`, `sweep` and `stability` name it. Printed one way, `solver[:K]/integrator`
// (`linear/euler`, `pgs:100/rattle`, `pgs:20/rattle4`; K = pgs sweeps, written for pgs only).
#pragma once

#include "core/model.h"

#include <optional>
#include <string>

namespace frontier::run
{

inline constexpr int cMaxPgsIterations = 1000000;

struct Method
{
    core::SolverKind solver = core::SolverKind::Linear;
    int pgsIterations = 20; // sweeps of pgs (ignored by the other solvers)
    core::IntegratorKind integrator = core::IntegratorKind::Euler;

    // "pgs:20/euler", "linear/rattle".
    std::string label() const;
    // The solver part of the label: "linear", "dense", "pgs:20".
    std::string solverLabel() const;
    // The same solver with the same options (pgs sweeps count for pgs only).
    bool sameSolver(const Method& other) const;

    static Method of(const core::SimulationSettings& settings);
    void applyTo(core::SimulationSettings& settings) const;
};

// Reads `solver[:K][/integrator]` (`dense` = `dense/euler`, `pgs` = `pgs:defaultPgsIterations`)
// and the sweep tables' `integrator solver[:K]` (`euler pgs:20`). nullopt for anything else:
// solver linear, dense or pgs, K a whole number 1 <= K <= cMaxPgsIterations and only for pgs,
// integrator euler, rattle or rattle4. hasIntegrator (when given) says whether the text named one.
std::optional<Method> parseMethod(const std::string& text, int defaultPgsIterations = 20,
                                  bool* hasIntegrator = nullptr);

} // namespace frontier::run
