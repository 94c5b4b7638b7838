// core/simulator.cpp: the step pipeline of the first-order (`euler`) scheme.
#include "core/simulator.h"

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

bool finite(const Vec3& v)
{
    return v.allFinite();
}
} // namespace

Simulator::Simulator(const Model& model, const StepOptions& options)
    : mModel(model), mOptions(options), mLayout(buildFrontierLayout(model)),
      mSolver(makeSolver(model.simulation.solver, model.simulation.pgsIterations)), mDt(model.simulation.dt)
{
    if (!mLayout.loopJoints.empty())
    {
        const Joint& joint = mModel.joints[static_cast<std::size_t>(mLayout.loopJoints.front())];
        throw UnsupportedModelError("joint '" + joint.name +
                                    "' closes a loop (a second path between its bodies or to the world); "
                                    "loop-closing joints are not supported by the tree solver yet");
    }
    const std::size_t nb = model.bodies.size();
    const std::size_t nj = model.joints.size();
    mRhs.resize(nb, nj);
    mSolution.resize(nb, nj);
    mCorrection.resize(nb, nj);
    mRhs.setZero();
    mSolution.setZero();
    mStart.resize(nb);
    mMomentum.resize(nb);
}

Simulator::~Simulator() = default;

void Simulator::step(State& state)
{
    checkState(state, "start of step");
    computeFreeVelocities(state);
    assembleRows(mModel, mLayout, state, mRows);
    mSolver->factor(mRows); // PAPER.md §3 step 2 (eliminate), once per step
    solveImpulses(state);   // §3 step 3 (back substitute)
    integratePositions(state);
    stabilizeJoints(state);
    carryAngularMomentum(state);
    state.time += mDt;
    ++state.step;
    checkState(state, "end of step");
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
        else if (!finite(s.velocity_W))
        {
            quantity = "velocity";
        }
        else if (!finite(s.angularVelocity_W))
        {
            quantity = "angular velocity";
        }
        if (quantity != nullptr)
        {
            std::ostringstream msg;
            msg << "simulation blew up at step " << state.step << " (t = " << state.time << " s, " << where
                << "): body '" << mModel.bodies[i].name << "' has a non-finite " << quantity;
            throw SimulationError(msg.str());
        }
    }
}

// u* = u + h M^-1 f: gravity on the centre of mass; no torque. Saves the start-of-step poses.
void Simulator::computeFreeVelocities(State& state)
{
    const Vec3 dv = mDt * mModel.simulation.gravity;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        mStart[i] = state.bodies[i];
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W += dv;
        }
    }
}

// Joint impulses at velocity level: M u' - J^T lambda = M u*, J u' = 0.
void Simulator::solveImpulses(State& state)
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
    mSolver->solve(mRhs, mSolution);
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (!mModel.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W = mSolution.body[i].head<3>();
            state.bodies[i].angularVelocity_W = mSolution.body[i].tail<3>();
        }
    }
}

// x_{n+1} = x_n + h v_{n+1}; R_{n+1} = exp(h w_{n+1}) R_n, from the start-of-step pose.
void Simulator::integratePositions(State& state)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (mModel.bodies[i].isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        s.position_W = mStart[i].position_W + mDt * s.velocity_W;
        s.orientation_WB =
            (rotationFromVector(mDt * s.angularVelocity_W) * mStart[i].orientation_WB).normalized();
    }
}

void Simulator::measureJointErrors(const RowSystem& rows)
{
    mStats.maxJointErrorM = 0.0;
    mStats.maxJointErrorRad = 0.0;
    for (std::size_t k = 0; k < rows.joints.size(); ++k)
    {
        const JointRows& r = rows.joints[k];
        for (int row = 0; row < r.count; ++row)
        {
            double& slot = row < r.positionRows ? mStats.maxJointErrorM : mStats.maxJointErrorRad;
            slot = std::max(slot, std::abs(r.error(row)));
        }
    }
}

// SHAKE-type projection: impulses along J^T that bring C(q_{n+1}) to zero. Each iteration solves
// [M J^T; J 0][du; -dlambda] = [0; -C/h] and moves velocities by du and positions by h du. The
// first iterations reuse the step's factorization (quasi-Newton: J at the start of the step stands
// for J at the end); when that contracts the error by less than cSlowContraction per iteration
// (fast rotation, thin bodies), the system is re-factored once at the current configuration.
void Simulator::stabilizeJoints(State& state)
{
    constexpr double cSlowContraction = 0.1;
    mStats.stabilizationIterations = 0;
    double previous = std::numeric_limits<double>::infinity();
    bool refactored = false;
    for (int iteration = 0;; ++iteration)
    {
        assembleRows(mModel, mLayout, state, mRowsAfter);
        measureJointErrors(mRowsAfter);
        const double error = std::max(mStats.maxJointErrorM, mStats.maxJointErrorRad);
        if (error <= mOptions.stabilizationTolerance || iteration >= mOptions.stabilizationIterations)
        {
            break;
        }
        if (!refactored && error > cSlowContraction * previous)
        {
            mRowsRefactored = mRowsAfter;
            mSolver->factor(mRowsRefactored);
            refactored = true;
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
        s.angularVelocity_W = worldInertia(body, s).ldlt().solve(momentum);
    }
}

std::pair<double, double> Simulator::jointErrors(const State& state)
{
    assembleRows(mModel, mLayout, state, mRowsAfter);
    measureJointErrors(mRowsAfter);
    return {mStats.maxJointErrorM, mStats.maxJointErrorRad};
}

} // namespace frontier::core
