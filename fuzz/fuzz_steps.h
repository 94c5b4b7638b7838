// fuzz/fuzz_steps.h: a loaded model stepped as `frontier run` steps it, for the fuzz targets that
// go past the readers. The errors a run reports cleanly are not findings: core::SimulationError (a
// blow-up naming the step, body and quantity), core::SingularJointError and
// core::UnsupportedModelError (exit 2). Anything else escaping, a crash or a sanitizer report is.
#pragma once

#include "core/impulse_solver.h"
#include "core/model.h"
#include "core/simulation_error.h"
#include "run/simulation.h"

namespace frontier::fuzz
{

inline void stepModel(const core::Model& model, long steps)
{
    try
    {
        run::Simulation simulation(model);
        simulation.step(steps);
    }
    catch (const core::SimulationError&)
    {
    }
    catch (const core::SingularJointError&)
    {
    }
    catch (const core::UnsupportedModelError&)
    {
    }
}

} // namespace frontier::fuzz
