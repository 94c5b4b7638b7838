// run/overrides.cpp: settings given beside a scene over the scene file's own.
#include "run/overrides.h"

#include "io/scene.h"
#include "run/method.h"

#include <cmath>
#include <cstdio>

namespace frontier::run
{

void applySettingOverrides(const SettingOverrides& overrides, core::Model& model)
{
    const auto refuse = [&](const std::string& text) { throw io::InputError(model.sourceFile, 0, 0, text); };
    core::SimulationSettings& sim = model.simulation;
    if (overrides.dt)
    {
        if (!(std::isfinite(*overrides.dt) && *overrides.dt > 0.0 && *overrides.dt <= core::cMaxTimeStep))
        {
            char text[160];
            std::snprintf(text, sizeof text, "dt %.6g s: expected a time step in (0, %g] s", *overrides.dt,
                          core::cMaxTimeStep);
            refuse(text);
        }
        sim.dt = *overrides.dt;
    }
    Method method = Method::of(sim);
    if (overrides.solver)
    {
        const std::optional<core::SolverKind> solver = core::solverFromName(*overrides.solver);
        if (!solver)
        {
            refuse("unknown solver '" + *overrides.solver + "' (expected " +
                   core::nameList(core::solverNames(), "or") + ")");
        }
        method.solver = *solver;
    }
    if (overrides.pgsIterations)
    {
        if (*overrides.pgsIterations < 1 || *overrides.pgsIterations > cMaxPgsIterations)
        {
            refuse("pgs iterations " + std::to_string(*overrides.pgsIterations) + ": expected 1 to " +
                   std::to_string(cMaxPgsIterations));
        }
        method.pgsIterations = *overrides.pgsIterations;
    }
    if (overrides.integrator)
    {
        const std::optional<core::IntegratorKind> integrator =
            core::integratorFromName(*overrides.integrator);
        if (!integrator)
        {
            refuse("unknown integrator '" + *overrides.integrator + "' (expected " +
                   core::nameList(core::integratorNames(), "or") + ")");
        }
        method.integrator = *integrator;
    }
    method.applyTo(sim);
    overrides.contact.applyTo(model.contact);
}

} // namespace frontier::run
