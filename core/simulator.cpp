// core/simulator.cpp: the step pipelines of the first-order (`euler`) and second-order (`rattle`)
// schemes.
#include "core/simulator.h"

#include "core/failure_hint.h"
#include "core/joints/coordinates.h"
#include "core/penetration.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace frontier::core
{

namespace
{
// exp of a rotation vector (rad) as a unit quaternion.
Quat rotationFromVector(const Vec3& theta)
{
    const double angle = theta.norm();
    if (angle < 1e-12)
    {
        return Quat(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
    }
    return Quat(Eigen::AngleAxisd(angle, theta / angle));
}

// Wall time of consecutive stages of one step, into StepStats::seconds.
class StageClock
{
  public:
    explicit StageClock(std::array<double, cStepStages>& out)
        : mOut(out), mLast(std::chrono::steady_clock::now())
    {
    }
    void lap(StepStage stage)
    {
        const auto now = std::chrono::steady_clock::now();
        mOut[static_cast<std::size_t>(stage)] = std::chrono::duration<double>(now - mLast).count();
        mLast = now;
    }

  private:
    std::array<double, cStepStages>& mOut;
    std::chrono::steady_clock::time_point mLast;
};

// Anything beyond these is a blow-up even while still finite.
constexpr double cMaxSpeed = 1e5;        // m/s
constexpr double cMaxAngularSpeed = 1e6; // rad/s

bool finite(const Vec3& v)
{
    return v.allFinite();
}

// One-sided rows that keep bodies apart (contacts, limits): what removePenetration projects.
bool pushesApart(const ExtraBlock& block)
{
    return block.kind == ExtraBlock::Kind::Contact || block.kind == ExtraBlock::Kind::Limit;
}
} // namespace

Simulator::Simulator(const Model& model, const StepOptions& options, ContactSource* contacts)
    : mModel(model), mOptions(options), mContactSource(contacts), mLayout(buildFrontierLayout(model)),
      mActuation(model, mLayout),
      mSolver(makeSolver(model.simulation.solver, model.simulation.pgsIterations)), mDt(model.simulation.dt)
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
    for (std::size_t k = 0; k < nj; ++k)
    {
        const Joint& joint = model.joints[k];
        if (joint.limits && (joint.type == JointType::Revolute || joint.type == JointType::Prismatic))
        {
            mLimitedJoints.push_back(static_cast<int>(k));
        }
        if (joint.friction > 0.0 && !jointCoordinates(joint.type).empty())
        {
            mFrictionJoints.push_back(static_cast<int>(k));
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
    const bool penetrationCapped = mPenetrationCapped;
    if (!stepRattle(state))
    {
        // RATTLE's position iteration stalled (very fast rotation within the step): this step is
        // taken again from its start by the robust first-order scheme.
        state = mStepStart;
        mPenetrationCapped = penetrationCapped;
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
        carryImpulses(); // the last step's impulses on those rows join the right-hand side
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
    carryAngularMomentum(state);
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
        carryImpulses();
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
    carryAngularMomentum(state); // w_{n+1} = I_W(R_{n+1})^-1 L
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
        buildLoopRows(mRows);
        mEndBlocks = mLoopBlocks;
        for (const ExtraBlock& block : mExtra)
        {
            if (block.kind == ExtraBlock::Kind::Drive)
            {
                if (block.actuator < 0)
                {
                    mEndBlocks.push_back(block); // joint friction acts in both halves of the step
                }
                continue;
            }
            if (block.kind != ExtraBlock::Kind::Loop && mExtraLambda(block.offset) > 0.0)
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
            solveExtraRows(mEndBlocks, mEndG, mEndVelocity, mOptions.contactSolve, mEndLambda, mExtraScratch,
                           &mEndCoupling);
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
        mStartDefects = findStartDefects(mContacts, mExtra, mModel, state);
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
    for (const ExtraBlock& block : mExtra)
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
            std::ostringstream msg;
            msg << "simulation blew up at step " << state.step << " (t = " << state.time << " s, " << where
                << "): body '" << mModel.bodies[i].name << "' has a non-finite or runaway " << quantity
                << " (limits " << cMaxSpeed << " m/s, " << cMaxAngularSpeed << " rad/s)"
                << likelyCause(state);
            throw SimulationError(msg.str());
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
        mActuation.acceptSolve(mRows, mSolution, mExtra, mExtraLambda, driveStep()))
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
    mContacts.clear();
    if (mContactSource != nullptr)
    {
        mContactSource->detect(state, mContacts);
    }
    mStats.contacts = static_cast<int>(mContacts.size());
    mStats.maxPenetrationM = 0.0;
    for (const Contact& contact : mContacts)
    {
        mStats.maxPenetrationM = std::max(mStats.maxPenetrationM, contact.depth);
    }
}

// Contact rows with their targets (restitution, or the gap that may close this step), the rows of
// loop-closing joints, and limit rows near a limit. Evaluated at the start-of-step pose.
void Simulator::buildExtraRows(const State& state)
{
    mExtra.clear();
    const double e = mModel.contact.restitution;
    for (std::size_t c = 0; c < mContacts.size(); ++c)
    {
        const Contact& contact = mContacts[c];
        // A gap that the bodies cannot close within cSpeculativeSteps steps, even moving straight
        // at each other at their relative speed plus this step's gravity, needs no row: only the
        // rows a scene needs are built (resting bodies near each other add none).
        constexpr double cSpeculativeSteps = 3.0;
        if (contact.depth < 0.0)
        {
            Vec3 relative = Vec3::Zero(); // velocity of B's point relative to A's (m/s)
            const BodyState& a = mStart[static_cast<std::size_t>(contact.bodyA)];
            relative -= a.velocity_W + a.angularVelocity_W.cross(contact.point_W - a.position_W);
            if (contact.bodyB >= 0 && !mModel.bodies[static_cast<std::size_t>(contact.bodyB)].isStatic)
            {
                const BodyState& b = mStart[static_cast<std::size_t>(contact.bodyB)];
                relative += b.velocity_W + b.angularVelocity_W.cross(contact.point_W - b.position_W);
            }
            const double closing = relative.norm() + mModel.simulation.gravity.norm() * mDt;
            if (closing * mDt * cSpeculativeSteps < -contact.depth)
            {
                continue;
            }
        }
        ExtraBlock& block =
            appendContactBlock(mModel, state, contact, mModel.contact.friction, static_cast<int>(c), mExtra);
        // Normal velocity before this step's gravity (m/s); < 0 approaching.
        double approach =
            block.J_A.row(0).dot((Vec6() << mStart[static_cast<std::size_t>(block.bodyA)].velocity_W,
                                  mStart[static_cast<std::size_t>(block.bodyA)].angularVelocity_W)
                                     .finished());
        if (block.bodyB >= 0)
        {
            const BodyState& b = mStart[static_cast<std::size_t>(block.bodyB)];
            approach += block.J_B.row(0).dot((Vec6() << b.velocity_W, b.angularVelocity_W).finished());
        }
        const bool closes = contact.depth >= 0.0 || approach * mDt <= contact.depth;
        if (!closes)
        {
            block.target(0) = contact.depth / mDt; // speculative: may approach by the gap, no more
        }
        else if (approach < -mOptions.restitutionSpeed)
        {
            block.target(0) = -e * approach; // Newton restitution
        }
    }
    buildLoopRows(mRows);
    for (const ExtraBlock& loop : mLoopBlocks)
    {
        mExtra.push_back(loop);
    }
    for (int joint : mLimitedJoints)
    {
        const std::size_t before = mExtra.size();
        appendLimitBlocks(mModel, state, joint, mOptions.limitMargin, mExtra);
        if (mExtra.size() > before && mExtra.back().error(0) < 0.0)
        {
            mExtra.back().target(0) = mExtra.back().error(0) / mDt; // the gap to the limit
        }
    }
    for (int joint : mFrictionJoints)
    {
        appendFrictionBlocks(mModel, state, joint, driveStep(), mExtra);
    }
    mActuation.appendBoundedRows(state, state.time + driveStep(), driveStep(), mExtra);
    mStats.extraRows = layoutExtraRows(mExtra);
}

// Loop-closing joints: all their rows bilateral, velocity target 0.
void Simulator::buildLoopRows(const RowSystem& rows)
{
    mLoopBlocks.clear();
    for (int k : mLayout.loopJoints)
    {
        const Joint& joint = mModel.joints[static_cast<std::size_t>(k)];
        const JointRows& r = rows.joints[static_cast<std::size_t>(k)];
        ExtraBlock block;
        block.kind = ExtraBlock::Kind::Loop;
        block.count = r.count;
        block.bodyA = jointToWorld(mModel, joint) ? -1 : joint.parent;
        block.bodyB = joint.child;
        block.J_A = r.J_a;
        block.J_B = r.J_b;
        block.error = r.error;
        const int drives = r.count - r.constraintRows;
        block.compliance.segment(r.constraintRows, drives) = r.compliance.segment(r.constraintRows, drives);
        block.source = k;
        mLoopBlocks.push_back(block);
    }
    layoutExtraRows(mLoopBlocks);
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

// The last step's impulses on this step's rows (warmStart), and their momentum J_x^T lambda in
// the right-hand side of the step's first solve: that solve then gives u(lambda_carried) =
// H^-1 (M u* + J_x^T lambda_carried) exactly, so a step whose carried impulses still hold needs no
// second O(n) solve, and the others apply only the change of the impulses.
void Simulator::carryImpulses()
{
    mExtraLambda.setZero(mStats.extraRows);
    mWarm = mStats.extraRows > 0 && warmStart();
    mBaseLambda = mExtraLambda;
    if (mWarm)
    {
        ImpulseSolver::addExtraImpulses(mExtra, mExtraLambda, mRhs);
    }
}

// solution += H^-1 J_x^T (lambda - lambda_carried): from u(lambda_carried) to u(lambda).
void Simulator::applyImpulseChange(BlockVector& solution)
{
    mImpulseChange = mExtraLambda - mBaseLambda;
    mSolver->applyExtraImpulses(mExtra, mImpulseChange, solution);
}

// With the tree's solution u(lambda_carried) (mSolution, u_free when nothing was carried), the
// extra rows in constraint space: v = J_x u_free + G lambda with the complementarity conditions,
// and u' = u_free + H^-1 J_x^T lambda; then the state takes u'.
void Simulator::solveContactImpulses(State& state)
{
    mStats.contactSweeps = 0;
    mStats.contactRoute = ContactRoute::None;
    mDelassusValid = false;
    if (mDelassusAge >= 0 && mDelassusAge <= cMaxDelassusAge)
    {
        ++mDelassusAge; // stops one past the limit
    }
    if (mStats.extraRows > 0)
    {
        if (mWarm && lastImpulsesStillHold())
        {
            mStats.contactRoute = ContactRoute::Carried;
        }
        else if (mWarm && mOptions.reuseDelassus && solveWithLastDelassus())
        {
            mStats.contactRoute = ContactRoute::Reused;
        }
        else
        {
            mStats.contactRoute = ContactRoute::Built;
            buildDelassus();
            if (mWarm)
            {
                mExtraScratch.velocity = mExtraVelocity; // exact at the impulses reached so far
            }
            else
            {
                extraRowVelocities(mExtra, mSolution, mExtraScratch.velocity); // lambda = 0
            }
            mStats.contactSweeps += solveExtraRowsFrom(mExtra, mG, mOptions.contactSolve, mExtraLambda,
                                                       mExtraScratch, &mCoupling, mDelassusVersion)
                                        .sweeps;
            applyImpulseChange(mSolution);
        }
    }
    rememberImpulses();
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W = mSolution.body[i].head<3>();
            state.bodies[i].angularVelocity_W = mSolution.body[i].tail<3>();
        }
    }
}

// Resting contact: the impulses carried over from the last step often still meet every
// condition of this step to the solve's tolerance (core::conditionResidual). The step's first
// solve included them (carryImpulses), so the check is v = J_x u(lambda_carried), without G; when
// they hold, the step keeps them (0 sweeps, the same criterion the Gauss-Seidel stops on).
bool Simulator::lastImpulsesStillHold()
{
    extraRowVelocities(mExtra, mSolution, mExtraVelocity);
    return conditionsMet(mExtra, mExtraVelocity, mExtraLambda, mOptions.contactSolve.velocityTolerance);
}

// The Delassus matrix of this step's extra rows and their coupling by tree, once per step and
// only when needed. The rows it was built for are remembered for solveWithLastDelassus.
void Simulator::buildDelassus()
{
    if (!mDelassusValid)
    {
        mSolver->delassus(mExtra, mStats.extraRows, mG);
        ++mDelassusVersion; // the Gauss-Seidel's pivots of the last G no longer hold
        coupleRowsByTree(mExtra, mLayout.treeOfBody, mCoupling, mTreeRuns);
        mDelassusValid = true;
        mDelassusRows.clear();
        for (const ExtraBlock& block : mExtra)
        {
            mDelassusRows.push_back(rowKey(block));
        }
        mDelassusAge = 0;
    }
}

Simulator::RowKey Simulator::rowKey(const ExtraBlock& block) const
{
    RowKey key{block.kind,   block.count,    block.bodyA,  block.bodyB,
               block.source, block.actuator, Vec3::Zero(), Vec6::Zero()};
    if (block.kind == ExtraBlock::Kind::Contact)
    {
        const Contact& c = mContacts[static_cast<std::size_t>(block.source)];
        key.source = -1; // contact indices are not stable; the point and normal are compared
        key.point_W = c.point_W;
        key.direction.head<3>() = c.normal_W;
    }
    else
    {
        // Loops and limits by joint; the first row tells which side a limit is on (its sign
        // flips between the lower and the upper limit).
        key.direction = (block.bodyA >= 0 ? block.J_A : block.J_B).row(0).transpose();
    }
    return key;
}

// The same rows as when mG was built, each contact within cReuseDistance of its point then.
bool Simulator::sameRowsAsLastDelassus() const
{
    constexpr double cReuseDistance = 1e-3; // m
    if (mDelassusAge < 0 || mDelassusAge > cMaxDelassusAge || mDelassusRows.size() != mExtra.size())
    {
        return false;
    }
    for (std::size_t b = 0; b < mExtra.size(); ++b)
    {
        const RowKey now = rowKey(mExtra[b]);
        const RowKey& then = mDelassusRows[b];
        if (now.kind != then.kind || now.count != then.count || now.bodyA != then.bodyA ||
            now.bodyB != then.bodyB || now.source != then.source)
        {
            return false;
        }
        const bool contact = now.kind == ExtraBlock::Kind::Contact;
        if (contact && ((now.point_W - then.point_W).squaredNorm() > cReuseDistance * cReuseDistance ||
                        now.direction.dot(then.direction) < 0.999))
        {
            return false;
        }
        if (!contact && !sameJointRows(now, then))
        {
            return false;
        }
    }
    return true;
}

bool Simulator::sameJointRows(const RowKey& now, const RowKey& then)
{
    return now.kind == then.kind && now.source == then.source && now.actuator == then.actuator &&
           now.direction.dot(then.direction) > 0.0;
}

// Resting contact whose carried-over impulses just miss the tolerance: the Delassus matrix G~ of
// a recent step (same rows, contacts within a millimetre) stands in for this step's G in a defect
// correction. With the exact row velocities v(lambda) = J_x (u_free + H^-1 J_x^T lambda) (one
// O(n) solve), Gauss-Seidel solves v(lambda) + G~ (lambda' - lambda) against the contact
// conditions; the result is accepted only when the exact velocities meet every condition to the
// solve's tolerance (core::conditionResidual), the criterion of the full solve. Building G costs
// a path sweep per body and a product per pair of bodies; a round here costs one O(n) solve and a
// few sweeps. False (after cReuseRounds) leaves the full solve to the caller.
//
// Reads mExtraVelocity as lastImpulsesStillHold leaves it (the exact row velocities at the
// carried-over impulses), so it runs only after that check has failed. When it gives up, the
// full solve starts from the impulses reached here (one-sided and inside the cone), and the
// step's sweep count includes both.
bool Simulator::solveWithLastDelassus()
{
    constexpr int cReuseRounds = 2;
    if (!sameRowsAsLastDelassus())
    {
        return false;
    }
    ExtraSolveSettings settings = mOptions.contactSolve;
    settings.velocityTolerance *= 0.9; // margin for the difference between G~ and G
    for (int round = 0; round < cReuseRounds; ++round)
    {
        mExtraScratch.velocity = mExtraVelocity; // v(lambda), then v(lambda) + G~ (lambda' - lambda)
        const ExtraSolveStats sweeps = solveExtraRowsFrom(mExtra, mG, settings, mExtraLambda, mExtraScratch,
                                                          &mCoupling, mDelassusVersion);
        mStats.contactSweeps += sweeps.sweeps;
        mTrial = mSolution;
        applyImpulseChange(mTrial);
        extraRowVelocities(mExtra, mTrial, mExtraVelocity);
        if (conditionsMet(mExtra, mExtraVelocity, mExtraLambda, mOptions.contactSolve.velocityTolerance))
        {
            std::swap(mSolution, mTrial);
            return true;
        }
        if (!sweeps.converged)
        {
            return false; // Gauss-Seidel did not converge even on G~: a hard step, G is built
        }
    }
    return false;
}

// Contacts persist from step to step: a contact between the same bodies within cWarmDistance of
// one of the last step's starts from that one's impulse, so resting contact needs few sweeps.
// Loop and limit blocks start from their joint's impulse of the last step. True when some
// impulse was carried over.
bool Simulator::warmStart()
{
    bool any = false;
    constexpr double cWarmDistance = 5e-3; // m
    for (const ExtraBlock& block : mExtra)
    {
        if (block.kind != ExtraBlock::Kind::Contact)
        {
            // Loops and limits by joint, a limit only on the same side as last step.
            const RowKey key = rowKey(block);
            for (const JointImpulse& previous : mPreviousJointImpulses)
            {
                if (sameJointRows(key, previous.key))
                {
                    mExtraLambda.segment(block.offset, block.count) = previous.lambda.head(block.count);
                    any = any || previous.lambda.head(block.count).cwiseAbs().maxCoeff() > 0.0;
                    break;
                }
            }
            continue;
        }
        const Contact& c = mContacts[static_cast<std::size_t>(block.source)];
        double best = cWarmDistance * cWarmDistance;
        int match = -1;
        // The last step's contacts of the same body pair (mPreviousOrder: by pair, then index).
        const std::uint64_t pair = bodyPairKey(c);
        const auto first = std::lower_bound(mPreviousOrder.begin(), mPreviousOrder.end(),
                                            std::pair<std::uint64_t, int>(pair, -1));
        for (auto it = first; it != mPreviousOrder.end() && it->first == pair; ++it)
        {
            const std::size_t p = static_cast<std::size_t>(it->second);
            const Contact& q = mPreviousContacts[p];
            const double d = (q.point_W - c.point_W).squaredNorm();
            if (d < best && q.normal_W.dot(c.normal_W) > 0.99)
            {
                best = d;
                match = static_cast<int>(p);
            }
        }
        if (match >= 0)
        {
            mExtraLambda.segment(block.offset, block.count) =
                mPreviousImpulses[static_cast<std::size_t>(match)].head(block.count);
            any = any || mExtraLambda(block.offset) > 0.0;
        }
    }
    return any;
}

std::uint64_t Simulator::bodyPairKey(const Contact& c)
{
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.bodyA)) << 32) |
           static_cast<std::uint32_t>(c.bodyB);
}

void Simulator::rememberImpulses()
{
    mPreviousContacts = mContacts;
    mPreviousOrder.resize(mContacts.size());
    for (std::size_t k = 0; k < mContacts.size(); ++k)
    {
        mPreviousOrder[k] = {bodyPairKey(mContacts[k]), static_cast<int>(k)};
    }
    std::sort(mPreviousOrder.begin(), mPreviousOrder.end()); // by pair, then index
    mPreviousImpulses.assign(mContacts.size(), Vec3::Zero());
    mPreviousJointImpulses.clear();
    for (const ExtraBlock& block : mExtra)
    {
        if (block.kind == ExtraBlock::Kind::Contact)
        {
            mPreviousImpulses[static_cast<std::size_t>(block.source)].head(block.count) =
                mExtraLambda.segment(block.offset, block.count);
        }
        else
        {
            JointImpulse previous{rowKey(block), Vec6::Zero()};
            previous.lambda.head(block.count) = mExtraLambda.segment(block.offset, block.count);
            mPreviousJointImpulses.push_back(previous);
        }
    }
}

// Moves positions by a displacement (m, rad) without touching velocities.
void Simulator::displacePositions(State& state, const BlockVector& displacement)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (mModel.bodies[i].isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        s.position_W += displacement.body[i].head<3>();
        s.orientation_WB =
            (rotationFromVector(displacement.body[i].tail<3>()) * s.orientation_WB).normalized();
        mStart[i].position_W += displacement.body[i].head<3>();
        mStart[i].orientation_WB =
            (rotationFromVector(displacement.body[i].tail<3>()) * mStart[i].orientation_WB).normalized();
    }
}

// Penetration beyond the slop (contacts) or past a limit, predicted at the end of the step, is
// removed by a displacement H^-1 J^T mu (through the joints, so they stay together) with mu >= 0:
// a position projection that leaves velocities, and so kinetic energy, unchanged. Loop joints
// ride along as bilateral rows with target 0. It is bounded (core/penetration.h): rows the joints
// hold are left alone, and a step moves no body faster than penetrationMaxSpeed nor turns it
// faster than penetrationMaxAngularSpeed (deep overlaps come out over several steps); a
// displacement that turns bodies puts their joints back by displacement too (restoreJoints).
void Simulator::removePenetration(State& state)
{
    const bool wasCapped = mPenetrationCapped;
    mPenetrationCapped = false; // set again below when this step's displacement is capped
    if (mStats.extraRows == 0)
    {
        return;
    }
    // Overlap predicted after this step (m or rad): now minus h times the separating speed; the
    // part beyond the slop (contacts) or the limit is removed. Most steps have none.
    extraRowVelocities(mExtra, mSolution, mExtraVelocity);
    auto excessOf = [&](const ExtraBlock& block)
    {
        const double predicted = block.error(0) - mDt * mExtraVelocity(block.offset);
        return predicted - (block.kind == ExtraBlock::Kind::Contact ? mOptions.penetrationSlop : 0.0);
    };
    bool any = false;
    for (const ExtraBlock& block : mExtra)
    {
        any = any || (pushesApart(block) && excessOf(block) > 0.0);
    }
    if (!any)
    {
        return;
    }
    buildDelassus();
    std::vector<ExtraBlock>& blocks = mPenetrationBlocks;
    std::vector<int>& rows = mPenetrationRows;
    blocks.clear();
    rows.clear();
    any = false;
    for (const ExtraBlock& block : mExtra)
    {
        if (block.kind == ExtraBlock::Kind::Drive)
        {
            continue; // joint friction has no position to restore
        }
        ExtraBlock p = block;
        p.target.setZero();
        if (block.kind != ExtraBlock::Kind::Loop)
        {
            // A row the joints hold: no displacement they allow moves it (its G_ii is round-off).
            if (heldByJoints(block, mG(block.offset, block.offset), mRows, mPrincipal,
                             mOptions.penetrationHeldRatio))
            {
                continue;
            }
            p.count = 1;
            p.target(0) = std::max(0.0, excessOf(block));
            any = any || p.target(0) > 0.0;
        }
        for (int k = 0; k < p.count; ++k)
        {
            rows.push_back(block.offset + k);
        }
        blocks.push_back(p);
    }
    if (!any)
    {
        return;
    }
    const int n = layoutExtraRows(blocks);
    mPenetrationG = mG(rows, rows); // the normal, limit and loop rows of the step's G
    mPenetrationFree.setZero(n);
    mPenetrationImpulse.setZero(n);
    ExtraSolveSettings settings = mOptions.contactSolve;
    settings.velocityTolerance *= mDt; // here the rows are displacements (m), one step's worth
    coupleRowsByTree(blocks, mLayout.treeOfBody, mPenetrationCoupling, mTreeRuns);
    solveExtraRows(blocks, mPenetrationG, mPenetrationFree, settings, mPenetrationImpulse, mExtraScratch,
                   &mPenetrationCoupling);
    mCorrection.setZero();
    mSolver->applyExtraImpulses(blocks, mPenetrationImpulse, mCorrection);
    const double scale = displacementScale(mModel, mCorrection, mOptions.penetrationMaxSpeed * mDt,
                                           mOptions.penetrationMaxAngularSpeed * mDt);
    if (scale < 1.0)
    {
        for (Vec6& d : mCorrection.body)
        {
            d *= scale;
        }
    }
    // A recovery (its capped steps, and the one that finishes it) keeps the joints by displacement.
    const bool recovering = scale < 1.0 || wasCapped;
    mPenetrationCapped = scale < 1.0;
    if (recovering || largestRotation(mModel, mCorrection) > cRestoreRotation)
    {
        restoreJoints(state);
        return;
    }
    displacePositions(state, mCorrection);
}

// Applies the penetration displacement (mCorrection) and puts the joints back as they were. The
// displacement keeps them to first order only: turning a body by theta leaves a joint at lever L
// about theta^2 L / 2 apart, which stabilizeJoints would remove with a velocity (C / h), adding
// kinetic energy. Here the tree joints' conditions are driven back to their values before the
// displacement by further displacements H^-1 J^T nu (J d = -(C - C_before)), on the step's
// factorization; velocities are not touched. Loop joints are left to stabilizeJoints.
void Simulator::restoreJoints(State& state)
{
    constexpr int cRestoreIterations = 10;
    assembleRows(mModel, mLayout, state, driveStep(), mRowsAfter, mActuation.gains());
    mJointErrorBefore.resize(mModel.joints.size());
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        mJointErrorBefore[k] = mRowsAfter.joints[k].error;
    }
    displacePositions(state, mCorrection);
    for (int iteration = 0; iteration < cRestoreIterations; ++iteration)
    {
        assembleRows(mModel, mLayout, state, driveStep(), mRowsAfter, mActuation.gains());
        double worst = 0.0;
        for (std::size_t k = 0; k < mModel.joints.size(); ++k)
        {
            const JointRows& r = mRowsAfter.joints[k];
            mRhs.joint[k] = -(r.error - mJointErrorBefore[k]);
            if (!std::binary_search(mLayout.loopJoints.begin(), mLayout.loopJoints.end(),
                                    static_cast<int>(k)))
            {
                worst = std::max(worst, mRhs.joint[k].head(r.count).cwiseAbs().maxCoeff());
            }
        }
        if (worst <= mOptions.stabilizationTolerance)
        {
            break;
        }
        for (Vec6& p : mRhs.body)
        {
            p.setZero();
        }
        mSolver->solve(mRhs, mCorrection);
        displacePositions(state, mCorrection);
    }
}

// x_{n+1} = x_n + h v_{n+1}, from the start-of-step pose. Rotation: euler R_{n+1} = exp(h w) R_n;
// rattle the free rigid-body rotation at the world angular momentum L = I_W(R_n) w.
void Simulator::integratePositions(State& state)
{
    const bool rattle = mRattleStep;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (mModel.bodies[i].isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        s.position_W = mStart[i].position_W + mDt * s.velocity_W;
        s.orientation_WB =
            rattle ? rotateFreely(mStart[i].orientation_WB, mPrincipal[i],
                                  mRows.inertia_W[i] * s.angularVelocity_W, mDt)
                   : (rotationFromVector(mDt * s.angularVelocity_W) * mStart[i].orientation_WB).normalized();
    }
}

void Simulator::measureJointErrors(const RowSystem& rows)
{
    mStats.maxJointErrorM = 0.0;
    mStats.maxJointErrorRad = 0.0;
    double worst = -1.0;
    for (std::size_t k = 0; k < rows.joints.size(); ++k)
    {
        const JointRows& r = rows.joints[k];
        for (int row = 0; row < r.count; ++row)
        {
            const double error = std::abs(r.error(row));
            double& slot = row < r.positionRows ? mStats.maxJointErrorM : mStats.maxJointErrorRad;
            slot = std::max(slot, error);
            if (error > worst)
            {
                worst = error;
                mWorstJoint = static_cast<int>(k);
            }
        }
    }
}

// SHAKE-type projection: impulses along J^T that bring C(q_{n+1}) to zero. Each iteration solves
// [M J^T; J 0][du; -dlambda] = [0; -C/h] and moves velocities by du and positions by h du. The
// first iterations reuse the step's factorization (quasi-Newton: J at the start of the step stands
// for J at the end); when an iteration contracts the error by less than cSlowContraction
// (fast rotation, thin bodies, large steps), the system is re-factored at the current
// configuration (once per step: re-factoring again made convergence worse in tests). A joint
// still apart by more than cJointBlowUp after the last iteration is a
// blow-up: the run stops naming the step, the joint and the gap, instead of going on with garbage.
bool Simulator::stabilizeJoints(State& state)
{
    constexpr double cSlowContraction = 0.1;
    constexpr double cJointBlowUp = 1e-3; // m or rad
    mStats.stabilizationIterations = 0;
    double previous = std::numeric_limits<double>::infinity();
    bool loopsFactored = false;
    bool refactored = false;
    // rattle: the quasi-Newton iteration keeps RATTLE's impulse direction J(q_n)^T (so the step is
    // the symplectic map) and is never re-factored; when it stalls (contraction worse than
    // cRattleStall, or not converged after cRattleIterations: very fast rotation within the
    // step), it reports false and the step is taken again by the first-order scheme.
    constexpr double cRattleStall = 0.5;
    constexpr int cRattleIterations = 12;
    const bool rattle = mRattleStep;
    mLoopCorrection.setZero(mLoopBlocks.empty() ? 0 : mLoopBlocks.back().offset + mLoopBlocks.back().count);
    for (int iteration = 0;; ++iteration)
    {
        assembleRows(mModel, mLayout, state, driveStep(), mRowsAfter, mActuation.gains());
        measureJointErrors(mRowsAfter);
        const double error = std::max(mStats.maxJointErrorM, mStats.maxJointErrorRad);
        if (error <= mOptions.stabilizationTolerance)
        {
            break;
        }
        if (rattle && (error > cRattleStall * previous || iteration >= cRattleIterations))
        {
            return false;
        }
        if (iteration >= mOptions.stabilizationIterations)
        {
            if (error > cJointBlowUp)
            {
                const Joint& joint = mModel.joints[static_cast<std::size_t>(mWorstJoint)];
                const std::string parent =
                    joint.parent == cWorld
                        ? std::string("the world")
                        : "'" + mModel.bodies[static_cast<std::size_t>(joint.parent)].name + "'";
                const bool positional = mStats.maxJointErrorM >= mStats.maxJointErrorRad;
                std::ostringstream msg;
                msg << "simulation blew up at step " << state.step << " (t = " << state.time << " s): body '"
                    << mModel.bodies[static_cast<std::size_t>(joint.child)].name << "' came off " << parent
                    << " at joint '" << joint.name << "': joint " << (positional ? "position" : "orientation")
                    << " error " << error << (positional ? " m" : " rad")
                    << " after the correction did not converge" << likelyCause(state);
                throw SimulationError(msg.str());
            }
            break;
        }
        if (!refactored && error > cSlowContraction * previous)
        {
            refactored = true;
            mRowsRefactored = mRowsAfter;
            mSolver->factor(mRowsRefactored);
            buildLoopRows(mRowsRefactored);
            loopsFactored = false;
        }
        if (!mLoopBlocks.empty() && !loopsFactored)
        {
            // Loop rows join the projection exactly: their Delassus block, once per factorization.
            mSolver->delassus(mLoopBlocks, layoutExtraRows(mLoopBlocks), mLoopG);
            addLoopCompliance();
            mLoopLdlt.compute(mLoopG);
            loopsFactored = true;
        }
        mLoopError.resize(mLoopG.rows());
        for (const ExtraBlock& loop : mLoopBlocks)
        {
            mLoopError.segment(loop.offset, loop.count) =
                mRowsAfter.joints[static_cast<std::size_t>(loop.source)].error.head(loop.count);
        }
        previous = error;
        mStats.stabilizationIterations = iteration + 1;
        for (Vec6& p : mRhs.body)
        {
            p.setZero();
        }
        for (std::size_t k = 0; k < mModel.joints.size(); ++k)
        {
            mRhs.joint[k] = -mRowsAfter.joints[k].error / mDt;
        }
        mSolver->solve(mRhs, mCorrection);
        if (!mLoopBlocks.empty())
        {
            correctLoops();
        }
        for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
        {
            if (!mModel.bodies[i].isStatic)
            {
                state.bodies[i].velocity_W += mCorrection.body[i].head<3>();
                state.bodies[i].angularVelocity_W += mCorrection.body[i].tail<3>();
            }
        }
        for (std::size_t k = 0; k < mModel.joints.size(); ++k)
        {
            mSolution.joint[k] += mCorrection.joint[k];
        }
        integratePositions(state);
    }
    return true;
}

// Loop rows in the projection: the tree correction du_0 leaves J_loop du_0 + C_loop / h; the loop
// impulse mu = G_loop^-1 (-C_loop / h - J_loop du_0) removes it, and du += H^-1 J_loop^T mu.
void Simulator::correctLoops()
{
    extraRowVelocities(mLoopBlocks, mCorrection, mExtraVelocity);
    const Eigen::VectorXd residual = -mLoopError / mDt - mExtraVelocity;
    const Eigen::VectorXd mu = mLoopLdlt.solve(residual);
    mSolver->applyExtraImpulses(mLoopBlocks, mu, mCorrection);
    mLoopCorrection += mu;
}

// Drive rows of loop joints are compliant in the projection too: G_loop gains E on their diagonal.
void Simulator::addLoopCompliance()
{
    for (const ExtraBlock& loop : mLoopBlocks)
    {
        mLoopG.diagonal().segment(loop.offset, loop.count) += loop.compliance.head(loop.count);
    }
}

// The angular momentum I_W(R_n) w that the step gave each body is kept through the rotation:
// w_{n+1} = I_W(R_{n+1})^-1 I_W(R_n) w.
void Simulator::carryAngularMomentum(State& state)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        const Body& body = mModel.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        const Vec3 momentum = mRows.inertia_W[i] * s.angularVelocity_W;
        // I_W^-1 L in the principal frame P of the new orientation: w = R_WP diag(1/I) R_WP^T L.
        const Quat toWorld = s.orientation_WB * mPrincipal[i].rotation_BP;
        s.angularVelocity_W = toWorld * (toWorld.conjugate() * momentum).cwiseQuotient(mPrincipal[i].moments);
    }
}

std::pair<double, double> Simulator::jointErrors(const State& state)
{
    mEndRowsValid = false; // mRowsAfter is about to hold other rows
    assembleRows(mModel, mLayout, state, driveStep(), mRowsAfter, mActuation.gains());
    measureJointErrors(mRowsAfter);
    return {mStats.maxJointErrorM, mStats.maxJointErrorRad};
}

} // namespace frontier::core
