// core/step/contact_problem.h: the extra rows of a step on top of the tree's factorization
// (docs/method.md §5): contacts (one-sided, Coulomb friction cone, Newton restitution), loop-closing
// joints (bilateral), joint limits near a limit, joint friction and actuators at their effort
// limits; their Delassus matrix G, its reuse over steps with the same rows, and their impulses.
#pragma once

#include "core/actuation.h"
#include "core/contact.h"
#include "core/extra_rows.h"
#include "core/impulse_solver.h"
#include "core/step/impulse_memory.h"
#include "core/step/row_key.h"
#include "core/step/step_options.h"
#include "core/step/step_stats.h"

#include <Eigen/Dense>
#include <cstdint>
#include <utility>
#include <vector>

namespace frontier::core
{

// The rows of the loop-closing joints in `rows` as bilateral extra blocks (velocity target 0),
// laid out on their own.
void buildLoopBlocks(const Model& model, const FrontierLayout& layout, const RowSystem& rows,
                     std::vector<ExtraBlock>& out);

class ContactProblem
{
  public:
    ContactProblem(const Model& model, const StepOptions& options, const FrontierLayout& layout,
                   ImpulseSolver& solver);

    // The contacts of the step (detection fills them, at the start-of-step pose).
    std::vector<Contact>& contacts() { return mContacts; }
    const std::vector<Contact>& contacts() const { return mContacts; }

    // Contact rows with their targets (restitution, or the gap that may close this step), the
    // given rows of loop-closing joints, limit rows near a limit, joint friction and actuators at
    // their limits. Evaluated at the start-of-step pose; `start` holds its velocities (before the
    // free-velocity kick), dt the step (s), driveStep the duration of this impulse solve (s).
    // Returns the number of rows.
    int build(const State& state, const std::vector<BodyState>& start, const std::vector<ExtraBlock>& loops,
              double dt, double driveStep, const Actuation& actuation);

    // The last step's impulses on this step's rows (warm start), and their momentum J_x^T lambda in
    // the right-hand side of the step's first solve: that solve then gives u(lambda_carried) =
    // H^-1 (M u* + J_x^T lambda_carried) exactly, so a step whose carried impulses still hold needs
    // no second O(n) solve, and the others apply only the change of the impulses.
    void carryImpulses(BlockVector& rhs);

    // With the tree's solution u(lambda_carried) (u_free when nothing was carried), the extra rows
    // in constraint space: v = J_x u_free + G lambda with the complementarity conditions, and
    // u' = u_free + H^-1 J_x^T lambda into `solution`. Remembers the impulses for the next step.
    struct Outcome
    {
        ContactRoute route = ContactRoute::None;
        int sweeps = 0; // Gauss-Seidel sweeps
    };
    Outcome solve(BlockVector& solution);

    // The Delassus matrix of this step's rows and their coupling by tree, once per step and only
    // when needed (the solve, the penetration projection).
    void buildDelassus();

    const std::vector<ExtraBlock>& blocks() const { return mExtra; }
    int rows() const { return mRows; }                               // rows of the blocks
    const Eigen::VectorXd& impulses() const { return mExtraLambda; } // N s or N m s, by row
    const Eigen::MatrixXd& delassus() const { return mG; }           // valid after buildDelassus
    ExtraSolveScratch& scratch() { return mExtraScratch; } // the Gauss-Seidel's, shared with other solves

  private:
    bool lastImpulsesStillHold(const BlockVector& solution);
    bool solveWithLastDelassus(BlockVector& solution, int& sweeps);
    bool sameRowsAsLastDelassus() const;
    void applyImpulseChange(BlockVector& solution);

    const Model& mModel;
    const StepOptions& mOptions;
    const FrontierLayout& mLayout;
    ImpulseSolver& mSolver;
    std::vector<int> mLimitedJoints;  // joints with limits (revolute, prismatic)
    std::vector<int> mFrictionJoints; // joints with Coulomb friction (a bounded drive row per coordinate)
    std::vector<Contact> mContacts;
    std::vector<ExtraBlock> mExtra; // contacts, loops, limits, joint friction of this step
    int mRows = 0;                  // their rows
    Eigen::MatrixXd mG;             // their Delassus matrix
    Eigen::VectorXd mExtraVelocity, mExtraLambda;
    ExtraSolveScratch mExtraScratch;
    RowCoupling mCoupling;                                   // rows each extra block can move
    std::vector<std::vector<std::pair<int, int>>> mTreeRuns; // scratch of coupleRowsByTree
    BlockVector mTrial;                                      // velocities with trial impulses (reuse rounds)
    // The warm-start impulses that the step's first solve included (solution = u(mBaseLambda));
    // mWarm: some impulse was carried from the last step.
    Eigen::VectorXd mBaseLambda, mImpulseChange;
    bool mWarm = false;
    ImpulseMemory mMemory;
    bool mDelassusValid = false;               // mG and mCoupling belong to this step's extra rows
    static constexpr int cMaxDelassusAge = 50; // steps a G~ may stand in for the current G
    std::vector<RowKey> mDelassusRows;         // the blocks mG was built for
    int mDelassusAge = -1;                     // steps since mG was built, -1 none
    std::uint64_t mDelassusVersion = 0;        // counts the builds of mG (names it for solveExtraRowsFrom)
};

} // namespace frontier::core
