// run/simulation.cpp: the detector, simulator and state of a run.
#include "run/simulation.h"

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
