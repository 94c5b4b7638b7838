// core/simulator.h: the fixed-step integrator and its step pipeline.
//
// One step of the first-order scheme (`euler`: symplectic Euler with a SHAKE-type projection)
// reads like the physics, in Simulator::step():
//   checkState -> computeFreeVelocities -> assembleRows -> factorJoints -> solveImpulses
//   -> integratePositions -> stabilizeJoints -> carryAngularMomentum -> checkState
// Velocity level (PAPER.md §5 "Time stepping"): u* = u + h M^-1 f, then the joint impulses
// solve M u' = M u* + J^T lambda, J u' = 0 with the chosen solver. Positions: x += h v,
// R = exp(h w) R (a rotation-vector update, so orientations stay unit).
// Drift (PAPER.md §5 "Drift"): the joint position conditions C(q) are driven back to zero by a
// further impulse along J^T, solved with the same factorization (a quasi-Newton iteration: J at
// the start of the step stands for J at the end; re-factored once when that is slow); the impulse changes
// velocities and positions together (SHAKE), so it is internal: momentum is conserved and no
// energy is injected by a bias velocity.
// Gyroscopic term: each body's world angular momentum I_W w is carried through the rotation
// update (w = I_W(R_new)^-1 I_W(R_old) w), so a free body's angular momentum is exact.
#pragma once

#include "core/impulse_solver.h"

#include <memory>
#include <stdexcept>
#include <string>

namespace frontier::core
{

// A run that blew up: names the step, the body and the quantity.
class SimulationError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// A model the solver cannot take (e.g. a loop it does not support): bad input, not a failed run.
class UnsupportedModelError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

struct StepOptions
{
    double stabilizationTolerance = 1e-10; // m (rad for angular rows)
    int stabilizationIterations = 8;
};

struct StepStats
{
    double maxJointErrorM = 0.0;   // largest positional joint violation after the step (m)
    double maxJointErrorRad = 0.0; // largest angular joint violation after the step (rad)
    int stabilizationIterations = 0;
    int contacts = 0;             // contact points found this step
    double maxPenetrationM = 0.0; // deepest contact overlap this step (m)
};

class Simulator
{
  public:
    Simulator(const Model& model, const StepOptions& options = {});
    ~Simulator();

    // Advances the state by one time step of the model's dt (s). Throws SimulationError.
    void step(State& state);

    const FrontierLayout& layout() const { return mLayout; }
    const StepStats& lastStep() const { return mStats; }
    // Joint violations of a state (m, rad), without stepping.
    std::pair<double, double> jointErrors(const State& state);
    // Joint impulses of the last step (per joint index; N s or N m s).
    const std::vector<Vec6>& jointImpulses() const { return mSolution.joint; }

  private:
    void checkState(const State& state, const char* where) const;
    void computeFreeVelocities(State& state);
    void solveImpulses(State& state);
    void integratePositions(State& state);
    void stabilizeJoints(State& state);
    void carryAngularMomentum(State& state);
    void measureJointErrors(const RowSystem& rows);

    const Model& mModel;
    StepOptions mOptions;
    FrontierLayout mLayout;
    std::unique_ptr<ImpulseSolver> mSolver;
    RowSystem mRows;           // rows at the start of the step (the factored ones)
    RowSystem mRowsAfter;      // rows re-evaluated after the position update (errors only)
    RowSystem mRowsRefactored; // rows of a re-factorization when the quasi-Newton iteration is slow
    BlockVector mRhs, mSolution, mCorrection;
    std::vector<BodyState> mStart; // poses at the start of the step
    std::vector<Vec3> mMomentum;   // world angular momentum per body during the step
    StepStats mStats;
    double mDt;
};

} // namespace frontier::core
