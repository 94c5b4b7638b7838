// run/simulation.cpp: the detector, simulator and state of a run.
#include "run/simulation.h"

#include <stdexcept>
#include <string>

namespace frontier::run
{

// The detector's margin covers the longest stage of a step (rattle4's middle stage runs 1.70 dt),
// and it sweeps bodies that move far in one (docs/method.md §10).
Simulation::Simulation(const core::Model& model, const core::StepOptions& options)
    : mModel(model), mDetector(model, collision::contactMargin(core::longestStage(model.simulation))),
      mSimulator(model, options, &mDetector), mState(core::initialState(model))
{
    mDetector.setStepTime(core::longestStage(model.simulation));
}

Simulation::Snapshot Simulation::snapshot() const
{
    return {mState, mSimulator.memory()};
}

void Simulation::restore(const Snapshot& snapshot)
{
    const core::State& state = snapshot.state;
    if (state.bodies.size() != mModel.bodies.size() || state.jointAngles.size() != mModel.joints.size())
    {
        throw std::invalid_argument(
            "a snapshot of a model of " + std::to_string(state.bodies.size()) + " bodies and " +
            std::to_string(state.jointAngles.size()) + " joints does not fit this one of " +
            std::to_string(mModel.bodies.size()) + " and " + std::to_string(mModel.joints.size()));
    }
    mSimulator.restoreMemory(snapshot.memory); // checks the model's size before it changes anything
    mState = state;
}

void Simulation::step()
{
    mSimulator.step(mState);
}

void Simulation::step(long steps)
{
    for (long k = 0; k < steps; ++k)
    {
        mSimulator.step(mState);
    }
}

} // namespace frontier::run
