// run/run_tally.cpp: a run's figures gathered state by state.
#include "run/run_tally.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace frontier::run
{

// Sums of the actuators' figures over the steps, made into ActuatorSummary at the end of the run.
class RunTally::ActuatorTally
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

RunTally::RunTally(const core::Model& model, core::Simulator& simulator, const core::State& state)
    : mModel(model), mActuators(std::make_unique<ActuatorTally>(model))
{
    mSummary.energyInitialJ = core::totalEnergy(model, state);
    mSummary.energyMaxJ = mSummary.energyInitialJ;
    mSummary.energyMinJ = mSummary.energyInitialJ;
    mSummary.energyScaleJ = energyScale(model, state);
    const auto [errorM, errorRad] = simulator.jointErrors(state);
    mSummary.maxJointErrorM = errorM;
    mSummary.maxJointErrorRad = errorRad;
}

RunTally::~RunTally() = default;

void RunTally::addStep(const core::Simulator& simulator, const core::State& state)
{
    RunSummary& summary = mSummary;
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
    lastActuatorEfforts(mModel, simulator, mEfforts);
    mActuators->add(state, mEfforts);
    bool atLimit = false;
    for (const CoordinateEffort& e : mEfforts)
    {
        summary.maxActuatorEffort = std::max(summary.maxActuatorEffort, std::abs(e.effort));
        atLimit = atLimit || e.atLimit;
    }
    summary.actuatorLimitSteps += atLimit ? 1 : 0;
    for (std::size_t stage = 0; stage < core::cStepStages; ++stage)
    {
        summary.stageSeconds[stage] += stats.seconds[stage];
    }
    const double energy = core::totalEnergy(mModel, state);
    summary.energyMaxJ = std::max(summary.energyMaxJ, energy);
    summary.energyMinJ = std::min(summary.energyMinJ, energy);
    ++summary.steps;
}

void RunTally::interrupt(int signal, const std::string& text)
{
    mSummary.completed = false;
    mSummary.interruptedBy = signal;
    mSummary.failure = text;
}

void RunTally::fail(const core::SingularJointError& error)
{
    mSummary.completed = false;
    mSummary.failure = error.what();
}

void RunTally::fail(const core::SimulationError& error, const core::Simulator& simulator)
{
    RunSummary& summary = mSummary;
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

RunSummary RunTally::finish(const core::State& state, double wallSeconds) const
{
    RunSummary summary = mSummary;
    summary.wallSeconds = wallSeconds;
    summary.energyFinalJ = core::totalEnergy(mModel, state);
    summary.actuators = mActuators->finish();
    return summary;
}

} // namespace frontier::run
