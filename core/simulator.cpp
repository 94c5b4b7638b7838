// core/simulator.cpp: the step pipelines of the first-order (`euler`), second-order (`rattle`) and
// fourth-order (`rattle4`) schemes.
#include "core/simulator.h"

#include "core/joints/coordinates.h"
#include "core/joints/drive.h"
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

Simulator::Simulator(const Model& model, const StepOptions& options, ContactSource* contacts)
    : mModel(model), mOptions(options), mContactSource(contacts), mLayout(buildFrontierLayout(model)),
      mActuation(model, mLayout),
      mSolver(makeSolver(model.simulation.solver, model.simulation.pgsIterations)),
      mProblem(model, mOptions, mLayout, *mSolver), mPenetration(model, mOptions, mLayout, *mSolver),
      mDrift(model, mOptions, mLayout, *mSolver), mRattle(model, mOptions, mLayout, *mSolver),
      mBlowUp(model, mOptions, model.simulation.dt), mDt(model.simulation.dt)
{
    mH = mDt;
    mDriveStep = model.simulation.integrator == IntegratorKind::Euler ? mDt : 0.5 * mDt;
    const std::vector<std::uint8_t> actuated = actuatedJoints(model);
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        mHasBlockDrives = mHasBlockDrives || blockDriveRows(model.joints[k], actuated[k] != 0) > 0;
    }
    const std::size_t nb = model.bodies.size();
    const std::size_t nj = model.joints.size();
    mRhs.resize(nb, nj);
    mSolution.resize(nb, nj);
    mRhs.setZero();
    mSolution.setZero();
    mStart.resize(nb);
    mPrincipal.resize(nb);
    for (std::size_t i = 0; i < nb; ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            mPrincipal[i] = principalAxes(model.bodies[i].inertia_B);
        }
    }
    mHeldInRotation = bodiesHeldInRotation(model);
}

Simulator::~Simulator() = default;

void Simulator::step(State& state)
{
    takeStep(state);
    if (mActuation.finishStep(mDt))
    {
        // Actuators returned to their joints' blocks: rows assembled for the next step before
        // this are stale.
        mEndRowsValid = false;
        mRattle.forgetFactoredPose();
    }
}

void Simulator::applyForceAtPoint(const State& state, int body, const Vec3& force_N, const Vec3& point_W)
{
    const std::size_t i = static_cast<std::size_t>(body);
    const bool known = body >= 0 && i < state.bodies.size();
    const Vec3 lever = point_W - (known ? state.bodies[i].position_W : Vec3::Zero()); // m
    applyWrench(body, force_N, lever.cross(force_N)); // refuses the index, a static body, a point not finite
}

void Simulator::takeStep(State& state)
{
    mStats.seconds.fill(0.0);
    mStats.firstOrderFallback = false;
    mStats.secondOrderFallback = false;
    mComposedStep = false;
    mH = mDt;
    const IntegratorKind integrator = mModel.simulation.integrator;
    mRattleStep = integrator != IntegratorKind::Euler;
    if (integrator != IntegratorKind::Rattle4) // rattle4 keeps its last stage's (stepRattle4)
    {
        mDriveStep = mRattleStep ? 0.5 * mDt : mDt;
    }
    if (!mRattleStep)
    {
        stepEuler(state);
        return;
    }
    mStepStart = state;
    mEndRowsValid = false; // the rattle projection swaps mRowsAfter away
    const bool penetrationCapped = mPenetration.capped();
    if (integrator == IntegratorKind::Rattle4)
    {
        if (stepRattle4(state))
        {
            return;
        }
        // A stage met a contact or a joint limit, or stalled: the step is taken again from its
        // start as one RATTLE step (docs/method.md §11).
        state = mStepStart;
        mPenetration.setCapped(penetrationCapped);
        mRattle.forgetFactoredPose();
        mH = mDt;
        mDriveStep = 0.5 * mDt;
        mStats.secondOrderFallback = true;
    }
    if (stepRattle(state, true) != RattleOutcome::Done)
    {
        // RATTLE's position iteration stalled (very fast rotation within the step): this step is
        // taken again from its start by the robust first-order scheme.
        state = mStepStart;
        mPenetration.setCapped(penetrationCapped);
        mRattleStep = false;
        mDriveStep = mDt;
        mRattle.forgetFactoredPose();
        stepEuler(state);
        mStats.firstOrderFallback = true;
    }
}

// Fourth order (docs/method.md §11): RATTLE stages of c1 h, c2 h, c1 h (the triple jump; c2 < 0),
// each a whole RATTLE step at its own time. The drives and joint friction of a stage act over
// the positive time w h (the weights add up to 1), so they stay dissipative and stable in the
// backward stage. False: a stage met contact or limit rows (one-sided, not time-reversible) or
// stalled; the state is then partly stepped.
bool Simulator::stepRattle4(State& state)
{
    const double start = state.time;
    const TripleJump jump = tripleJumpCoefficients();
    const double c1 = jump.c1;
    const double c2 = jump.c2;
    const double total = c1 + c1 - c2; // the sum of |c|
    const std::array<double, 3> weights = {c1, c2, c1};
    bool first = true;
    int iterations = 0;
    mRattle4Stage = true;
    mStageJoint.assign(mModel.joints.size(), Vec6::Zero());
    mStageExtras.clear();
    int stageIndex = 0;
    for (const double c : weights)
    {
        const double driveStep = 0.5 * (std::abs(c) / total) * mDt;
        if (driveStep != mDriveStep && mHasBlockDrives)
        {
            mRattle.forgetFactoredPose(); // the drive rows' compliance depends on the stage's time
        }
        mH = c * mDt;
        mDriveStep = driveStep;
        if (stepRattle(state, first) != RattleOutcome::Done)
        {
            mRattle4Stage = false;
            return false;
        }
        iterations += mStats.stabilizationIterations;
        first = false;
        if (++stageIndex < 3)
        {
            keepStageImpulses();
        }
    }
    mRattle4Stage = false;
    mComposedStep = true;
    advanceClock(state, start, mDt);
    mStats.stabilizationIterations = iterations;
    return true;
}

// First order: kick h g, impulses (joints exact, contacts), drift, SHAKE-type drift removal.
void Simulator::stepEuler(State& state)
{
    StageClock clock(mStats.seconds);
    checkState(state, "start of step");
    mActuation.beginStep(state.time, mDt);
    detectContacts(state);
    clock.lap(StepStage::Detect);
    computeFreeVelocities(state, mDt);
    do
    {
        rowsAtStart(state);
        stiffenLoadedBodies(state); // light bodies under large joint forces turn implicitly (§7a)
        buildExtraRows(state);      // contacts, loops, limits at the start-of-step pose (§5)
        setMomentumRhs(state, state.time + mDt);
        predictDrift(state);
        carryImpulses(); // the last step's impulses on those rows join the right-hand side
        // docs/method.md §3, eq. (5) (eliminate), once per step, and eq. (6) (substitute) for the joint
        // impulses of the free velocities and the carried extra impulses, fused into one pass.
        mSolver->factorAndSolve(mRows, mRhs, mSolution);
        clock.lap(StepStage::Factor);
        solveContactImpulses(state); // the extra rows on top (§5)
        clock.lap(StepStage::Solve);
    } while (!actuatorsWithinLimits(state));
    predictDriftAfterExtraRows(state);
    integratePositions(state);
    removePenetration(state);
    stabilizeJoints(state); // leaves mRowsAfter at the end-of-step pose
    recordJointLoads(state);
    carryAngularMomentum(state);
    finishStep(state);
    mEndPose = state.bodies;
    mEndRowsValid = true;
    clock.lap(StepStage::Integrate);
}

// Rows at the start-of-step pose: the last step's drift correction evaluated them at its end
// pose, which is this one unless the state was changed between steps (bit-identical either way).
void Simulator::rowsAtStart(const State& state)
{
    if (mEndRowsValid && samePose(mModel, state, mEndPose))
    {
        std::swap(mRows, mRowsAfter);
    }
    else
    {
        assembleRows(mModel, mLayout, state, driveStep(), mRows, mActuation.gains());
    }
    mEndRowsValid = false;
}

// Second order (RATTLE): kick h/2 g; impulses at q_n (joints, contacts) that the Newton
// iteration of stabilizeJoints completes into the multiplier putting q_{n+1} on the constraint
// manifold; drift; kick h/2 g; velocity projection at q_{n+1}. h = mH: the step, or a stage of
// rattle4 (negative for its middle stage). firstStage: the step's actuator accounting starts.
Simulator::RattleOutcome Simulator::stepRattle(State& state, bool firstStage)
{
    StageClock clock(mStats.seconds);
    const bool stage = mRattle4Stage;
    checkState(state, "start of step");
    state.jointLoads.clear(); // the geometric stiffness is euler's (§7a)
    mStats.stiffenedBodies = 0;
    if (firstStage)
    {
        mActuation.beginStep(state.time, mDt);
    }
    detectContacts(state);
    clock.lap(StepStage::Detect);
    computeFreeVelocities(state, 0.5 * mH);
    do
    {
        factorAtStart(state); // docs/method.md §3, eq. (5), shared with the last step's projection
        clock.lap(StepStage::Factor);
        buildExtraRows(state);
        if (stage && hasOneSidedRows())
        {
            return RattleOutcome::OneSided;
        }
        setMomentumRhs(state, state.time + 0.5 * mH);
        carryImpulses();
        mSolver->solve(mRhs, mSolution); // §3 step 3: joint impulses of the free velocities
        solveContactImpulses(state);
        clock.lap(StepStage::Solve);
    } while (!actuatorsWithinLimits(state));
    integratePositions(state); // drift: x += h v, R by the free rotation at constant L
    removePenetration(state);
    if (!stabilizeJoints(state)) // Newton on C(q_{n+1}) = 0, impulses along J(q_n)^T
    {
        return RattleOutcome::Stalled;
    }
    carryAngularMomentum(state); // w_{n+1} = I_W(R_{n+1})^-1 L
    kickByGravity(state, 0.5 * mH);
    mActuation.applyForces(state, state.time + 0.5 * mH, state.time + mH);
    projectVelocities(state); // J(q_{n+1}) u_{n+1} = 0, factored for the next step
    if (stage)
    {
        trackJointAngles(mModel, state);
        state.time += mH;
        checkState(state, "end of step");
    }
    else
    {
        finishStep(state);
    }
    clock.lap(StepStage::Integrate);
    return RattleOutcome::Done;
}

// A rattle4 stage's impulses, kept for the step's report (core/step_report.cpp), which takes all of
// them at the pose the step ends in, as for rattle.
void Simulator::keepStageImpulses()
{
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        mStageJoint[k] += mSolution.joint[k];
    }
    const auto keep = [&](const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda)
    {
        if (!blocks.empty())
        {
            mStageExtras.emplace_back(blocks, lambda);
        }
    };
    keep(mProblem.blocks(), mProblem.impulses());
    keep(mLoopBlocks, mDrift.loopCorrection());
    keep(mRattle.blocks(), mRattle.impulses());
}

// Contact or joint-limit rows among the extra rows: one-sided, which a backward stage of rattle4
// cannot hold (docs/method.md §11).
bool Simulator::hasOneSidedRows() const
{
    return std::any_of(mProblem.blocks().begin(), mProblem.blocks().end(),
                       [](const ExtraBlock& block) {
                           return block.kind == ExtraBlock::Kind::Contact ||
                                  block.kind == ExtraBlock::Kind::Limit;
                       });
}

// Rows and factorization at the start-of-step pose (core/step/rattle_projection.h).
void Simulator::factorAtStart(const State& state)
{
    mRattle.factorAtStart(state, mRows, driveStep(), mActuation);
}

// RATTLE's velocity projection at q_{n+1} (core/step/rattle_projection.h).
void Simulator::projectVelocities(State& state)
{
    mRattle.project(state, mRows, mRowsAfter, mLoopBlocks, mProblem, mRhs, mSolution, mH, driveStep(),
                    mActuation);
}

// The joints' angles continued across +-pi (State::jointAngles), the clock advanced, the state checked.
void Simulator::finishStep(State& state)
{
    trackJointAngles(mModel, state);
    advanceClock(state, state.time, mDt);
    checkState(state, "end of step");
}

// The first step's contacts and limit rows: how the scene started (core/failure_hint.h).
void Simulator::recordStartDefects(const State& state)
{
    mBlowUp.recordStartDefects(mProblem.contacts(), mProblem.blocks(), state);
}

// A body's state non-finite or runaway: SimulationError (core/step/blow_up_check.h).
void Simulator::checkState(const State& state, const char* where) const
{
    mBlowUp.checkState(state, where, {mStats.maxPenetrationM, mProblem.blocks(), mStart});
}

// u* = u + h M^-1 f over a time h (s): gravity on the centre of mass, effort actuators and loads.
// Saves the start-of-step poses, and the free velocities when an actuator may make the step's
// first solve be taken again.
void Simulator::computeFreeVelocities(State& state, double h)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        mStart[i] = state.bodies[i];
    }
    kickByGravity(state, h);
    mActuation.applyForces(state, state.time, state.time + h); // effort actuators, loads
    keepFreeVelocities(state);
}

// v += h g for every moving body (h in s; core/step/velocity_stage.h).
void Simulator::kickByGravity(State& state, double h)
{
    core::kickByGravity(mModel, state, h);
}

// The free velocities, kept when an actuator may make the step's first solve be taken again.
void Simulator::keepFreeVelocities(const State& state)
{
    if (mActuation.hasDriveRows())
    {
        mFree = state.bodies;
    }
}

// After the first velocity stage: true when every actuator in its joint's block stayed within its
// effort limit. Otherwise that actuator is now a bounded extra row: the state goes back to the
// free velocities and the stage is solved again, rows assembled anew (core/actuation.h).
bool Simulator::actuatorsWithinLimits(State& state)
{
    if (!mActuation.hasDriveRows() ||
        mActuation.acceptSolve(mRows, mSolution, mProblem.blocks(), mProblem.impulses(), driveStep()))
    {
        return true;
    }
    state.bodies = mFree;
    mEndRowsValid = false;
    mRattle.forgetFactoredPose();
    return false;
}

void Simulator::detectContacts(const State& state)
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
void Simulator::buildExtraRows(const State& state)
{
    buildLoopBlocks(mModel, mLayout, mRows, mLoopBlocks);
    mStats.extraRows = mProblem.build(state, mStart, mLoopBlocks, std::abs(mH), driveStep(), mActuation);
    recordStartDefects(state);
}

// p = M u* (core/step/velocity_stage.h), targets of the drives in their blocks at tEnd (s).
void Simulator::setMomentumRhs(const State& state, double tEnd)
{
    core::setMomentumRhs(mModel, mRows, state, tEnd, driveStep(), mActuation, mRhs);
}

// docs/method.md §7a, eq. (11c): the bodies whose joints' loads of the last step make them turn
// stiffly take that stiffness implicitly in this step's factorization.
void Simulator::stiffenLoadedBodies(const State& state)
{
    mStats.stiffenedBodies = core::stiffenLoadedBodies(mModel, state.jointLoads, mDt, mRows);
}

// The joints' loads of this step (its rows and impulses), for the next step's stiffness.
void Simulator::recordJointLoads(State& state) const
{
    measureJointLoads(mModel, mRows, mSolution, state.jointLoads);
}

// docs/method.md §7, eq. (11a): the velocities ask J u = -D_pred / h so that the drift correction
// starts near C = 0. On steps whose first solve is the exact tree solve alone, that solve asks it
// (one solve for both); extra rows (contacts, limits, loops) are solved on top of the first solve
// and must not see the bias in their impulses, so those steps solve for it on its own after them
// (predictDriftAfterExtraRows). pgs solves approximately and never predicts.
bool Simulator::predictsDrift() const
{
    return mOptions.predictDrift && mModel.simulation.solver != SolverKind::Pgs;
}

void Simulator::predictDrift(const State& state)
{
    if (predictsDrift() && mStats.extraRows == 0)
    {
        mDrift.addPredictedDrift(state, mRhs, mDt);
    }
}

void Simulator::predictDriftAfterExtraRows(State& state)
{
    if (predictsDrift() && mStats.extraRows > 0)
    {
        mDrift.applyPredictedDrift(state, mSolution, mDt);
    }
}

// The last step's impulses on this step's rows, their momentum into the right-hand side
// (core/step/contact_problem.h).
void Simulator::carryImpulses()
{
    mProblem.carryImpulses(mRhs);
}

// The extra rows' impulses on top of the tree's solution (core/step/contact_problem.h); then the
// state takes the velocities u'.
void Simulator::solveContactImpulses(State& state)
{
    const ContactProblem::Outcome outcome = mProblem.solve(mSolution);
    mStats.contactSweeps = outcome.sweeps;
    mStats.contactRoute = outcome.route;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W = mSolution.body[i].head<3>();
            state.bodies[i].angularVelocity_W = mSolution.body[i].tail<3>();
        }
    }
}

// The bounded position projection of overlaps and limit overruns (core/step/penetration_projection.h).
void Simulator::removePenetration(State& state)
{
    mPenetration.apply(state, mStart, mProblem, mSolution, mRows, mPrincipal, std::abs(mH), driveStep(),
                       mActuation);
}

// The position update from the start-of-step pose, each body's rotation update chosen for the
// step (docs/method.md §4, eq. (8a); core/step/positions.h).
void Simulator::integratePositions(State& state)
{
    chooseRotationUpdates(mModel, mHeldInRotation, mRows, state, mH, mRattleStep, mFreeRotation);
    core::integratePositions(mModel, mStart, mPrincipal, mRows, mFreeRotation, mH, state);
}

// w_{n+1} = I_W(R_{n+1})^-1 I_W(R_n) w (core/step/positions.h).
void Simulator::carryAngularMomentum(State& state)
{
    core::carryAngularMomentum(mModel, mPrincipal, mRows, state);
}

// The drift correction of the joints (core/step/drift_correction.h). A joint still apart after it
// is a blow-up: the run stops naming the step, the joint and the gap. False: a rattle step stalled.
bool Simulator::stabilizeJoints(State& state)
{
    const DriftCorrection::Outcome outcome =
        mDrift.run(state, mStart, mPrincipal, mRows, mRowsAfter, mLoopBlocks, mSolution, mFreeRotation, mH,
                   driveStep(), mRattleStep, mActuation);
    const JointErrors& errors = mDrift.errors();
    mStats.maxJointErrorM = errors.maxM;
    mStats.maxJointErrorRad = errors.maxRad;
    mStats.stabilizationIterations = mDrift.iterations();
    if (outcome == DriftCorrection::Outcome::CameApart)
    {
        mBlowUp.jointCameApart(state, errors, {mStats.maxPenetrationM, mProblem.blocks(), mStart});
    }
    return outcome != DriftCorrection::Outcome::Stalled;
}

std::pair<double, double> Simulator::jointErrors(const State& state)
{
    mEndRowsValid = false; // mRowsAfter is about to hold other rows
    assembleRows(mModel, mLayout, state, driveStep(), mRowsAfter, mActuation.gains());
    const JointErrors& errors = mDrift.measure(mRowsAfter);
    mStats.maxJointErrorM = errors.maxM;
    mStats.maxJointErrorRad = errors.maxRad;
    return {mStats.maxJointErrorM, mStats.maxJointErrorRad};
}

} // namespace frontier::core
