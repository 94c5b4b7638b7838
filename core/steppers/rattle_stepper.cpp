// core/steppers/rattle_stepper.cpp: one step of the second-order scheme
// (core/steppers/rattle_stepper.h).
#include "core/steppers/rattle_stepper.h"

namespace frontier::core
{

void RattleStepper::step(State& state)
{
    mStages.beginStep(StepScheme::Rattle);
    StepContext& step = mStages.context();
    step.driveStep = 0.5 * step.dt;
    mStages.saveRestart(state);
    mStages.forgetEndRows(); // the rattle projection swaps rowsAfter away
    takeStep(state);
}

void RattleStepper::takeStep(State& state)
{
    if (stage(state, true) == Outcome::Done)
    {
        return;
    }
    // RATTLE's position iteration stalled (very fast rotation within the step): this step is
    // taken again from its start by the robust first-order scheme.
    mStages.restart(state);
    StepContext& step = mStages.context();
    step.scheme = StepScheme::Euler;
    step.driveStep = step.dt;
    mEuler.takeStep(state);
    mStages.stats().firstOrderFallback = true;
}

// Second order (RATTLE): kick h/2 g; impulses at q_n (joints, contacts) that the Newton
// iteration of stabilizeJoints completes into the multiplier putting q_{n+1} on the constraint
// manifold; drift; kick h/2 g; velocity projection at q_{n+1}. h: the step, or a stage of a
// composed step (negative for rattle4's middle stage).
RattleStepper::Outcome RattleStepper::stage(State& state, bool firstStage)
{
    StepStages& s = mStages;
    const double h = s.context().h;
    const bool composed = s.context().scheme == StepScheme::Rattle4Stage;
    StageClock clock(s.stats().seconds);
    s.checkState(state, "start of step");
    state.jointLoads.clear(); // the geometric stiffness is euler's (§7a)
    s.stats().stiffenedBodies = 0;
    if (firstStage)
    {
        s.actuation().beginStep(state.time, s.context().dt);
    }
    s.detectContacts(state);
    clock.lap(StepStage::Detect);
    s.computeFreeVelocities(state, 0.5 * h);
    do
    {
        s.factorAtStart(state); // docs/method.md §3, eq. (5), shared with the last step's projection
        clock.lap(StepStage::Factor);
        s.buildExtraRows(state);
        if (composed && s.hasOneSidedRows())
        {
            return Outcome::OneSided;
        }
        s.setMomentumRhs(state, state.time + 0.5 * h);
        s.carryImpulses();
        s.solve(); // §3 step 3: joint impulses of the free velocities
        s.solveContactImpulses(state);
        clock.lap(StepStage::Solve);
    } while (!s.actuatorsWithinLimits(state));
    s.integratePositions(state); // drift: x += h v, R by the free rotation at constant L
    s.removePenetration(state);
    if (!s.stabilizeJoints(state)) // Newton on C(q_{n+1}) = 0, impulses along J(q_n)^T
    {
        return Outcome::Stalled;
    }
    s.carryAngularMomentum(state); // w_{n+1} = I_W(R_{n+1})^-1 L
    s.kickByGravity(state, 0.5 * h);
    s.applyForces(state, state.time + 0.5 * h, state.time + h);
    s.projectVelocities(state); // J(q_{n+1}) u_{n+1} = 0, factored for the next step
    if (composed)
    {
        s.finishStage(state);
    }
    else
    {
        s.finishStep(state);
    }
    clock.lap(StepStage::Integrate);
    return Outcome::Done;
}

} // namespace frontier::core
