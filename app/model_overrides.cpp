// app/model_overrides.cpp: flags over scene settings.
#include "app/model_overrides.h"

#include "app/method.h"
#include "app/run_loop.h"

namespace frontier::app
{

long applyOverrides(const RunOptions& options, core::Model& model)
{
    core::SimulationSettings& sim = model.simulation;
    if (options.dt)
    {
        sim.dt = *options.dt;
    }
    Method method = Method::of(sim);
    if (options.solver)
    {
        method.solver = *core::solverFromName(*options.solver);
    }
    if (options.pgsIterations)
    {
        method.pgsIterations = *options.pgsIterations;
    }
    if (options.integrator)
    {
        method.integrator = *core::integratorFromName(*options.integrator);
    }
    method.applyTo(sim);
    if (options.steps)
    {
        sim.duration = static_cast<double>(*options.steps) * sim.dt;
        return *options.steps;
    }
    if (options.duration)
    {
        sim.duration = *options.duration;
    }
    return std::max(1L, stepsFor(sim.duration, sim.dt));
}

} // namespace frontier::app
