// core/steppers/rattle4_stepper.cpp: one step of the fourth-order scheme
// (core/steppers/rattle4_stepper.h).
#include "core/steppers/rattle4_stepper.h"

#include "core/joints/drive.h"

#include <cmath>
#include <utility>

namespace frontier::core
{

std::unique_ptr<Stepper> makeRattle4Stepper(StepStages& stages)
{
    // The triple jump (docs/method.md §11): c1 + c2 + c1 = 1.
    const TripleJump jump = tripleJumpCoefficients();
    return std::make_unique<ComposedRattleStepper>(stages, std::vector<double>{jump.c1, jump.c2, jump.c1});
}

ComposedRattleStepper::ComposedRattleStepper(StepStages& stages, std::vector<double> coefficients)
    : mStages(stages), mRattle(stages), mCoefficients(std::move(coefficients))
{
    const Model& model = stages.context().model;
    const std::vector<std::uint8_t> actuated = actuatedJoints(model);
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        mHasBlockDrives = mHasBlockDrives || blockDriveRows(model.joints[k], actuated[k] != 0) > 0;
    }
}

void ComposedRattleStepper::step(State& state)
{
    mStages.beginStep(StepScheme::Rattle); // the drive step stays the last stage's
    mStages.saveRestart(state);
    mStages.forgetEndRows(); // the rattle projection swaps rowsAfter away
    if (takeStages(state))
    {
        return;
    }
    // A stage met a contact or a joint limit, or stalled: the step is taken again from its start
    // as one RATTLE step (docs/method.md §11).
    mStages.restart(state);
    StepContext& step = mStages.context();
    step.h = step.dt;
    step.driveStep = 0.5 * step.dt;
    mStages.stats().secondOrderFallback = true;
    mRattle.takeStep(state);
}

// The stages in order, each a whole RATTLE step at its own time. The drives and joint friction of a
// stage act over the positive time |c| h / sum |c|, so they stay dissipative and stable in a
// backward stage.
bool ComposedRattleStepper::takeStages(State& state)
{
    StepContext& step = mStages.context();
    const double start = state.time;
    double total = 0.0; // the sum of |c|
    for (const double c : mCoefficients)
    {
        total += std::abs(c);
    }
    int iterations = 0;
    step.scheme = StepScheme::Rattle4Stage;
    mStages.clearStageImpulses();
    for (std::size_t i = 0; i < mCoefficients.size(); ++i)
    {
        const double c = mCoefficients[i];
        const double driveStep = 0.5 * (std::abs(c) / total) * step.dt;
        if (driveStep != step.driveStep && mHasBlockDrives)
        {
            mStages.forgetFactoredPose(); // the drive rows' compliance depends on the stage's time
        }
        step.h = c * step.dt;
        step.driveStep = driveStep;
        if (mRattle.stage(state, i == 0) != RattleStepper::Outcome::Done)
        {
            step.scheme = StepScheme::Rattle;
            return false;
        }
        iterations += mStages.stats().stabilizationIterations;
        if (i + 1 < mCoefficients.size())
        {
            mStages.keepStageImpulses(); // for the step's report (core/step_report.cpp)
        }
    }
    step.scheme = StepScheme::Rattle;
    mStages.setComposedStep(true);
    mStages.finishComposedStep(state, start);
    mStages.stats().stabilizationIterations = iterations;
    return true;
}

} // namespace frontier::core
