// app/run_loop.cpp: the run loop with progress, statistics and recording.
#include "app/run_loop.h"

#include "app/actuator_efforts.h"
#include "collision/contacts.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace frontier::app
{

long stepsFor(double duration, double dt)
{
    return static_cast<long>(std::llround(duration / dt));
}

RunSummary runSimulation(const core::Model& model, const RunSettings& settings, const Recorder& record)
{
    RunSummary summary;
    collision::ContactDetector detector(model,
                                        collision::contactMargin(core::longestStage(model.simulation)));
    core::Simulator simulator(model, {}, &detector);
    core::State state = core::initialState(model);
    summary.energyInitialJ = core::totalEnergy(model, state);
    summary.energyMaxJ = summary.energyInitialJ;
    summary.energyMinJ = summary.energyInitialJ;
    const auto [errorM, errorRad] = simulator.jointErrors(state);
    summary.maxJointErrorM = errorM;
    summary.maxJointErrorRad = errorRad;
    if (record)
    {
        record(state, nullptr);
    }
    std::vector<CoordinateEffort> efforts;
    const auto start = std::chrono::steady_clock::now();
    try
    {
        for (long k = 0; k < settings.steps; ++k)
        {
            simulator.step(state);
            const core::StepStats& stats = simulator.lastStep();
            summary.maxJointErrorM = std::max(summary.maxJointErrorM, stats.maxJointErrorM);
            summary.maxJointErrorRad = std::max(summary.maxJointErrorRad, stats.maxJointErrorRad);
            summary.maxPenetrationM = std::max(summary.maxPenetrationM, stats.maxPenetrationM);
            summary.maxContacts = std::max(summary.maxContacts, stats.contacts);
            summary.firstOrderSteps += stats.firstOrderFallback ? 1 : 0;
            ++summary.contactRoutes[core::routeIndex(stats.contactRoute)];
            summary.contactSweeps += stats.contactSweeps;
            summary.limitSteps += simulator.pushingLimitRows() > 0 ? 1 : 0;
            lastActuatorEfforts(model, simulator, efforts);
            bool atLimit = false;
            for (const CoordinateEffort& e : efforts)
            {
                summary.maxActuatorEffort = std::max(summary.maxActuatorEffort, std::abs(e.effort));
                atLimit = atLimit || e.atLimit;
            }
            summary.actuatorLimitSteps += atLimit ? 1 : 0;
            for (std::size_t stage = 0; stage < core::cStepStages; ++stage)
            {
                summary.stageSeconds[stage] += stats.seconds[stage];
            }
            const double energy = core::totalEnergy(model, state);
            summary.energyMaxJ = std::max(summary.energyMaxJ, energy);
            summary.energyMinJ = std::min(summary.energyMinJ, energy);
            summary.steps = k + 1;
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
    catch (const core::SimulationError& error)
    {
        summary.finite = false;
        summary.failure = error.what();
        summary.failureDetails = error.failure();
        // The failing step detected its contacts before it failed: a run that fails at step 0
        // still reports the overlap it started with.
        summary.maxPenetrationM = std::max(summary.maxPenetrationM, simulator.lastStep().maxPenetrationM);
        summary.maxContacts = std::max(summary.maxContacts, simulator.lastStep().contacts);
    }
    summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.energyFinalJ = core::totalEnergy(model, state);
    return summary;
}

} // namespace frontier::app
