// core/steppers/euler_stepper.h: the first-order scheme (`euler`), symplectic Euler with a
// SHAKE-type projection of the joints' drift. Its pipeline (core/steppers/euler_stepper.cpp;
// stage timings: StepStage, core/step_stats.h):
//   checkState -> detectContacts                                                       [Detect]
//   -> computeFreeVelocities -> rowsAtStart -> stiffenLoadedBodies -> buildExtraRows
//   -> setMomentumRhs -> predictDrift -> carryImpulses
//   -> factorAndSolve (O(n): elimination and the joint impulses in one pass)           [Factor]
//   -> solveContactImpulses                                                            [Solve]
//      (rowsAtStart .. solveContactImpulses again while an actuator went past its effort limit)
//   -> predictDriftAfterExtraRows
//   -> integratePositions -> removePenetration -> stabilizeJoints -> recordJointLoads
//   -> carryAngularMomentum -> finishStep (joint angles, time, checkState)             [Integrate]
// The physics of each stage: core/simulator.h and docs/method.md.
#pragma once

#include "core/step/step_stages.h"
#include "core/steppers/stepper.h"

namespace frontier::core
{

class EulerStepper final : public Stepper
{
  public:
    explicit EulerStepper(StepStages& stages) : mStages(stages) {}
    void step(State& state) override;
    // The pipeline alone, in a step already begun (also a stalled rattle step taken again).
    void takeStep(State& state);

  private:
    StepStages& mStages;
};

} // namespace frontier::core
