// run/simulation.h: a loaded model ready to step exactly as `frontier run` steps it: the contact
// detector with the run's margin and step time, the simulator, and the state.
#pragma once

#include "collision/contacts.h"
#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"

namespace frontier::run
{

// Steps a model from its initial state. Keeps a reference to the model, which must outlive it
// and not change while it steps; between steps its gravity (Model::simulation.gravity) may change,
// which the next step follows (nothing reads it ahead). Two Simulations of one model and one
// sequence of calls give bit-identical states.
class Simulation
{
  public:
    explicit Simulation(const core::Model& model, const core::StepOptions& options = {});

    // Where a rollout stands: the state and what the simulator carries from step to step
    // (core/step_memory.h). Not the model (gravity as it is when stepping) nor the detector,
    // whose history only skips work it proves has the same outcome.
    struct Snapshot
    {
        core::State state;
        core::StepMemory memory;
    };
    // The steps after restore(snapshot()) are bit-identical to those after snapshot(), here or in
    // another Simulation of the same model (a copy of vectors: microseconds). restore throws
    // std::invalid_argument for a snapshot of a model with other numbers of bodies, joints or
    // actuators, and then changes nothing.
    Snapshot snapshot() const;
    void restore(const Snapshot& snapshot);

    // One step of the model's dt (s), or `steps` of them. Throw core::SimulationError (a blow-up,
    // naming the step, body and quantity) and core::SingularJointError.
    void step();
    void step(long steps);

    double time() const { return mState.time; } // s
    const core::Model& model() const { return mModel; }
    const core::State& state() const { return mState; }
    core::State& state() { return mState; }
    core::Simulator& simulator() { return mSimulator; }
    const core::Simulator& simulator() const { return mSimulator; }
    collision::ContactDetector& detector() { return mDetector; }

  private:
    const core::Model& mModel;
    collision::ContactDetector mDetector;
    core::Simulator mSimulator;
    core::State mState;
};

} // namespace frontier::run
