// core/step/rattle_projection.cpp: RATTLE's velocity projection at the end of the step.
#include "core/step/rattle_projection.h"

#include "core/step/velocity_stage.h"

namespace frontier::core
{

RattleProjection::RattleProjection(const StepContext& step)
    : mModel(step.model), mOptions(step.options), mLayout(step.layout), mSolver(step.solver)
{
}

void RattleProjection::factorAtStart(StepContext& step, const State& state)
{
    RowSystem& rows = step.rows;
    const double driveStep = step.driveStep;
    const Actuation& actuation = step.actuation;
    if (!(mFactoredPoseValid && samePose(mModel, state, mFactoredPose)))
    {
        assembleRows(mModel, mLayout, state, driveStep, rows, actuation.gains());
        mSolver.factor(rows);
    }
    mFactoredPoseValid = false;
}

void RattleProjection::project(StepContext& step, State& state, ContactProblem& problem)
{
    RowSystem& rows = step.rows;
    RowSystem& rowsAfter = step.rowsAfter;
    std::vector<ExtraBlock>& loopBlocks = step.loopBlocks;
    BlockVector& rhs = step.rhs;
    BlockVector& solution = step.solution;
    const double dt = step.h; // s, signed
    const double driveStep = step.driveStep;
    Actuation& actuation = step.actuation;
    std::swap(rows, rowsAfter);
    mCorrection.resize(mModel.bodies.size(), mModel.joints.size()); // sized at first use: euler never uses it
    for (;;)
    {
        mSolver.factor(rows);
        buildLoopBlocks(mModel, mLayout, rows, loopBlocks);
        mEndBlocks = loopBlocks;
        for (const ExtraBlock& block : problem.blocks())
        {
            if (block.kind == ExtraBlock::Kind::Drive)
            {
                if (block.actuator < 0)
                {
                    mEndBlocks.push_back(block); // joint friction acts in both halves of the step
                }
                continue;
            }
            if (block.kind != ExtraBlock::Kind::Loop && problem.impulses()(block.offset) > 0.0)
            {
                ExtraBlock normal = block;
                normal.count = block.kind == ExtraBlock::Kind::Contact ? block.count : 1;
                normal.target.setZero();
                mEndBlocks.push_back(normal);
            }
        }
        // Actuators at their limits act in the second half too, with their targets at its end.
        actuation.appendBoundedRows(state, state.time + dt, driveStep, mEndBlocks);
        setMomentumRhs(mModel, rows, state, state.time + dt, driveStep, actuation, rhs);
        mSolver.solve(rhs, mCorrection);
        if (!mEndBlocks.empty())
        {
            const int n = layoutExtraRows(mEndBlocks);
            mSolver.delassus(mEndBlocks, mEndG);
            extraRowVelocities(mEndBlocks, mCorrection, mEndVelocity);
            mEndLambda.setZero(n);
            ExtraSolveSettings settings = mOptions.contactSolve;
            settings.velocityTolerance = mModel.contact.tolerance;
            solveExtraRows(mEndBlocks, mEndG, mEndVelocity, settings, mEndLambda, problem.scratch());
            mSolver.applyExtraImpulses(mEndBlocks, mEndLambda, mCorrection);
        }
        if (actuation.acceptSolve(rows, mCorrection, mEndBlocks, mEndLambda, driveStep))
        {
            break;
        }
        // An actuator went beyond its limit: out of its block, the projection again.
        assembleRows(mModel, mLayout, state, driveStep, rows, actuation.gains());
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
        solution.joint[k] += mCorrection.joint[k];
    }
}

} // namespace frontier::core
