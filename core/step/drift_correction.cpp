// core/step/drift_correction.cpp: the SHAKE-type drift correction of the joints (docs/method.md §7).
#include "core/step/drift_correction.h"

#include "core/fixed_rows.h"
#include "core/step/contact_problem.h"
#include "core/step/geometric_stiffness.h"
#include "core/step/positions.h"
#include "core/tree_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace frontier::core
{

JointErrors measureJointErrors(const RowSystem& rows, int worstBefore)
{
    JointErrors errors;
    errors.worstJoint = worstBefore;
    double worst = -1.0;
    for (std::size_t k = 0; k < rows.joints.size(); ++k)
    {
        const JointRowsTable::Rows r = rows.joints.rows(k);
        for (int row = 0; row < r.count; ++row)
        {
            const double error = std::abs(r.error[row]);
            double& slot = row < r.positionRows ? errors.maxM : errors.maxRad;
            slot = std::max(slot, error);
            if (error > worst)
            {
                worst = error;
                errors.worstJoint = static_cast<int>(k);
            }
        }
    }
    return errors;
}

DriftCorrection::DriftCorrection(const StepContext& step)
    : mModel(step.model), mOptions(step.options), mLayout(step.layout), mSolver(step.solver)
{
    const Model& model = step.model;
    const ImpulseSolver& solver = step.solver;
    // The correction's right-hand side has no momenta, -C / h on the joint rows alone: the linear
    // solver takes an empty body part for that (core/tree_solver.cpp), the others get the zeros.
    const bool momentaImplied = dynamic_cast<const TreeSolver*>(&solver) != nullptr;
    mRhs.resize(momentaImplied ? 0 : model.bodies.size(), model.joints.size());
    mRhs.setZero();
    mCorrection.resize(model.bodies.size(), model.joints.size());
}

void DriftCorrection::addPredictedDrift(const State& state, BlockVector& rhs, double dt)
{
    if (state.jointDrift.size() == mModel.joints.size())
    {
        for (std::size_t k = 0; k < state.jointDrift.size(); ++k)
        {
            rhs.joint[k] -= state.jointDrift[k] / dt;
        }
    }
    mPredictionApplied = true;
}

// docs/method.md §7, eq. (11a): D_pred = D_n + beta (D_n - D_(n-1)) where the joint's drift changed
// smoothly over the last step (by at most cSmoothChange of itself, and larger than cDriftFloor,
// below which the change is round-off), D_n otherwise. beta < 1 damps the extrapolation: at 1 the
// recurrence of the prediction's errors, z^2 = (1 + beta) z - beta, has a double root at 1, and the
// linear and dense solvers' trajectories of a damped 4-link chain parted by 7.6e-10 m in 0.5 s
// (3e-12 m at 0.9).
Vec6 DriftCorrection::extrapolatedDrift(const Vec6& drift, const Vec6& lastDrift)
{
    constexpr double cBeta = 0.9;
    constexpr double cSmoothChange = 0.2;
    constexpr double cDriftFloor = 1e-8; // m or rad
    const double size = drift.cwiseAbs().maxCoeff();
    const Vec6 change = drift - lastDrift;
    if (size > cDriftFloor && change.cwiseAbs().maxCoeff() <= cSmoothChange * size)
    {
        return drift + cBeta * change;
    }
    return drift;
}

// docs/method.md §7, eq. (11a). After the position update of a step that asked J u = -D / h, the
// rows measure what the prediction missed; D + that is the drift the free update would have left
// (to first order), the next step's prediction. A miss larger than the prediction itself (an
// impact, a changed drive) starts over; a step without the prediction leaves none. A joint under
// tension (a body of it past cTenseRatio) whose own miss exceeds a tenth of its prediction starts
// over alone: feeding its prediction back makes the zigzag of light links under high tension
// grow (the 1000-link chain of the stability suite needs this to hold its second). Elsewhere a
// joint's prediction is kept through such misses (a swinging chain's joints miss by 4-15% a
// step; starting over every other step doubled its projection iterations).
void DriftCorrection::updatePredictedDrift(const RowSystem& rowsAfter, State& state, double dt)
{
    constexpr double cJointMiss = 0.1;
    constexpr double cTenseRatio = 1.0; // h^2 k / I: a quarter of the explicit step's limit (4)
    const bool applied = mPredictionApplied;
    mPredictionApplied = false;
    if (!applied)
    {
        state.jointDrift.clear();
        state.jointDriftLast.clear();
        return;
    }
    state.jointDrift.resize(mModel.joints.size(), Vec6::Zero());
    state.jointDriftLast.resize(mModel.joints.size(), Vec6::Zero());
    geometricInertias(mModel, state.jointLoads, dt, mTension);
    for (std::size_t i = 0; i < mTension.size(); ++i)
    {
        const double meanMoment = mModel.bodies[i].inertia_B.trace() / 3.0; // kg m^2
        mTension[i] = meanMoment > 0.0 && mTension[i] > cTenseRatio * meanMoment ? 1.0 : 0.0;
    }
    double missed = 0.0;    // m or rad
    double predicted = 0.0; // m or rad
    for (std::size_t k = 0; k < state.jointDrift.size(); ++k)
    {
        const JointRowsTable::Rows r = rowsAfter.joints.rows(k);
        Vec6 miss = Vec6::Zero(); // condition rows only
        for (int row = 0; row < r.constraintRows; ++row)
        {
            miss(row) = r.error[row];
        }
        const double missedHere = miss.cwiseAbs().maxCoeff();
        const double predictedHere = state.jointDrift[k].cwiseAbs().maxCoeff();
        missed = std::max(missed, missedHere);
        predicted = std::max(predicted, predictedHere);
        Vec6 drift = state.jointDrift[k] + miss; // D_n
        if (predictedHere > 0.0 && missedHere > cJointMiss * predictedHere && underTension(mModel.joints[k]))
        {
            drift.setZero(); // this joint's drift is not smooth in time
        }
        state.jointDrift[k] = extrapolatedDrift(drift, state.jointDriftLast[k]);
        state.jointDriftLast[k] = drift;
    }
    if (predicted > 0.0 && missed > predicted)
    {
        state.jointDrift.clear();
        state.jointDriftLast.clear();
    }
}

void DriftCorrection::applyPredictedDrift(State& state, BlockVector& solution, double dt)
{
    mPredictionApplied = true;
    double largest = 0.0; // m or rad
    for (const Vec6& d : state.jointDrift)
    {
        largest = std::max(largest, d.cwiseAbs().maxCoeff());
    }
    if (state.jointDrift.size() != mModel.joints.size() || largest <= mOptions.stabilizationTolerance)
    {
        // Nothing to predict beyond what the correction leaves; with no prediction asked, the
        // update measures the whole drift (a kept D_n would add this step's miss to it).
        state.jointDrift.clear();
        return;
    }
    mRhs.setZero();
    addPredictedDrift(state, mRhs, dt); // the joint rows ask -D / h, the bodies nothing
    mSolver.solve(mRhs, mCorrection);
    addCorrection(state, solution);
}

// Velocities move by du (m/s, rad/s), the joints' impulses by dlambda.
void DriftCorrection::addCorrection(State& state, BlockVector& solution) const
{
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
        solution.joint[k] += mCorrection.joint[k];
    }
}

bool DriftCorrection::underTension(const Joint& joint) const
{
    const auto tense = [&](int body) { return body >= 0 && mTension[static_cast<std::size_t>(body)] > 0.0; };
    return tense(joint.parent) || tense(joint.child);
}

const JointErrors& DriftCorrection::measure(const RowSystem& rows)
{
    mErrors = measureJointErrors(rows, mErrors.worstJoint);
    return mErrors;
}

// The iteration of run(): measure C at the current pose, stop (converged, stalled, or at the cap),
// re-factor when the quasi-Newton iteration is slow, correct.
DriftCorrection::Outcome DriftCorrection::run(StepContext& step, State& state)
{
    std::vector<ExtraBlock>& loopBlocks = step.loopBlocks;
    mLoopCorrection.setZero(loopBlocks.empty() ? 0 : loopBlocks.back().offset + loopBlocks.back().count);
    mPrevious = std::numeric_limits<double>::infinity();
    mRefactored = false;
    mLoopsFactored = false;
    // The last step's iteration count is the guess of how many corrections this one takes (only
    // the cost depends on it).
    const int expectedCorrections = mIterations;
    mIterations = 0;
    for (int iteration = 0;; ++iteration)
    {
        measureAfter(step, state, iteration < expectedCorrections);
        if (iteration == 0)
        {
            updatePredictedDrift(step.rowsAfter, state, step.h);
        }
        const double error = std::max(mErrors.maxM, mErrors.maxRad);
        if (const std::optional<Outcome> outcome = stopsAt(step, error, iteration))
        {
            completeRows(step, state);
            return *outcome;
        }
        if (!mRefactored && error > cSlowContraction * mPrevious)
        {
            refactor(step, state);
        }
        factorLoops(loopBlocks);
        mPrevious = error;
        mIterations = iteration + 1;
        correct(step, state);
    }
}

// A measurement that a correction follows needs the joints' conditions only (`conditionsOnly`);
// the rows the step ends with are assembled in full once, at its end pose (completeRows).
void DriftCorrection::measureAfter(StepContext& step, const State& state, bool conditionsOnly)
{
    mRowsComplete = false;
    if (conditionsOnly)
    {
        assembleJointConditions(mModel, state, step.rowsAfter);
    }
    else
    {
        completeRows(step, state);
    }
    measure(step.rowsAfter);
}

void DriftCorrection::completeRows(StepContext& step, const State& state)
{
    if (!mRowsComplete)
    {
        assembleRows(mModel, mLayout, state, step.driveStep, step.rowsAfter, step.actuation.gains());
        mRowsComplete = true;
    }
}

// Where the iteration stops at an error (m or rad) after `iteration` corrections: converged; a
// rattle step that stalls (taken by euler); the iteration cap, where a joint still apart by more
// than cJointBlowUp is a blow-up (the run stops naming the step, the joint and the gap, instead
// of going on with garbage). None: correct again.
std::optional<DriftCorrection::Outcome> DriftCorrection::stopsAt(const StepContext& step, double error,
                                                                 int iteration) const
{
    constexpr double cRattleStall = 0.5;
    constexpr int cRattleIterations = 12;
    if (error <= mOptions.stabilizationTolerance)
    {
        return Outcome::Converged;
    }
    if (step.rattle() && (error > cRattleStall * mPrevious || iteration >= cRattleIterations))
    {
        return Outcome::Stalled;
    }
    if (iteration >= mOptions.stabilizationIterations)
    {
        return error > cJointBlowUp ? Outcome::CameApart : Outcome::Converged;
    }
    return std::nullopt;
}

// The system re-factored at the current configuration (once per step), the loop blocks rebuilt there.
void DriftCorrection::refactor(StepContext& step, const State& state)
{
    completeRows(step, state);
    mRefactored = true;
    mRowsRefactored = step.rowsAfter;
    mRowsRefactored.geometricInertia = step.rows.geometricInertia; // the step's metric (§7a)
    mSolver.factor(mRowsRefactored);
    buildLoopBlocks(mModel, mLayout, mRowsRefactored, step.loopBlocks);
    mLoopsFactored = false;
}

// Loop rows join the projection exactly: their Delassus block, once per factorization.
void DriftCorrection::factorLoops(std::vector<ExtraBlock>& loopBlocks)
{
    if (!loopBlocks.empty() && !mLoopsFactored)
    {
        mSolver.delassus(loopBlocks, layoutExtraRows(loopBlocks), mLoopG);
        addLoopCompliance(loopBlocks);
        mLoopLdlt.compute(mLoopG);
        mLoopsFactored = true;
    }
}

// One correction: [M J^T; J 0][du; -dlambda] = [0; -C/h], velocities moved by du and positions by
// h du from the start-of-step pose.
void DriftCorrection::correct(StepContext& step, State& state)
{
    const double dt = step.h; // s, signed: a backward stage of a composed step moves back
    mLoopError.resize(mLoopG.rows());
    for (const ExtraBlock& loop : step.loopBlocks)
    {
        mLoopError.segment(loop.offset, loop.count) =
            step.rowsAfter.joints[static_cast<std::size_t>(loop.source)].error.head(loop.count);
    }
    // mRhs.body stays zero: the correction's right-hand side is -C / h on the joint rows alone.
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        const JointRowsTable::Rows r = step.rowsAfter.joints.rows(k);
        Vec6 condition = Vec6::Zero(); // C as the 6 rows of a JointRows hold it
        withRows(r.count,
                 [&](auto n)
                 {
                     constexpr int R = decltype(n)::value;
                     condition.head<R>() = Eigen::Map<const Eigen::Matrix<double, R, 1>>(r.error);
                 });
        mRhs.joint[k] = -condition / dt;
    }
    mSolver.solve(mRhs, mCorrection);
    if (!step.loopBlocks.empty())
    {
        correctLoops(step.loopBlocks, dt);
    }
    addCorrection(state, step.solution);
    integratePositions(mModel, step.start, step.principal, step.rows, step.freeRotation, dt, state);
}

// Loop rows in the projection: the tree correction du_0 leaves J_loop du_0 + C_loop / h; the loop
// impulse mu = G_loop^-1 (-C_loop / h - J_loop du_0) removes it, and du += H^-1 J_loop^T mu.
void DriftCorrection::correctLoops(const std::vector<ExtraBlock>& loopBlocks, double dt)
{
    extraRowVelocities(loopBlocks, mCorrection, mLoopVelocity);
    const Eigen::VectorXd residual = -mLoopError / dt - mLoopVelocity;
    const Eigen::VectorXd mu = mLoopLdlt.solve(residual);
    mSolver.applyExtraImpulses(loopBlocks, mu, mCorrection);
    mLoopCorrection += mu;
}

// Drive rows of loop joints are compliant in the projection too: G_loop gains E on their diagonal.
void DriftCorrection::addLoopCompliance(const std::vector<ExtraBlock>& loopBlocks)
{
    for (const ExtraBlock& loop : loopBlocks)
    {
        mLoopG.diagonal().segment(loop.offset, loop.count) += loop.compliance.head(loop.count);
    }
}

} // namespace frontier::core
