// core/step/contact_problem.cpp: the extra rows of a step, their Delassus matrix and its reuse,
// and their impulses (docs/method.md §5).
#include "core/step/contact_problem.h"

#include "core/frontier_order.h"
#include "core/joints/coordinates.h"
#include "core/joints/joint_types.h"

#include <algorithm>
#include <utility>

namespace frontier::core
{

void buildLoopBlocks(const Model& model, const FrontierLayout& layout, const RowSystem& rows,
                     std::vector<ExtraBlock>& out)
{
    out.clear();
    for (int k : layout.loopJoints)
    {
        const Joint& joint = model.joints[static_cast<std::size_t>(k)];
        const JointRows& r = rows.joints[static_cast<std::size_t>(k)];
        ExtraBlock block;
        block.kind = ExtraBlock::Kind::Loop;
        block.count = r.count;
        block.bodyA = jointToWorld(model, joint) ? -1 : joint.parent;
        block.bodyB = joint.child;
        block.J_A = r.J_a;
        block.J_B = r.J_b;
        block.error = r.error;
        const int drives = r.count - r.constraintRows;
        block.compliance.segment(r.constraintRows, drives) = r.compliance.segment(r.constraintRows, drives);
        block.source = k;
        out.push_back(block);
    }
    layoutExtraRows(out);
}

ContactProblem::ContactProblem(const StepContext& step)
    : mModel(step.model), mOptions(step.options), mSolver(step.solver), mDelassus(step.layout, step.solver)
{
    const Model& model = step.model;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const Joint& joint = model.joints[k];
        if (joint.limits && hasLimits(joint.type))
        {
            mLimitedJoints.push_back(static_cast<int>(k));
        }
        if (joint.friction > 0.0 && !jointCoordinates(joint.type).empty())
        {
            mFrictionJoints.push_back(static_cast<int>(k));
        }
    }
}

namespace
{

// A gap that the bodies cannot close within cSpeculativeSteps steps of dt (s), even moving
// straight at each other at their relative speed plus this step's gravity, needs no row: only the
// rows a scene needs are built (resting bodies near each other add none).
inline bool outOfReach(const Model& model, const std::vector<BodyState>& start, const Contact& contact,
                       double dt)
{
    constexpr double cSpeculativeSteps = 3.0;
    if (contact.depth >= 0.0)
    {
        return false;
    }
    Vec3 relative = Vec3::Zero(); // velocity of B's point relative to A's (m/s)
    const BodyState& a = start[static_cast<std::size_t>(contact.bodyA)];
    relative -= a.velocity_W + a.angularVelocity_W.cross(contact.point_W - a.position_W);
    if (contact.bodyB >= 0 && !model.bodies[static_cast<std::size_t>(contact.bodyB)].isStatic)
    {
        const BodyState& b = start[static_cast<std::size_t>(contact.bodyB)];
        relative += b.velocity_W + b.angularVelocity_W.cross(contact.point_W - b.position_W);
    }
    const double closing = relative.norm() + model.simulation.gravity.norm() * dt;
    return closing * dt * cSpeculativeSteps < -contact.depth;
}

// The target normal velocity of a contact row (m/s): a speculative row's gap over dt (s), or
// Newton restitution of the start-of-step approach.
inline void setContactTarget(const Model& model, const StepOptions& options,
                             const std::vector<BodyState>& start, const Contact& contact, double dt,
                             ExtraBlock& block)
{
    // Normal velocity before this step's gravity (m/s); < 0 approaching.
    double approach = block.J_A.row(0).dot((Vec6() << start[static_cast<std::size_t>(block.bodyA)].velocity_W,
                                            start[static_cast<std::size_t>(block.bodyA)].angularVelocity_W)
                                               .finished());
    if (block.bodyB >= 0)
    {
        const BodyState& b = start[static_cast<std::size_t>(block.bodyB)];
        approach += block.J_B.row(0).dot((Vec6() << b.velocity_W, b.angularVelocity_W).finished());
    }
    const bool closes = contact.depth >= 0.0 || approach * dt <= contact.depth;
    if (!closes)
    {
        block.target(0) = contact.depth / dt; // speculative: may approach by the gap, no more
    }
    else if (approach < -options.restitutionSpeed)
    {
        // Newton restitution
        block.target(0) = -contactRestitution(model, contact.bodyA, contact.bodyB) * approach;
    }
}

} // namespace

int ContactProblem::build(const StepContext& step, const State& state)
{
    const std::vector<BodyState>& start = step.start;
    const std::vector<ExtraBlock>& loops = step.loopBlocks;
    const double dt = step.stepLength();
    const double driveStep = step.driveStep;
    const Actuation& actuation = step.actuation;
    mExtra.clear();
    for (std::size_t c = 0; c < mContacts.size(); ++c)
    {
        const Contact& contact = mContacts[c];
        if (outOfReach(mModel, start, contact, dt))
        {
            continue;
        }
        ExtraBlock& block =
            appendContactBlock(mModel, state, contact, contactFriction(mModel, contact.bodyA, contact.bodyB),
                               static_cast<int>(c), mExtra);
        setContactTarget(mModel, mOptions, start, contact, dt, block);
    }
    for (const ExtraBlock& loop : loops)
    {
        mExtra.push_back(loop);
    }
    for (int joint : mLimitedJoints)
    {
        const std::size_t before = mExtra.size();
        appendLimitBlocks(mModel, state, joint, mOptions.limitMargin, mExtra);
        if (mExtra.size() > before && mExtra.back().error(0) < 0.0)
        {
            mExtra.back().target(0) = mExtra.back().error(0) / dt; // the gap to the limit
        }
    }
    for (int joint : mFrictionJoints)
    {
        appendFrictionBlocks(mModel, state, joint, driveStep, mExtra);
    }
    actuation.appendBoundedRows(state, state.time + driveStep, driveStep, mExtra);
    mRows = layoutExtraRows(mExtra);
    return mRows;
}

void ContactProblem::carryImpulses(BlockVector& rhs)
{
    mExtraLambda.setZero(mRows);
    mWarm = mRows > 0 && mMemory.warmStart(mExtra, mContacts, mExtraLambda);
    mBaseLambda = mExtraLambda;
    if (mWarm)
    {
        ImpulseSolver::addExtraImpulses(mExtra, mExtraLambda, rhs);
    }
}

// solution += H^-1 J_x^T (lambda - lambda_carried): from u(lambda_carried) to u(lambda).
void ContactProblem::applyImpulseChange(BlockVector& solution)
{
    mImpulseChange = mExtraLambda - mBaseLambda;
    mSolver.applyExtraImpulses(mExtra, mImpulseChange, solution);
}

ContactProblem::Outcome ContactProblem::solve(BlockVector& solution)
{
    Outcome outcome;
    if (mRows > 0)
    {
        mDelassus.layOut(mExtra, mContacts);
        // The row velocities at the carried impulses (zero when none), exactly: the step's first
        // solve included them (carryImpulses).
        extraRowVelocities(mExtra, solution, mExtraVelocity);
        setIslandTolerances();
        const bool open = std::any_of(mIslandTolerance.begin(), mIslandTolerance.end(),
                                      [](double tolerance) { return tolerance >= 0.0; });
        // Resting contact: the carried impulses often still meet every condition of this step (0
        // sweeps, the criterion the Gauss-Seidel stops on); else the islands that do not are solved.
        outcome.route = open ? solveOpenIslands(solution, outcome.sweeps) : ContactRoute::Carried;
    }
    mMemory.remember(mExtra, mContacts, mExtraLambda);
    return outcome;
}

// Each island's tolerance: max(tolerance, relativeTolerance x its largest residual at the carried
// impulses) (ContactSettings); -1 for an island whose conditions hold there already.
void ContactProblem::setIslandTolerances()
{
    const DelassusMatrix& G = mDelassus.matrix();
    mIslandTolerance.resize(static_cast<std::size_t>(G.islands()));
    for (int i = 0; i < G.islands(); ++i)
    {
        const double start = conditionResidual(mExtra, G.islandBlocks(i), mExtraVelocity, mExtraLambda);
        const double tolerance = std::max(mModel.contact.tolerance, mModel.contact.relativeTolerance * start);
        mIslandTolerance[static_cast<std::size_t>(i)] = start <= tolerance ? -1.0 : tolerance; // NaN: solved
    }
}

// The islands whose conditions do not hold: their parts of G kept from a recent step or built, then
// solved; on kept parts (G~) by a defect correction checked against the exact velocities.
ContactRoute ContactProblem::solveOpenIslands(BlockVector& solution, int& sweeps)
{
    const DelassusMatrix& G = mDelassus.matrix();
    mOpen.resize(mIslandTolerance.size());
    for (std::size_t i = 0; i < mIslandTolerance.size(); ++i)
    {
        mOpen[i] = mIslandTolerance[i] >= 0.0;
    }
    mDelassus.prepare(mOpen, mWarm && mOptions.reuseDelassus);
    bool kept = false;
    for (int i = 0; i < G.islands(); ++i)
    {
        kept = kept || (mOpen[static_cast<std::size_t>(i)] && !mDelassus.exact(i));
    }
    if (!kept || !correctWithKeptParts(solution, sweeps))
    {
        // Every open island on its exact part of G (the kept parts of those not done built anew):
        // the Gauss-Seidel's result is final.
        mDelassus.rebuild(mOpen);
        mExtraScratch.velocity = mExtraVelocity; // exact at the impulses reached so far
        sweeps += solveExtraRowsFrom(mExtra, G, mOptions.contactSolve, mExtraLambda, mExtraScratch,
                                     mIslandTolerance)
                      .sweeps;
        applyImpulseChange(solution);
    }
    return mDelassus.builtAny() ? ContactRoute::Built : ContactRoute::Reused;
}

// Resting and slowly changing contact: the parts of G~ kept from a recent step (the same rows,
// contacts within a millimetre) stand in for this step's in a defect correction. With the exact
// row velocities v(lambda) = J_x (u_free + H^-1 J_x^T lambda) (one O(n) solve), Gauss-Seidel solves
// v(lambda) + G~ (lambda' - lambda) against the contact conditions; an island's result is taken
// when the exact velocities meet its conditions to its tolerance (or, when Gauss-Seidel stalled on
// G~, to within cStalledAcceptance of where it stalled: G would stall there too), and at once when
// all its parts were built this step. Building a part costs a path sweep per body and a product
// per pair of its tree's bodies; a round here costs one O(n) solve and a few sweeps. False (after
// cReuseRounds, or when an island neither converged nor stalled even on G~) leaves the islands
// not done to the caller, with the impulses reached here as their start and mExtraVelocity exact
// at them. Islands done are marked in mOpen and mIslandTolerance.
bool ContactProblem::correctWithKeptParts(BlockVector& solution, int& sweeps)
{
    using IslandEnd = ExtraSolveScratch::IslandEnd;
    constexpr int cReuseRounds = 2;
    constexpr double cStalledAcceptance = 2.0;
    constexpr double cMargin = 0.9; // of the tolerance, for the difference between G~ and G
    const DelassusMatrix& G = mDelassus.matrix();
    mTolerances.resize(mIslandTolerance.size());
    for (int round = 0; round < cReuseRounds; ++round)
    {
        for (std::size_t i = 0; i < mIslandTolerance.size(); ++i)
        {
            mTolerances[i] = mOpen[i] ? cMargin * mIslandTolerance[i] : -1.0;
        }
        mExtraScratch.velocity = mExtraVelocity; // v(lambda), then v(lambda) + G~ (lambda' - lambda)
        sweeps +=
            solveExtraRowsFrom(mExtra, G, mOptions.contactSolve, mExtraLambda, mExtraScratch, mTolerances)
                .sweeps;
        mTrial = solution;
        applyImpulseChange(mTrial);
        extraRowVelocities(mExtra, mTrial, mExtraVelocity);
        bool pending = false, hopeless = false;
        for (int i = 0; i < G.islands(); ++i)
        {
            const std::size_t k = static_cast<std::size_t>(i);
            if (!mOpen[k])
            {
                continue;
            }
            const IslandEnd end = mExtraScratch.islandEnd[k];
            const double reached =
                end == IslandEnd::Stalled
                    ? std::max(mIslandTolerance[k], cStalledAcceptance * mExtraScratch.islandResidual[k])
                    : mIslandTolerance[k];
            if (mDelassus.exact(i) ||
                conditionResidual(mExtra, G.islandBlocks(i), mExtraVelocity, mExtraLambda) <= reached)
            {
                mOpen[k] = 0;
                mIslandTolerance[k] = -1.0;
                continue;
            }
            pending = true;
            hopeless = hopeless || (end != IslandEnd::Converged && end != IslandEnd::Stalled);
        }
        if (!pending)
        {
            std::swap(solution, mTrial);
            return true;
        }
        if (hopeless)
        {
            return false; // Gauss-Seidel did not converge even on G~: a hard step, G is built
        }
    }
    return false;
}

void ContactProblem::prepareDelassus()
{
    mDelassus.prepare({}, mOptions.reuseDelassus);
}

} // namespace frontier::core
