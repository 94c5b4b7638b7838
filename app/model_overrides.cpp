// app/model_overrides.cpp: flags over scene settings.
#include "app/model_overrides.h"

#include "io/scene.h"
#include "run/overrides.h"
#include "run/run_loop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace frontier::app
{

long checkedStepCount(double duration, double dt, const std::string& source)
{
    const double count = duration / dt;
    if (!(std::isfinite(dt) && dt > 0.0 && std::isfinite(duration) && duration > 0.0 && count <= cMaxSteps))
    {
        char text[200];
        std::snprintf(text, sizeof text,
                      "duration %.6g s at dt %.6g s makes %.6g steps; a run takes 1 to %.0e steps of a "
                      "finite positive dt",
                      duration, dt, count, cMaxSteps);
        throw io::InputError(source, 0, 0, text);
    }
    return std::max(1L, run::stepsFor(duration, dt));
}

long applyOverrides(const RunOptions& options, core::Model& model)
{
    run::applySettingOverrides(
        {options.dt, options.solver, options.pgsIterations, options.integrator, options.contact}, model);
    core::SimulationSettings& sim = model.simulation;
    if (options.steps)
    {
        sim.duration = static_cast<double>(*options.steps) * sim.dt;
        checkedStepCount(sim.duration, sim.dt, model.sourceFile);
        return *options.steps;
    }
    if (options.duration)
    {
        sim.duration = *options.duration;
    }
    return checkedStepCount(sim.duration, sim.dt, model.sourceFile);
}

std::string roundedDurationNote(double duration, long steps, double dt)
{
    const double simulated = static_cast<double>(steps) * dt; // s
    if (std::abs(simulated - duration) <= 1e-9 * std::max(duration, dt))
    {
        return {};
    }
    char text[200];
    std::snprintf(text, sizeof text, "simulating %.9g s instead of %.9g s: %ld whole steps of %.9g s",
                  simulated, duration, steps, dt);
    return text;
}

std::vector<std::string> loadsAfterTheEnd(const core::Model& model, double end)
{
    std::vector<std::string> warnings;
    for (const core::Load& load : model.loads)
    {
        const double start = load.instant.value_or(load.from); // s
        if (start >= end)
        {
            char text[320];
            std::snprintf(
                text, sizeof text,
                "the %s on body '%s' at t = %.9g s never acts: the run ends at %.9g s (give --duration, "
                "or the scene's simulation: {duration: ...})",
                load.instant ? "impulse" : "load",
                model.bodies[static_cast<std::size_t>(load.body)].name.c_str(), start, end);
            warnings.push_back(text);
        }
    }
    return warnings;
}

} // namespace frontier::app
