// core/steppers/rattle_stepper.h: the second-order scheme (`rattle`), RATTLE on the bodies'
// positions and rotations. Its pipeline (core/steppers/rattle_stepper.cpp):
//   checkState -> detectContacts                                                       [Detect]
//   -> computeFreeVelocities (h/2) -> factorAtStart                                    [Factor]
//   -> buildExtraRows -> setMomentumRhs -> carryImpulses -> solve -> solveContactImpulses [Solve]
//      (factorAtStart .. solveContactImpulses again while an actuator went past its effort limit)
//   -> integratePositions -> removePenetration -> stabilizeJoints (stalled: the step is taken
//      again by euler) -> carryAngularMomentum -> kickByGravity (h/2) -> applyForces (h/2)
//   -> projectVelocities -> finishStep                                                 [Integrate]
// The physics of each stage: core/simulator.h and docs/method.md.
#pragma once

#include "core/step/step_stages.h"
#include "core/steppers/euler_stepper.h"
#include "core/steppers/stepper.h"

namespace frontier::core
{

class RattleStepper final : public Stepper
{
  public:
    explicit RattleStepper(StepStages& stages) : mStages(stages), mEuler(stages) {}
    void step(State& state) override;

    // A RATTLE step begun from the state StepStages::saveRestart kept: taken again by euler when
    // its position iteration stalls.
    void takeStep(State& state);

    enum class Outcome
    {
        Done,
        Stalled,  // the position iteration stalled; state partly stepped
        OneSided, // a stage of a composed step met contact or limit rows; state partly stepped
    };
    // One RATTLE step of the context's h, or a stage of a composed step (StepScheme::Rattle4Stage).
    // firstStage: the step's actuator accounting starts.
    Outcome stage(State& state, bool firstStage);

  private:
    StepStages& mStages;
    EulerStepper mEuler; // a stalled step taken again
};

} // namespace frontier::core
