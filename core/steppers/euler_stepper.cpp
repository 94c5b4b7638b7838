// core/steppers/euler_stepper.cpp: one step of the first-order scheme (core/steppers/euler_stepper.h).
#include "core/steppers/euler_stepper.h"

namespace frontier::core
{

void EulerStepper::step(State& state)
{
    mStages.beginStep(StepScheme::Euler);
    StepContext& step = mStages.context();
    step.driveStep = step.dt;
    takeStep(state);
}

// First order: kick h g, impulses (joints exact, contacts), drift, SHAKE-type drift removal.
void EulerStepper::takeStep(State& state)
{
    StepStages& s = mStages;
    const double dt = s.context().dt;
    StageClock clock(s.stats().seconds);
    s.checkState(state, "start of step");
    s.actuation().beginStep(state.time, dt);
    s.detectContacts(state);
    clock.lap(StepStage::Detect);
    s.computeFreeVelocities(state, dt);
    do
    {
        s.rowsAtStart(state);
        s.stiffenLoadedBodies(state); // light bodies under large joint forces turn implicitly (§7a)
        s.buildExtraRows(state);      // contacts, loops, limits at the start-of-step pose (§5)
        s.setMomentumRhs(state, state.time + dt);
        s.predictDrift(state);
        s.carryImpulses();  // the last step's impulses on those rows join the right-hand side
        s.factorAndSolve(); // docs/method.md §3, eqs. (5) and (6) in one pass
        clock.lap(StepStage::Factor);
        s.solveContactImpulses(state); // the extra rows on top (§5)
        clock.lap(StepStage::Solve);
    } while (!s.actuatorsWithinLimits(state));
    s.predictDriftAfterExtraRows(state);
    s.integratePositions(state);
    s.removePenetration(state);
    s.stabilizeJoints(state); // leaves rowsAfter at the end-of-step pose
    s.recordJointLoads(state);
    s.carryAngularMomentum(state);
    s.finishStep(state);
    s.keepEndRows(state);
    clock.lap(StepStage::Integrate);
}

} // namespace frontier::core
