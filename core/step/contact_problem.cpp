// core/step/contact_problem.cpp: the extra rows of a step, their Delassus matrix and its reuse,
// and their impulses (docs/method.md §5).
#include "core/step/contact_problem.h"

#include "core/frontier_order.h"
#include "core/joints/coordinates.h"

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

ContactProblem::ContactProblem(const Model& model, const StepOptions& options, const FrontierLayout& layout,
                               ImpulseSolver& solver)
    : mModel(model), mOptions(options), mLayout(layout), mSolver(solver)
{
    for (std::size_t k = 0; k < model.joints.size(); ++k)
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

int ContactProblem::build(const State& state, const std::vector<BodyState>& start,
                          const std::vector<ExtraBlock>& loops, double dt, double driveStep,
                          const Actuation& actuation)
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
            const BodyState& a = start[static_cast<std::size_t>(contact.bodyA)];
            relative -= a.velocity_W + a.angularVelocity_W.cross(contact.point_W - a.position_W);
            if (contact.bodyB >= 0 && !mModel.bodies[static_cast<std::size_t>(contact.bodyB)].isStatic)
            {
                const BodyState& b = start[static_cast<std::size_t>(contact.bodyB)];
                relative += b.velocity_W + b.angularVelocity_W.cross(contact.point_W - b.position_W);
            }
            const double closing = relative.norm() + mModel.simulation.gravity.norm() * dt;
            if (closing * dt * cSpeculativeSteps < -contact.depth)
            {
                continue;
            }
        }
        ExtraBlock& block =
            appendContactBlock(mModel, state, contact, mModel.contact.friction, static_cast<int>(c), mExtra);
        // Normal velocity before this step's gravity (m/s); < 0 approaching.
        double approach =
            block.J_A.row(0).dot((Vec6() << start[static_cast<std::size_t>(block.bodyA)].velocity_W,
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
        else if (approach < -mOptions.restitutionSpeed)
        {
            block.target(0) = -e * approach; // Newton restitution
        }
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
    mDelassusValid = false;
    if (mDelassusAge >= 0 && mDelassusAge <= cMaxDelassusAge)
    {
        ++mDelassusAge; // stops one past the limit
    }
    if (mRows > 0)
    {
        if (mWarm && lastImpulsesStillHold(solution))
        {
            outcome.route = ContactRoute::Carried;
        }
        else if (mWarm && mOptions.reuseDelassus && solveWithLastDelassus(solution, outcome.sweeps))
        {
            outcome.route = ContactRoute::Reused;
        }
        else
        {
            outcome.route = ContactRoute::Built;
            buildDelassus();
            if (mWarm)
            {
                mExtraScratch.velocity = mExtraVelocity; // exact at the impulses reached so far
            }
            else
            {
                extraRowVelocities(mExtra, solution, mExtraScratch.velocity); // lambda = 0
            }
            outcome.sweeps += solveExtraRowsFrom(mExtra, mG, mOptions.contactSolve, mExtraLambda,
                                                 mExtraScratch, &mCoupling, mDelassusVersion)
                                  .sweeps;
            applyImpulseChange(solution);
        }
    }
    mMemory.remember(mExtra, mContacts, mExtraLambda);
    return outcome;
}

// Resting contact: the impulses carried over from the last step often still meet every
// condition of this step to the solve's tolerance (core::conditionResidual). The step's first
// solve included them (carryImpulses), so the check is v = J_x u(lambda_carried), without G; when
// they hold, the step keeps them (0 sweeps, the same criterion the Gauss-Seidel stops on).
bool ContactProblem::lastImpulsesStillHold(const BlockVector& solution)
{
    extraRowVelocities(mExtra, solution, mExtraVelocity);
    return conditionsMet(mExtra, mExtraVelocity, mExtraLambda, mOptions.contactSolve.velocityTolerance);
}

// The rows it was built for are remembered for solveWithLastDelassus.
void ContactProblem::buildDelassus()
{
    if (!mDelassusValid)
    {
        mSolver.delassus(mExtra, mRows, mG);
        ++mDelassusVersion; // the Gauss-Seidel's pivots of the last G no longer hold
        coupleRowsByTree(mExtra, mLayout.treeOfBody, mCoupling, mTreeRuns);
        mDelassusValid = true;
        mDelassusRows.clear();
        for (const ExtraBlock& block : mExtra)
        {
            mDelassusRows.push_back(rowKey(block, mContacts));
        }
        mDelassusAge = 0;
    }
}

// The same rows as when mG was built, each contact within cReuseDistance of its point then.
bool ContactProblem::sameRowsAsLastDelassus() const
{
    constexpr double cReuseDistance = 1e-3; // m
    if (mDelassusAge < 0 || mDelassusAge > cMaxDelassusAge || mDelassusRows.size() != mExtra.size())
    {
        return false;
    }
    for (std::size_t b = 0; b < mExtra.size(); ++b)
    {
        const RowKey now = rowKey(mExtra[b], mContacts);
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
bool ContactProblem::solveWithLastDelassus(BlockVector& solution, int& sweepCount)
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
        sweepCount += sweeps.sweeps;
        mTrial = solution;
        applyImpulseChange(mTrial);
        extraRowVelocities(mExtra, mTrial, mExtraVelocity);
        if (conditionsMet(mExtra, mExtraVelocity, mExtraLambda, mOptions.contactSolve.velocityTolerance))
        {
            std::swap(solution, mTrial);
            return true;
        }
        if (!sweeps.converged)
        {
            return false; // Gauss-Seidel did not converge even on G~: a hard step, G is built
        }
    }
    return false;
}

} // namespace frontier::core
