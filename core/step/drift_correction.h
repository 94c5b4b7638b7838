// core/step/drift_correction.h: the SHAKE-type projection of the joints' position conditions
// C(q) back to zero after the position update (docs/method.md §7), and the joint errors it reads.
#pragma once

#include "core/actuation.h"
#include "core/free_rotation.h"
#include "core/impulse_solver.h"
#include "core/step/step_context.h"
#include "core/step_options.h"

#include <Eigen/Dense>
#include <cstdint>
#include <optional>
#include <vector>

namespace frontier::core
{

// The largest joint violations of a set of rows: positional (m), angular (rad), and the joint of
// the largest of either.
struct JointErrors
{
    double maxM = 0.0;
    double maxRad = 0.0;
    int worstJoint = 0;
};
// `worstJoint` is the joint of the largest violation, or `worstBefore` when no row is violated.
JointErrors measureJointErrors(const RowSystem& rows, int worstBefore);

// A joint the drift correction leaves apart by more than this after its last iteration has come
// apart: the run stops there (m or rad).
constexpr double cJointBlowUp = 1e-3;

class DriftCorrection
{
  public:
    explicit DriftCorrection(const StepContext& step);

    enum class Outcome
    {
        Converged, // to stabilizationTolerance, or within cJointBlowUp after the last iteration
        Stalled,   // a rattle step whose iteration stalled (to be taken by euler)
        CameApart, // a joint still apart by more than cJointBlowUp: errors() names it
    };

    // Impulses along J^T that bring C(q_{n+1}) to zero. Each iteration solves
    // [M J^T; J 0][du; -dlambda] = [0; -C/h] and moves velocities by du and positions by h du
    // (integratePositions from `start`, each body by the rotation update `freeRotation` the step
    // chose). The first iterations reuse the step's factorization
    // (quasi-Newton: J at the start of the step stands for J at the end); when an iteration
    // contracts the error by less than cSlowContraction (fast rotation, thin bodies, large steps),
    // the system is re-factored at the current configuration (once per step: re-factoring again
    // made convergence worse in tests), the loop blocks rebuilt there. Loop joints join exactly
    // through their Delassus block. rattle: the impulse direction stays J(q_n)^T (so the step is
    // the symplectic map), never re-factored; Stalled when it contracts by less than cRattleStall
    // or has not converged after cRattleIterations. Leaves `rowsAfter` at the final pose, adds
    // the joint impulses to `solution`. The step's context gives the start-of-step pose `start`,
    // `rows`, `rowsAfter`, `loopBlocks`, `solution`, `freeRotation`, its h (dt here) and driveStep,
    // and whether it is a RATTLE step or stage.
    Outcome run(StepContext& step, State& state);

    // The predicted drift (docs/method.md §7, eq. (11a)): the step's first velocity solve asks
    // J u = -D / h of each joint's condition rows, D = State::jointDrift the violation the last
    // step's position update left (a smooth function of time between impacts), so that the
    // projection starts close to the manifold. It moves the iteration's starting point, not what
    // it converges to. Adds -D / h to `rhs`; run() then updates State::jointDrift.
    void addPredictedDrift(const State& state, BlockVector& rhs, double dt);
    // The same prediction on a step with extra rows (contacts, limits, loops), whose impulses must
    // not see it: its own solve with the step's factorization after theirs, J du = -D / h, added
    // to the velocities in `state` and to the joint impulses in `solution`.
    void applyPredictedDrift(State& state, BlockVector& solution, double dt);

    const JointErrors& errors() const { return mErrors; } // after the last iteration
    int iterations() const { return mIterations; }        // iterations that moved the state
    // The loop impulses of this step's correction (N s, N m s), by the rows of the loop blocks.
    const Eigen::VectorXd& loopCorrection() const { return mLoopCorrection; }
    // Joint violations of `rows` (a measurement outside the step: the worst joint is kept too).
    const JointErrors& measure(const RowSystem& rows);

  private:
    // The steps of run().
    static constexpr double cSlowContraction = 0.1; // an iteration contracting less re-factors
    void measureAfter(StepContext& step, const State& state, bool conditionsOnly);
    void completeRows(StepContext& step, const State& state);
    std::optional<Outcome> stopsAt(const StepContext& step, double error, int iteration) const;
    void refactor(StepContext& step, const State& state);
    void factorLoops(std::vector<ExtraBlock>& loopBlocks); // lays their rows out
    void correct(StepContext& step, State& state);
    void addCorrection(State& state, BlockVector& solution) const; // mCorrection
    void correctLoops(const std::vector<ExtraBlock>& loopBlocks, double dt);
    void updatePredictedDrift(const RowSystem& rowsAfter, State& state, double dt);
    static Vec6 extrapolatedDrift(const Vec6& drift, const Vec6& lastDrift); // eq. (11a)
    bool underTension(const Joint& joint) const; // mTension, for updatePredictedDrift
    void addLoopCompliance(const std::vector<ExtraBlock>& loopBlocks);

    const Model& mModel;
    const StepOptions& mOptions;
    const FrontierLayout& mLayout;
    ImpulseSolver& mSolver;
    JointErrors mErrors;
    int mIterations = 0;
    bool mPredictionApplied = false; // addPredictedDrift was called for this step
    // run()'s iteration: the last error (m or rad), re-factored this step, the loops' G factored
    // for the current factorization, rowsAfter assembled in full at the current pose.
    double mPrevious = 0.0;
    bool mRefactored = false;
    bool mLoopsFactored = false;
    bool mRowsComplete = false;
    LargeVector<double> mTension;  // per body: 1 where h^2 k / I > cTenseRatio (§7a)
    RowSystem mRowsRefactored;     // rows of a re-factorization when the quasi-Newton iteration is slow
    BlockVector mRhs, mCorrection; // mRhs: no body part for the linear solver (zero momenta)
    Eigen::MatrixXd mLoopG;
    Eigen::LDLT<Eigen::MatrixXd> mLoopLdlt;
    Eigen::VectorXd mLoopError;      // C of the loop rows (m, rad)
    Eigen::VectorXd mLoopVelocity;   // J_loop du of the tree correction
    Eigen::VectorXd mLoopCorrection; // loop impulses of this step's correction (N s, N m s)
};

} // namespace frontier::core
