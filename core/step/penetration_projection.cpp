// core/step/penetration_projection.cpp: the bounded position projection of overlaps and limit
// overruns, and the restoration of the joints it turns.
#include "core/step/penetration_projection.h"

#include "core/penetration.h"
#include "core/step/positions.h"

#include <algorithm>

namespace frontier::core
{

namespace
{
// One-sided rows that keep bodies apart (contacts, limits): what the projection removes.
bool pushesApart(const ExtraBlock& block)
{
    return block.kind == ExtraBlock::Kind::Contact || block.kind == ExtraBlock::Kind::Limit;
}
} // namespace

PenetrationProjection::PenetrationProjection(const StepContext& step)
    : mModel(step.model), mOptions(step.options), mLayout(step.layout), mSolver(step.solver)
{
    const Model& model = step.model;
    mDisplacement.resize(model.bodies.size(), model.joints.size());
    mRhs.resize(model.bodies.size(), model.joints.size());
    mRhs.setZero();
}

void PenetrationProjection::apply(StepContext& step, State& state, ContactProblem& problem)
{
    const bool wasCapped = mMemory.capped;
    mMemory.capped = false; // set again below when this step's displacement is capped
    if (problem.rows() == 0 || !overlapsAfterStep(step, problem) || !gatherRows(step, problem))
    {
        return;
    }
    const double scale = solveDisplacement(step, problem);
    // A recovery (its capped steps, and the one that finishes it) keeps the joints by displacement.
    const bool recovering = scale < 1.0 || wasCapped;
    mMemory.capped = scale < 1.0;
    if (recovering || largestRotation(mModel, mDisplacement) > cRestoreRotation)
    {
        restoreJoints(state, step.start, step.driveStep, step.actuation);
        return;
    }
    displacePositions(mModel, mDisplacement, state, step.start);
}

// Overlap predicted after this step (m or rad): now minus h times the separating speed (the rows'
// velocities mRowVelocity); the part beyond the slop (contacts) or the limit is to be removed.
double PenetrationProjection::excess(const ExtraBlock& block, double dt) const
{
    const double predicted = block.error(0) - dt * mRowVelocity(block.offset);
    return predicted - (block.kind == ExtraBlock::Kind::Contact ? mOptions.penetrationSlop : 0.0);
}

// Some row that pushes apart is predicted beyond its slop or limit (most steps have none).
bool PenetrationProjection::overlapsAfterStep(const StepContext& step, const ContactProblem& problem)
{
    const double dt = step.stepLength();
    extraRowVelocities(problem.blocks(), step.solution, mRowVelocity);
    bool any = false;
    for (const ExtraBlock& block : problem.blocks())
    {
        any = any || (pushesApart(block) && excess(block, dt) > 0.0);
    }
    return any;
}

// The projection's rows (mBlocks, their rows in the step's G in mRows): the normal and limit rows
// the joints do not hold, with their excess as target, and the loop rows with target 0. False:
// none has an excess.
bool PenetrationProjection::gatherRows(const StepContext& step, ContactProblem& problem)
{
    const double dt = step.stepLength();
    problem.prepareDelassus();
    const DelassusMatrix& G = problem.delassus();
    mBlocks.clear();
    mRows.clear();
    bool any = false;
    for (const ExtraBlock& block : problem.blocks())
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
            if (heldByJoints(block, G.entry(block.offset, block.offset), step.rows, step.principal,
                             mOptions.penetrationHeldRatio))
            {
                continue;
            }
            p.count = 1;
            p.target(0) = std::max(0.0, excess(block, dt));
            any = any || p.target(0) > 0.0;
        }
        for (int k = 0; k < p.count; ++k)
        {
            mRows.push_back(block.offset + k);
        }
        mBlocks.push_back(p);
    }
    return any;
}

// The displacement H^-1 J^T mu into mDisplacement, mu >= 0 from the rows' Gauss-Seidel, scaled
// down to the bounds of a step; returns the scale (1: within them).
double PenetrationProjection::solveDisplacement(const StepContext& step, ContactProblem& problem)
{
    const double dt = step.stepLength();
    const int n = layoutExtraRows(mBlocks);
    mG.gather(mBlocks, mLayout.treeOfBody, problem.delassus(), mRows); // the normal, limit and loop rows
    mFree.setZero(n);
    mImpulse.setZero(n);
    ExtraSolveSettings settings = mOptions.contactSolve;
    settings.velocityTolerance = mModel.contact.tolerance * dt; // here the rows are displacements (m)
    solveExtraRows(mBlocks, mG, mFree, settings, mImpulse, problem.scratch());
    mDisplacement.setZero();
    mSolver.applyExtraImpulses(mBlocks, mImpulse, mDisplacement);
    const double scale = displacementScale(mModel, mDisplacement, mOptions.penetrationMaxSpeed * dt,
                                           mOptions.penetrationMaxAngularSpeed * dt);
    if (scale < 1.0)
    {
        for (Vec6& d : mDisplacement.body)
        {
            d *= scale;
        }
    }
    return scale;
}

// Applies the penetration displacement (mDisplacement) and puts the joints back as they were. The
// displacement keeps them to first order only: turning a body by theta leaves a joint at lever L
// about theta^2 L / 2 apart, which the drift correction would remove with a velocity (C / h),
// adding kinetic energy. Here the tree joints' conditions are driven back to their values before
// the displacement by further displacements H^-1 J^T nu (J d = -(C - C_before)), on the step's
// factorization; velocities are not touched. Loop joints are left to the drift correction.
void PenetrationProjection::restoreJoints(State& state, std::vector<BodyState>& start, double driveStep,
                                          const Actuation& actuation)
{
    constexpr int cRestoreIterations = 10;
    assembleRows(mModel, mLayout, state, driveStep, mMovedRows, actuation.gains());
    mJointErrorBefore.resize(mModel.joints.size());
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        mJointErrorBefore[k] = mMovedRows.joints[k].error;
    }
    displacePositions(mModel, mDisplacement, state, start);
    for (int iteration = 0; iteration < cRestoreIterations; ++iteration)
    {
        assembleRows(mModel, mLayout, state, driveStep, mMovedRows, actuation.gains());
        double worst = 0.0;
        for (std::size_t k = 0; k < mModel.joints.size(); ++k)
        {
            const JointRows& r = mMovedRows.joints[k];
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
        mSolver.solve(mRhs, mDisplacement);
        displacePositions(mModel, mDisplacement, state, start);
    }
}

} // namespace frontier::core
