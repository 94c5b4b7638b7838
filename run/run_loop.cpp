// run/run_loop.cpp: the run loop with progress, statistics and recording.
#include "run/run_loop.h"

#include "core/impulse_solver.h"
#include "run/actuator_efforts.h"
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

namespace
{
// Sums of the actuators' figures over the steps, made into ActuatorSummary at the end of the run.
class ActuatorTally
{
  public:
    explicit ActuatorTally(const core::Model& model)
        : mModel(model), mTrackingSquares(model.actuators.size(), 0.0),
          mEffortSquares(model.actuators.size(), 0.0), mSummaries(model.actuators.size())
    {
    }

    // One step: `efforts` from lastActuatorEfforts, `state` the state it ended in.
    void add(const core::State& state, std::span<const CoordinateEffort> efforts)
    {
        for (std::size_t a = 0; a < efforts.size() && a < mSummaries.size(); ++a)
        {
            ActuatorSummary& s = mSummaries[a];
            const double tracking = trackingError(mModel, state, a);
            mTrackingSquares[a] += tracking * tracking;
            s.trackingMax = std::max(s.trackingMax, std::abs(tracking));
            mEffortSquares[a] += efforts[a].effort * efforts[a].effort;
            s.effortMax = std::max(s.effortMax, std::abs(efforts[a].effort));
            s.limitSteps += efforts[a].atLimit ? 1 : 0;
        }
        ++mSteps;
    }

    std::vector<ActuatorSummary> finish() const
    {
        std::vector<ActuatorSummary> out = mSummaries;
        const double n = static_cast<double>(std::max(1L, mSteps));
        for (std::size_t a = 0; a < out.size(); ++a)
        {
            out[a].trackingRms = std::sqrt(mTrackingSquares[a] / n);
            out[a].effortRms = std::sqrt(mEffortSquares[a] / n);
            if (mModel.actuators[a].kind == core::ActuatorKind::Effort)
            {
                out[a].trackingRms = out[a].trackingMax = std::numeric_limits<double>::quiet_NaN();
            }
        }
        return out;
    }

  private:
    const core::Model& mModel;
    std::vector<double> mTrackingSquares; // rad^2 or m^2 (per s^2 for a velocity motor)
    std::vector<double> mEffortSquares;   // N^2 or N^2 m^2
    std::vector<ActuatorSummary> mSummaries;
    long mSteps = 0;
};
} // namespace

long stepsFor(double duration, double dt)
{
    return static_cast<long>(std::llround(duration / dt));
}

RunSummary runSimulation(const core::Model& model, const RunSettings& settings, const Recorder& record)
{
    RunSummary summary;
    Simulation simulation(model);
    core::Simulator& simulator = simulation.simulator();
    core::State& state = simulation.state();
    summary.energyInitialJ = core::totalEnergy(model, state);
    summary.energyMaxJ = summary.energyInitialJ;
    summary.energyMinJ = summary.energyInitialJ;
    summary.energyScaleJ = energyScale(model, state);
    const auto [errorM, errorRad] = simulator.jointErrors(state);
    summary.maxJointErrorM = errorM;
    summary.maxJointErrorRad = errorRad;
    if (record)
    {
        record(state, nullptr);
    }
    std::vector<CoordinateEffort> efforts;
    ActuatorTally actuators(model);
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
                summary.completed = false;
                summary.interruptedBy = signal;
                summary.failure = text;
                break;
            }
            simulation.step();
            const core::StepStats& stats = simulator.lastStep();
            summary.maxJointErrorM = std::max(summary.maxJointErrorM, stats.maxJointErrorM);
            summary.maxJointErrorRad = std::max(summary.maxJointErrorRad, stats.maxJointErrorRad);
            summary.maxPenetrationM = std::max(summary.maxPenetrationM, stats.maxPenetrationM);
            summary.maxContacts = std::max(summary.maxContacts, stats.contacts);
            summary.firstOrderSteps += stats.firstOrderFallback ? 1 : 0;
            summary.secondOrderSteps += stats.secondOrderFallback ? 1 : 0;
            ++summary.contactRoutes[core::routeIndex(stats.contactRoute)];
            summary.contactSweeps += stats.contactSweeps;
            summary.limitSteps += simulator.pushingLimitRows() > 0 ? 1 : 0;
            summary.stiffenedSteps += stats.stiffenedBodies > 0 ? 1 : 0;
            lastActuatorEfforts(model, simulator, efforts);
            actuators.add(state, efforts);
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
    catch (const core::SingularJointError& error)
    {
        summary.completed = false;
        summary.failure = error.what();
    }
    catch (const core::SimulationError& error)
    {
        summary.finite = false;
        summary.completed = false;
        summary.failure = error.what();
        summary.failureDetails = error.failure();
        // The failing step detected its contacts before it failed: a run that fails at step 0
        // still reports the overlap it started with; a joint that came apart reports its gap.
        const core::StepStats& failed = simulator.lastStep();
        summary.maxPenetrationM = std::max(summary.maxPenetrationM, failed.maxPenetrationM);
        summary.maxContacts = std::max(summary.maxContacts, failed.contacts);
        summary.maxJointErrorM = std::max(summary.maxJointErrorM, failed.maxJointErrorM);
        summary.maxJointErrorRad = std::max(summary.maxJointErrorRad, failed.maxJointErrorRad);
    }
    summary.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.energyFinalJ = core::totalEnergy(model, state);
    summary.actuators = actuators.finish();
    return summary;
}

} // namespace frontier::run
