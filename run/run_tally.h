// run/run_tally.h: the figures of a run (RunSummary) gathered state by state: by the run loop
// (runSimulation) and by a loop of a library user's own (the Python module's recording).
#pragma once

#include "run/actuator_efforts.h"
#include "run/run_loop.h"

#include <memory>
#include <vector>

namespace frontier::run
{

class RunTally
{
  public:
    // From the initial state, before any step (energies, joint errors).
    RunTally(const core::Model& model, core::Simulator& simulator, const core::State& state);
    ~RunTally();
    RunTally(const RunTally&) = delete;
    RunTally& operator=(const RunTally&) = delete;

    // After each step: `state` the state it ended in, `simulator` the one that took it.
    void addStep(const core::Simulator& simulator, const core::State& state);
    // The run stopped early: a signal (`text` says when), a singular joint, a blow-up (the failing
    // step's contacts and joint errors still count).
    void interrupt(int signal, const std::string& text);
    void fail(const core::SingularJointError& error);
    void fail(const core::SimulationError& error, const core::Simulator& simulator);

    // The summary at the run's last state, `wallSeconds` (s) the time its steps took.
    RunSummary finish(const core::State& state, double wallSeconds) const;

  private:
    class ActuatorTally;
    const core::Model& mModel;
    RunSummary mSummary;
    std::unique_ptr<ActuatorTally> mActuators;
    std::vector<CoordinateEffort> mEfforts; // scratch
};

} // namespace frontier::run
