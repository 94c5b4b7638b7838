// run/run_loop.cpp: the run loop with progress, statistics and recording.
#include "run/run_loop.h"

#include "core/impulse_solver.h"
#include "run/run_tally.h"
#include "run/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <vector>

namespace frontier::run
{

bool isPassive(const core::Model& model)
{
    return model.actuators.empty() && model.loads.empty();
}

double energyScale(const core::Model& model, const core::State& state)
{
    double scale = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            scale += core::bodyEnergyScale(model, i, state.bodies[i]);
        }
    }
    return scale;
}

double passiveEnergyRise(const core::Model& model, const RunSummary& summary)
{
    if (!isPassive(model))
    {
        return 0.0;
    }
    return (summary.energyMaxJ - summary.energyInitialJ) / std::max(summary.energyScaleJ, cEnergyScaleFloorJ);
}

long stepsFor(double duration, double dt)
{
    return static_cast<long>(std::llround(duration / dt));
}

RunSummary runSimulation(const core::Model& model, const RunSettings& settings, const Recorder& record)
{
    Simulation simulation(model);
    core::Simulator& simulator = simulation.simulator();
    core::State& state = simulation.state();
    RunTally tally(model, simulator, state);
    if (record)
    {
        record(state, nullptr);
    }
    const auto start = std::chrono::steady_clock::now();
    try
    {
        for (long k = 0; k < settings.steps; ++k)
        {
            if (const int signal = interruptSignal(); signal != 0)
            {
                char text[160];
                std::snprintf(text, sizeof text, "interrupted by %s at t = %.9g s (step %ld of %ld)",
                              signalName(signal).c_str(), state.time, k, settings.steps);
                tally.interrupt(signal, text);
                break;
            }
            simulation.step();
            tally.addStep(simulator, state);
            if (record)
            {
                record(state, &simulator);
            }
            if (settings.progress)
            {
                settings.progress(k + 1);
            }
        }
    }
    catch (const core::SingularJointError& error)
    {
        tally.fail(error);
    }
    catch (const core::SimulationError& error)
    {
        tally.fail(error, simulator);
    }
    return tally.finish(state,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

} // namespace frontier::run
