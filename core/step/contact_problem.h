// core/step/contact_problem.h: the extra rows of a step on top of the tree's factorization
// (docs/method.md §5): contacts (one-sided, Coulomb friction cone, Newton restitution), loop-closing
// joints (bilateral), joint limits near a limit, joint friction and actuators at their effort
// limits; their Delassus matrix G, its reuse over steps with the same rows, and their impulses.
#pragma once

#include "core/actuation.h"
#include "core/contact.h"
#include "core/extra_rows.h"
#include "core/impulse_solver.h"
#include "core/step/delassus_cache.h"
#include "core/step/impulse_memory.h"
#include "core/step/row_key.h"
#include "core/step/step_context.h"
#include "core/step_options.h"
#include "core/step_stats.h"

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
    explicit ContactProblem(const StepContext& step);

    // The contacts of the step (detection fills them, at the start-of-step pose).
    std::vector<Contact>& contacts() { return mContacts; }
    const std::vector<Contact>& contacts() const { return mContacts; }

    // Contact rows with their targets (restitution, or the gap that may close this step), the
    // step's rows of loop-closing joints (loopBlocks), limit rows near a limit, joint friction and
    // actuators at their limits. Evaluated at the start-of-step pose; the step's `start` holds its
    // velocities (before the free-velocity kick), its |h| the step (s), driveStep the duration of
    // this impulse solve (s). Returns the number of rows.
    int build(const StepContext& step, const State& state);

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

    // Values for every part of this step's Delassus matrix (kept from a recent step where its
    // rows match, else built): what the penetration projection needs, only when it needs it.
    void prepareDelassus();

    const std::vector<ExtraBlock>& blocks() const { return mExtra; }
    int rows() const { return mRows; }                                    // rows of the blocks
    const Eigen::VectorXd& impulses() const { return mExtraLambda; }      // N s or N m s, by row
    const DelassusMatrix& delassus() const { return mDelassus.matrix(); } // after solve()
    ExtraSolveScratch& scratch() { return mExtraScratch; } // the Gauss-Seidel's, shared with other solves

    // What carries over from one step to the next (core/step_memory.h): the impulses of the warm
    // start and the parts of G kept for reuse.
    struct Memory
    {
        ImpulseMemory impulses;
        DelassusCache::Memory delassus;
    };
    Memory memory() const { return {mMemory, mDelassus.memory()}; }
    void restore(const Memory& memory)
    {
        mMemory = memory.impulses;
        mDelassus.restore(memory.delassus);
    }

  private:
    void setIslandTolerances();
    ContactRoute solveOpenIslands(BlockVector& solution, int& sweeps);
    bool correctWithKeptParts(BlockVector& solution, int& sweeps);
    void applyImpulseChange(BlockVector& solution);

    const Model& mModel;
    const StepOptions& mOptions;
    ImpulseSolver& mSolver;
    std::vector<int> mLimitedJoints;  // joints with limits (revolute, prismatic)
    std::vector<int> mFrictionJoints; // joints with Coulomb friction (a bounded drive row per coordinate)
    std::vector<Contact> mContacts;
    std::vector<ExtraBlock> mExtra; // contacts, loops, limits, joint friction of this step
    int mRows = 0;                  // their rows
    DelassusCache mDelassus;        // their Delassus matrix, by tree, parts kept across steps
    Eigen::VectorXd mExtraVelocity, mExtraLambda;
    ExtraSolveScratch mExtraScratch;
    BlockVector mTrial; // velocities with trial impulses (defect correction rounds)
    // The warm-start impulses that the step's first solve included (solution = u(mBaseLambda));
    // mWarm: some impulse was carried from the last step.
    Eigen::VectorXd mBaseLambda, mImpulseChange;
    bool mWarm = false;
    // Per island of the step's G: the velocity tolerance of its solve (m/s; ContactSettings), or
    // -1 when it needs none (its conditions held at the carried impulses) or is done.
    std::vector<double> mIslandTolerance;
    std::vector<std::uint8_t> mOpen; // per island: not done yet (scratch of the solve)
    std::vector<double> mTolerances; // scratch: the tolerances of a defect correction round
    ImpulseMemory mMemory;
};

} // namespace frontier::core
