// core/step/step_stages.cpp: the stages of a step, each one call into a unit of core/step/ with the
// step's context; the steppers (core/steppers/) put them in the order of their scheme.
#include "core/step/step_stages.h"

#include "core/joints/coordinates.h"
#include "core/step/geometric_stiffness.h"
#include "core/step/positions.h"
#include "core/step/velocity_stage.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace frontier::core
{

namespace
{
// The clock after a step of dt that started at `start` (s), state.step the steps before it. While
// the clock is on the grid of dt (start == step dt exactly: a run from 0 at one dt), it stays on
// it, (step + 1) dt, so a run's times carry no round-off (1.2, not 1.1999999999999786 after 1200
// steps of 1 ms); a clock set elsewhere by its user advances by dt.
void advanceClock(State& state, double start, double dt)
{
    const bool onGrid = start == static_cast<double>(state.step) * dt;
    ++state.step;
    state.time = onGrid ? static_cast<double>(state.step) * dt : start + dt;
}
} // namespace

StepContext::StepContext(const Model& model_, const StepOptions& options_, const FrontierLayout& layout_,
                         ImpulseSolver& solver_, Actuation& actuation_)
    : model(model_), options(options_), layout(layout_), solver(solver_), actuation(actuation_),
      dt(model_.simulation.dt), h(model_.simulation.dt)
{
    const std::size_t nb = model.bodies.size();
    const std::size_t nj = model.joints.size();
    rhs.resize(nb, nj);
    solution.resize(nb, nj);
    rhs.setZero();
    solution.setZero();
    start.resize(nb);
    principal.resize(nb);
    for (std::size_t i = 0; i < nb; ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            principal[i] = principalAxes(model.bodies[i].inertia_B);
        }
    }
}

StepStages::StepStages(const Model& model, const StepOptions& options, ContactSource* contacts)
    : mModel(model), mOptions(options), mContactSource(contacts), mLayout(buildFrontierLayout(model)),
      mActuation(model, mLayout),
      mSolver(makeSolver(model.simulation.solver, model.simulation.pgsIterations)),
      mStep(model, mOptions, mLayout, *mSolver, mActuation), mProblem(mStep), mPenetration(mStep),
      mDrift(mStep), mRattle(mStep), mBlowUp(model, mOptions, model.simulation.dt)
{
    mStep.driveStep = model.simulation.integrator == IntegratorKind::Euler ? mStep.dt : 0.5 * mStep.dt;
    mHeldInRotation = bodiesHeldInRotation(model);
}

void StepStages::beginStep(StepScheme scheme)
{
    mStats.seconds.fill(0.0);
    mStats.firstOrderFallback = false;
    mStats.secondOrderFallback = false;
    mComposedStep = false;
    mStep.h = mStep.dt;
    mStep.scheme = scheme;
}

void StepStages::finishActuation()
{
    if (mActuation.finishStep(mStep.dt))
    {
        // Actuators returned to their joints' blocks: rows assembled for the next step before
        // this are stale.
        mEndRowsValid = false;
        mRattle.forgetFactoredPose();
    }
}

void StepStages::saveRestart(const State& state)
{
    mRestart.state = state;
    mRestart.penetration = mPenetration.memory();
}

void StepStages::restart(State& state)
{
    state = mRestart.state;
    mPenetration.restore(mRestart.penetration);
    mRattle.forgetFactoredPose();
}

// Rows at the start-of-step pose: the last step's drift correction evaluated them at its end
// pose, which is this one unless the state was changed between steps (bit-identical either way).
void StepStages::rowsAtStart(const State& state)
{
    if (mEndRowsValid && samePose(mModel, state, mEndPose))
    {
        std::swap(mStep.rows, mStep.rowsAfter);
    }
    else
    {
        assembleRows(mModel, mLayout, state, mStep.driveStep, mStep.rows, mActuation.gains());
    }
    mEndRowsValid = false;
}

// The step ended at `state` with rowsAfter evaluated there: the next step starting there reuses them.
void StepStages::keepEndRows(const State& state)
{
    mEndPose = state.bodies;
    mEndRowsValid = true;
}

// docs/method.md §3, eq. (5) (eliminate), once per step, and eq. (6) (substitute) for the joint
// impulses of the free velocities and the carried extra impulses, fused into one pass.
void StepStages::factorAndSolve()
{
    mSolver->factorAndSolve(mStep.rows, mStep.rhs, mStep.solution);
}

// §3 step 3: the joint impulses of the free velocities with the factorization at hand.
void StepStages::solve()
{
    mSolver->solve(mStep.rhs, mStep.solution);
}

// A stage of a composed step: joint angles, the clock advanced by the stage's h, the state checked.
void StepStages::finishStage(State& state)
{
    trackJointAngles(mModel, state);
    state.time += mStep.h;
    checkState(state, "end of step");
}

void StepStages::clearStageImpulses()
{
    mStageJoint.assign(mModel.joints.size(), Vec6::Zero());
    mStageExtras.clear();
}

// A rattle4 stage's impulses, kept for the step's report (core/step_report.cpp), which takes all of
// them at the pose the step ends in, as for rattle.
void StepStages::keepStageImpulses()
{
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        mStageJoint[k] += mStep.solution.joint[k];
    }
    const auto keep = [&](const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda)
    {
        if (!blocks.empty())
        {
            mStageExtras.emplace_back(blocks, lambda);
        }
    };
    keep(mProblem.blocks(), mProblem.impulses());
    keep(mStep.loopBlocks, mDrift.loopCorrection());
    keep(mRattle.blocks(), mRattle.impulses());
}

// Contact or joint-limit rows among the extra rows: one-sided, which a backward stage of rattle4
// cannot hold (docs/method.md §11).
bool StepStages::hasOneSidedRows() const
{
    return std::any_of(mProblem.blocks().begin(), mProblem.blocks().end(),
                       [](const ExtraBlock& block) {
                           return block.kind == ExtraBlock::Kind::Contact ||
                                  block.kind == ExtraBlock::Kind::Limit;
                       });
}

// Rows and factorization at the start-of-step pose (core/step/rattle_projection.h).
void StepStages::factorAtStart(const State& state)
{
    mRattle.factorAtStart(mStep, state);
}

// RATTLE's velocity projection at q_{n+1} (core/step/rattle_projection.h).
void StepStages::projectVelocities(State& state)
{
    mRattle.project(mStep, state, mProblem);
}

// The joints' angles continued across +-pi (State::jointAngles), the clock advanced, the state checked.
void StepStages::finishStep(State& state)
{
    trackJointAngles(mModel, state);
    advanceClock(state, state.time, mStep.dt);
    checkState(state, "end of step");
}

// The clock of a composed step that started at `start` (s), advanced by dt over its stages.
void StepStages::finishComposedStep(State& state, double start)
{
    advanceClock(state, start, mStep.dt);
}

// The first step's contacts and limit rows: how the scene started (core/failure_hint.h).
void StepStages::recordStartDefects(const State& state)
{
    mBlowUp.recordStartDefects(mProblem.contacts(), mProblem.blocks(), state);
}

// A body's state non-finite or runaway: SimulationError (core/step/blow_up_check.h).
void StepStages::checkState(const State& state, const char* where) const
{
    mBlowUp.checkState(state, where, {mStats.maxPenetrationM, mProblem.blocks(), mStep.start});
}

// u* = u + h M^-1 f over a time h (s): gravity on the centre of mass, effort actuators and loads.
// Saves the start-of-step poses, and the free velocities when an actuator may make the step's
// first solve be taken again.
void StepStages::computeFreeVelocities(State& state, double h)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        mStep.start[i] = state.bodies[i];
    }
    kickByGravity(state, h);
    applyForces(state, state.time, state.time + h); // effort actuators, loads
    keepFreeVelocities(state);
}

// v += h g for every moving body (h in s; core/step/velocity_stage.h).
void StepStages::kickByGravity(State& state, double h)
{
    core::kickByGravity(mModel, state, h);
}

// Effort actuators and loads over [tBegin, tEnd] (s; core/actuation.h).
void StepStages::applyForces(State& state, double tBegin, double tEnd)
{
    mActuation.applyForces(state, tBegin, tEnd);
}

// The free velocities, kept when an actuator may make the step's first solve be taken again.
void StepStages::keepFreeVelocities(const State& state)
{
    if (mActuation.hasDriveRows())
    {
        mFree = state.bodies;
    }
}

// After the first velocity stage: true when every actuator in its joint's block stayed within its
// effort limit. Otherwise that actuator is now a bounded extra row: the state goes back to the
// free velocities and the stage is solved again, rows assembled anew (core/actuation.h).
bool StepStages::actuatorsWithinLimits(State& state)
{
    if (!mActuation.hasDriveRows() || mActuation.acceptSolve(mStep.rows, mStep.solution, mProblem.blocks(),
                                                             mProblem.impulses(), mStep.driveStep))
    {
        return true;
    }
    state.bodies = mFree;
    mEndRowsValid = false;
    mRattle.forgetFactoredPose();
    return false;
}

void StepStages::detectContacts(const State& state)
{
    std::vector<Contact>& contacts = mProblem.contacts();
    contacts.clear();
    if (mContactSource != nullptr)
    {
        mContactSource->detect(state, contacts);
    }
    mStats.contacts = static_cast<int>(contacts.size());
    mStats.maxPenetrationM = 0.0;
    for (const Contact& contact : contacts)
    {
        mStats.maxPenetrationM = std::max(mStats.maxPenetrationM, contact.depth);
    }
}

// The step's extra rows at the start-of-step pose (core/step/contact_problem.h): the loop joints'
// rows of the factored rows, contacts, limits, joint friction and actuators at their limits. The
// first step's also tell how the scene started.
void StepStages::buildExtraRows(const State& state)
{
    buildLoopBlocks(mModel, mLayout, mStep.rows, mStep.loopBlocks);
    mStats.extraRows = mProblem.build(mStep, state);
    recordStartDefects(state);
}

// p = M u* (core/step/velocity_stage.h), targets of the drives in their blocks at tEnd (s).
void StepStages::setMomentumRhs(const State& state, double tEnd)
{
    core::setMomentumRhs(mModel, mStep.rows, state, tEnd, mStep.driveStep, mActuation, mStep.rhs);
}

// docs/method.md §7a, eq. (11c): the bodies whose joints' loads of the last step make them turn
// stiffly take that stiffness implicitly in this step's factorization.
void StepStages::stiffenLoadedBodies(const State& state)
{
    mStats.stiffenedBodies = core::stiffenLoadedBodies(mModel, state.jointLoads, mStep.dt, mStep.rows);
}

// The joints' loads of this step (its rows and impulses), for the next step's stiffness.
void StepStages::recordJointLoads(State& state) const
{
    measureJointLoads(mModel, mStep.rows, mStep.solution, state.jointLoads);
}

// docs/method.md §7, eq. (11a): the velocities ask J u = -D_pred / h so that the drift correction
// starts near C = 0. On steps whose first solve is the exact tree solve alone, that solve asks it
// (one solve for both); extra rows (contacts, limits, loops) are solved on top of the first solve
// and must not see the bias in their impulses, so those steps solve for it on its own after them
// (predictDriftAfterExtraRows). pgs solves approximately and never predicts.
bool StepStages::predictsDrift() const
{
    return mOptions.predictDrift && mModel.simulation.solver != SolverKind::Pgs;
}

void StepStages::predictDrift(const State& state)
{
    if (predictsDrift() && mStats.extraRows == 0)
    {
        mDrift.addPredictedDrift(state, mStep.rhs, mStep.dt);
    }
}

void StepStages::predictDriftAfterExtraRows(State& state)
{
    if (predictsDrift() && mStats.extraRows > 0)
    {
        mDrift.applyPredictedDrift(state, mStep.solution, mStep.dt);
    }
}

// The last step's impulses on this step's rows, their momentum into the right-hand side
// (core/step/contact_problem.h).
void StepStages::carryImpulses()
{
    mProblem.carryImpulses(mStep.rhs);
}

// The extra rows' impulses on top of the tree's solution (core/step/contact_problem.h); then the
// state takes the velocities u'.
void StepStages::solveContactImpulses(State& state)
{
    const ContactProblem::Outcome outcome = mProblem.solve(mStep.solution);
    mStats.contactSweeps = outcome.sweeps;
    mStats.contactRoute = outcome.route;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W = mStep.solution.body[i].head<3>();
            state.bodies[i].angularVelocity_W = mStep.solution.body[i].tail<3>();
        }
    }
}

// The bounded position projection of overlaps and limit overruns (core/step/penetration_projection.h).
void StepStages::removePenetration(State& state)
{
    mPenetration.apply(mStep, state, mProblem);
}

// The position update from the start-of-step pose, each body's rotation update chosen for the
// step (docs/method.md §4, eq. (8a); core/step/positions.h).
void StepStages::integratePositions(State& state)
{
    chooseRotationUpdates(mModel, mHeldInRotation, mStep.rows, state, mStep.h, mStep.rattle(),
                          mStep.freeRotation);
    core::integratePositions(mModel, mStep.start, mStep.principal, mStep.rows, mStep.freeRotation, mStep.h,
                             state);
}

// w_{n+1} = I_W(R_{n+1})^-1 I_W(R_n) w (core/step/positions.h).
void StepStages::carryAngularMomentum(State& state)
{
    core::carryAngularMomentum(mModel, mStep.principal, mStep.rows, state);
}

// The drift correction of the joints (core/step/drift_correction.h). A joint still apart after it
// is a blow-up: the run stops naming the step, the joint and the gap. False: a rattle step stalled.
bool StepStages::stabilizeJoints(State& state)
{
    const DriftCorrection::Outcome outcome = mDrift.run(mStep, state);
    const JointErrors& errors = mDrift.errors();
    mStats.maxJointErrorM = errors.maxM;
    mStats.maxJointErrorRad = errors.maxRad;
    mStats.stabilizationIterations = mDrift.iterations();
    if (outcome == DriftCorrection::Outcome::CameApart)
    {
        mBlowUp.jointCameApart(state, errors, {mStats.maxPenetrationM, mProblem.blocks(), mStep.start});
    }
    return outcome != DriftCorrection::Outcome::Stalled;
}

std::pair<double, double> StepStages::jointErrors(const State& state)
{
    mEndRowsValid = false; // rowsAfter is about to hold other rows
    assembleRows(mModel, mLayout, state, mStep.driveStep, mStep.rowsAfter, mActuation.gains());
    const JointErrors& errors = mDrift.measure(mStep.rowsAfter);
    mStats.maxJointErrorM = errors.maxM;
    mStats.maxJointErrorRad = errors.maxRad;
    return {mStats.maxJointErrorM, mStats.maxJointErrorRad};
}

} // namespace frontier::core
