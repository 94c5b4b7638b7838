// core/simulator.cpp: the step pipelines of the first-order (`euler`) and second-order (`rattle`)
// schemes.
#include "core/simulator.h"

#include "core/failure_hint.h"
#include "core/joints/coordinates.h"
#include "core/penetration.h"
#include "core/step/positions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace frontier::core
{

namespace
{
// Anything beyond these is a blow-up even while still finite.
constexpr double cMaxSpeed = 1e5;        // m/s
constexpr double cMaxAngularSpeed = 1e6; // rad/s

bool finite(const Vec3& v)
{
    return v.allFinite();
}

} // namespace

Simulator::Simulator(const Model& model, const StepOptions& options, ContactSource* contacts)
    : mModel(model), mOptions(options), mContactSource(contacts), mLayout(buildFrontierLayout(model)),
      mActuation(model, mLayout),
      mSolver(makeSolver(model.simulation.solver, model.simulation.pgsIterations)),
      mProblem(model, mOptions, mLayout, *mSolver), mPenetration(model, mOptions, mLayout, *mSolver),
      mDrift(model, mOptions, mLayout, *mSolver), mDt(model.simulation.dt)
{
    const std::size_t nb = model.bodies.size();
    const std::size_t nj = model.joints.size();
    mRhs.resize(nb, nj);
    mSolution.resize(nb, nj);
    mCorrection.resize(nb, nj);
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
        mFactoredPoseValid = false;
    }
}

void Simulator::takeStep(State& state)
{
    mRattleStep = mModel.simulation.integrator == IntegratorKind::Rattle;
    mStats.firstOrderFallback = false;
    if (!mRattleStep)
    {
        stepEuler(state);
        return;
    }
    mStepStart = state;
    mEndRowsValid = false; // the rattle projection swaps mRowsAfter away
    const bool penetrationCapped = mPenetration.capped();
    if (!stepRattle(state))
    {
        // RATTLE's position iteration stalled (very fast rotation within the step): this step is
        // taken again from its start by the robust first-order scheme.
        state = mStepStart;
        mPenetration.setCapped(penetrationCapped);
        mRattleStep = false;
        mFactoredPoseValid = false;
        stepEuler(state);
        mStats.firstOrderFallback = true;
    }
}

// First order: kick h g, impulses (joints exact, contacts), drift, SHAKE-type drift removal.
void Simulator::stepEuler(State& state)
{
    StageClock clock(mStats.seconds);
    checkState(state, "start of step");
    mActuation.beginStep();
    detectContacts(state);
    clock.lap(StepStage::Detect);
    computeFreeVelocities(state, mDt);
    keepFreeVelocities(state);
    do
    {
        rowsAtStart(state);
        buildExtraRows(state); // contacts, loops, limits at the start-of-step pose (§5)
        recordStartDefects(state);
        setMomentumRhs(state, state.time + mDt);
        mProblem.carryImpulses(mRhs); // the last step's impulses on those rows join the right-hand side
        // docs/method.md §3, eq. (5) (eliminate), once per step, and eq. (6) (substitute) for the joint
        // impulses of the free velocities and the carried extra impulses, fused into one pass.
        mSolver->factorAndSolve(mRows, mRhs, mSolution);
        clock.lap(StepStage::Factor);
        solveContactImpulses(state); // the extra rows on top (§5)
        clock.lap(StepStage::Solve);
    } while (!actuatorsWithinLimits(state));
    integratePositions(state);
    removePenetration(state);
    stabilizeJoints(state); // leaves mRowsAfter at the end-of-step pose
    carryAngularMomentum(mModel, mPrincipal, mRows, state);
    trackJointAngles(mModel, state);
    state.time += mDt;
    ++state.step;
    checkState(state, "end of step");
    mEndPose = state.bodies;
    mEndRowsValid = true;
    clock.lap(StepStage::Integrate);
}

// Rows at the start-of-step pose: the last step's drift correction evaluated them at its end
// pose, which is this one unless the state was changed between steps (bit-identical either way).
void Simulator::rowsAtStart(const State& state)
{
    if (mEndRowsValid && samePose(state, mEndPose))
    {
        std::swap(mRows, mRowsAfter);
    }
    else
    {
        assembleRows(mModel, mLayout, state, driveStep(), mRows, mActuation.gains());
    }
    mEndRowsValid = false;
}

bool Simulator::samePose(const State& state, const std::vector<BodyState>& pose) const
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        const BodyState& now = state.bodies[i];
        const BodyState& then = pose[i];
        if (now.position_W != then.position_W || now.orientation_WB.coeffs() != then.orientation_WB.coeffs())
        {
            return false;
        }
    }
    return true;
}

// Second order (RATTLE): kick h/2 g; impulses at q_n (joints, contacts) that the Newton
// iteration of stabilizeJoints completes into the multiplier putting q_{n+1} on the constraint
// manifold; drift; kick h/2 g; velocity projection at q_{n+1}.
bool Simulator::stepRattle(State& state)
{
    StageClock clock(mStats.seconds);
    checkState(state, "start of step");
    mActuation.beginStep();
    detectContacts(state);
    clock.lap(StepStage::Detect);
    computeFreeVelocities(state, 0.5 * mDt);
    keepFreeVelocities(state);
    do
    {
        factorAtStart(state); // docs/method.md §3, eq. (5), shared with the last step's projection
        clock.lap(StepStage::Factor);
        buildExtraRows(state);
        recordStartDefects(state);
        setMomentumRhs(state, state.time + 0.5 * mDt);
        mProblem.carryImpulses(mRhs);
        mSolver->solve(mRhs, mSolution); // §3 step 3: joint impulses of the free velocities
        solveContactImpulses(state);
        clock.lap(StepStage::Solve);
    } while (!actuatorsWithinLimits(state));
    integratePositions(state); // drift: x += h v, R by the free rotation at constant L
    removePenetration(state);
    if (!stabilizeJoints(state)) // Newton on C(q_{n+1}) = 0, impulses along J(q_n)^T
    {
        return false;
    }
    carryAngularMomentum(mModel, mPrincipal, mRows, state); // w_{n+1} = I_W(R_{n+1})^-1 L
    kickByGravity(state, 0.5 * mDt);
    mActuation.applyForces(state, state.time + 0.5 * mDt, state.time + mDt);
    projectVelocities(state); // J(q_{n+1}) u_{n+1} = 0, factored for the next step
    trackJointAngles(mModel, state);
    state.time += mDt;
    ++state.step;
    checkState(state, "end of step");
    clock.lap(StepStage::Integrate);
    return true;
}

// Rows and factorization at the start-of-step pose; the rattle scheme's last projection left
// them factored at exactly this pose unless the state was changed between steps.
void Simulator::factorAtStart(const State& state)
{
    if (!(mFactoredPoseValid && samePose(state, mFactoredPose)))
    {
        assembleRows(mModel, mLayout, state, driveStep(), mRows, mActuation.gains());
        mSolver->factor(mRows);
    }
    mFactoredPoseValid = false;
}

// The second half of RATTLE's velocity update: u_{n+1} = u - M^-1 J^T mu with J(q_{n+1}) u_{n+1} = 0,
// M and J at q_{n+1} (the rows the last Newton iteration assembled). Loop joints join as
// bilateral rows; contacts and limits that pushed in this step's impulse stage as one-sided
// normal rows with target 0 (they may separate, never pull).
void Simulator::projectVelocities(State& state)
{
    std::swap(mRows, mRowsAfter);
    for (;;)
    {
        mSolver->factor(mRows);
        buildLoopBlocks(mModel, mLayout, mRows, mLoopBlocks);
        mEndBlocks = mLoopBlocks;
        for (const ExtraBlock& block : mProblem.blocks())
        {
            if (block.kind == ExtraBlock::Kind::Drive)
            {
                if (block.actuator < 0)
                {
                    mEndBlocks.push_back(block); // joint friction acts in both halves of the step
                }
                continue;
            }
            if (block.kind != ExtraBlock::Kind::Loop && mProblem.impulses()(block.offset) > 0.0)
            {
                ExtraBlock normal = block;
                normal.count = block.kind == ExtraBlock::Kind::Contact ? block.count : 1;
                normal.target.setZero();
                mEndBlocks.push_back(normal);
            }
        }
        // Actuators at their limits act in the second half too, with their targets at its end.
        mActuation.appendBoundedRows(state, state.time + mDt, driveStep(), mEndBlocks);
        setMomentumRhs(state, state.time + mDt);
        mSolver->solve(mRhs, mCorrection);
        if (!mEndBlocks.empty())
        {
            const int rows = layoutExtraRows(mEndBlocks);
            mSolver->delassus(mEndBlocks, rows, mEndG);
            extraRowVelocities(mEndBlocks, mCorrection, mEndVelocity);
            mEndLambda.setZero(rows);
            coupleRowsByTree(mEndBlocks, mLayout.treeOfBody, mEndCoupling, mTreeRuns);
            solveExtraRows(mEndBlocks, mEndG, mEndVelocity, mOptions.contactSolve, mEndLambda,
                           mProblem.scratch(), &mEndCoupling);
            mSolver->applyExtraImpulses(mEndBlocks, mEndLambda, mCorrection);
        }
        if (mActuation.acceptSolve(mRows, mCorrection, mEndBlocks, mEndLambda, driveStep()))
        {
            break;
        }
        // An actuator went beyond its limit: out of its block, the projection again.
        assembleRows(mModel, mLayout, state, driveStep(), mRows, mActuation.gains());
    }
    mFactoredPose = state.bodies;
    mFactoredPoseValid = true;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W = mCorrection.body[i].head<3>();
            state.bodies[i].angularVelocity_W = mCorrection.body[i].tail<3>();
        }
    }
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        mSolution.joint[k] += mCorrection.joint[k];
    }
}

// The first step's contacts and limit rows tell whether the scene started with bodies deep inside
// each other or a joint beyond its limit (core/failure_hint.h).
void Simulator::recordStartDefects(const State& state)
{
    if (!mStartRecorded)
    {
        mStartDefects = findStartDefects(mProblem.contacts(), mProblem.blocks(), mModel, state);
        mStartRecorded = true;
    }
}

// The hint of a failure at this state: the start defects while their recovery (at most
// penetrationMaxSpeed, penetrationMaxAngularSpeed) could still be under way, with some steps to
// spare, or while they are still there; else a smaller step when a body turned far within the
// failing step.
std::string Simulator::likelyCause(const State& state) const
{
    constexpr double cSpareSteps = 10.0;
    const double recoverySteps =
        cSpareSteps + mStartDefects.overlapM / (mOptions.penetrationMaxSpeed * mDt) +
        mStartDefects.limitExcess /
            (std::min(mOptions.penetrationMaxSpeed, mOptions.penetrationMaxAngularSpeed) * mDt);
    bool stillThere = mStats.maxPenetrationM > cDeepOverlap;
    for (const ExtraBlock& block : mProblem.blocks())
    {
        stillThere =
            stillThere || (block.kind == ExtraBlock::Kind::Limit &&
                           block.source == mStartDefects.limitJoint && block.error(0) > cDeepOverlap);
    }
    double rotation = 0.0;
    int fastest = -1;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        const double turn = mStart[i].angularVelocity_W.norm() * mDt;
        if (!mModel.bodies[i].isStatic && turn > rotation)
        {
            rotation = turn;
            fastest = static_cast<int>(i);
        }
    }
    const bool recovering = stillThere || static_cast<double>(state.step) <= recoverySteps;
    return failureHint(mModel, mStartDefects, recovering, rotation, fastest);
}

void Simulator::checkState(const State& state, const char* where) const
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        const BodyState& s = state.bodies[i];
        const char* quantity = nullptr;
        if (!finite(s.position_W))
        {
            quantity = "position";
        }
        else if (!s.orientation_WB.coeffs().allFinite())
        {
            quantity = "orientation";
        }
        else if (!finite(s.velocity_W) || s.velocity_W.norm() > cMaxSpeed)
        {
            quantity = "velocity";
        }
        else if (!finite(s.angularVelocity_W) || s.angularVelocity_W.norm() > cMaxAngularSpeed)
        {
            quantity = "angular velocity";
        }
        if (quantity != nullptr)
        {
            SimulationFailure failure;
            failure.step = state.step;
            failure.time = state.time;
            failure.where = where;
            failure.body = static_cast<int>(i);
            failure.bodyName = mModel.bodies[i].name;
            failure.quantity = quantity;
            failure.maxSpeed = cMaxSpeed;
            failure.maxAngularSpeed = cMaxAngularSpeed;
            failure.hint = likelyCause(state);
            throw SimulationError(std::move(failure));
        }
    }
}

// u* = u + h M^-1 f over a time h (s): gravity on the centre of mass; no torque. Saves the
// start-of-step poses.
void Simulator::computeFreeVelocities(State& state, double h)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        mStart[i] = state.bodies[i];
    }
    kickByGravity(state, h);
    mActuation.applyForces(state, state.time, state.time + h); // effort actuators, loads
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
    mFactoredPoseValid = false;
    return false;
}

// v += h g for every moving body (h in s).
void Simulator::kickByGravity(State& state, double h)
{
    const Vec3 dv = h * mModel.simulation.gravity;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W += dv;
        }
    }
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
// rows of the factored rows, contacts, limits, joint friction and actuators at their limits.
void Simulator::buildExtraRows(const State& state)
{
    buildLoopBlocks(mModel, mLayout, mRows, mLoopBlocks);
    mStats.extraRows = mProblem.build(state, mStart, mLoopBlocks, mDt, driveStep(), mActuation);
}

// p = M u* for the joint-impulse solve M u' - J^T lambda = M u*, J u' + E lambda = c: c = 0 but
// for the rows of servos and motors in their joints' blocks (targets at tEnd, s).
void Simulator::setMomentumRhs(const State& state, double tEnd)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (mModel.bodies[i].isStatic)
        {
            continue;
        }
        const BodyState& s = state.bodies[i];
        mRhs.body[i].head<3>() = mRows.mass[i] * s.velocity_W;
        mRhs.body[i].tail<3>() = mRows.inertia_W[i] * s.angularVelocity_W;
    }
    for (Vec6& c : mRhs.joint)
    {
        c.setZero();
    }
    mActuation.setRowTargets(state, tEnd, driveStep(), mRhs); // servos and motors in their blocks
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
    mPenetration.apply(state, mStart, mProblem, mSolution, mRows, mPrincipal, mDt, driveStep(), mActuation);
}

// The position update from the start-of-step pose (core/step/positions.h).
void Simulator::integratePositions(State& state)
{
    core::integratePositions(mModel, mStart, mPrincipal, mRows, mDt, mRattleStep, state);
}

// The drift correction of the joints (core/step/drift_correction.h). A joint still apart after it
// is a blow-up: the run stops naming the step, the joint and the gap. False: a rattle step stalled.
bool Simulator::stabilizeJoints(State& state)
{
    const DriftCorrection::Outcome outcome =
        mDrift.run(state, mStart, mPrincipal, mRows, mRowsAfter, mLoopBlocks, mSolution, mDt, driveStep(),
                   mRattleStep, mActuation);
    const JointErrors& errors = mDrift.errors();
    mStats.maxJointErrorM = errors.maxM;
    mStats.maxJointErrorRad = errors.maxRad;
    mStats.stabilizationIterations = mDrift.iterations();
    if (outcome == DriftCorrection::Outcome::CameApart)
    {
        const Joint& joint = mModel.joints[static_cast<std::size_t>(errors.worstJoint)];
        SimulationFailure failure;
        failure.step = state.step;
        failure.time = state.time;
        failure.body = joint.child;
        failure.bodyName = mModel.bodies[static_cast<std::size_t>(joint.child)].name;
        failure.joint = errors.worstJoint;
        failure.jointName = joint.name;
        if (joint.parent != cWorld)
        {
            failure.parentName = mModel.bodies[static_cast<std::size_t>(joint.parent)].name;
        }
        const bool positional = errors.maxM >= errors.maxRad;
        failure.quantity = positional ? "position" : "orientation";
        failure.gap = std::max(errors.maxM, errors.maxRad);
        failure.hint = likelyCause(state);
        throw SimulationError(std::move(failure));
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
