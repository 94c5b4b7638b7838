// core/step/penetration_projection.h: the position projection that removes overlaps beyond the
// slop and limit overruns (docs/method.md §5), without touching velocities, bounded by
// core/penetration.h.
#pragma once

#include "core/actuation.h"
#include "core/free_rotation.h"
#include "core/impulse_solver.h"
#include "core/step/contact_problem.h"
#include "core/step/step_context.h"
#include "core/step_options.h"

#include <Eigen/Dense>
#include <utility>
#include <vector>

namespace frontier::core
{

class PenetrationProjection
{
  public:
    explicit PenetrationProjection(const StepContext& step);

    // Penetration beyond the slop (contacts) or past a limit, predicted at the end of the step
    // from the velocities `solution` of the step's extra rows, is removed by a displacement
    // H^-1 J^T mu (through the joints, so they stay together) with mu >= 0: a position projection
    // that leaves velocities, and so kinetic energy, unchanged. Loop joints ride along as
    // bilateral rows with target 0. It is bounded (core/penetration.h): rows the joints hold are
    // left alone, and a step moves no body faster than penetrationMaxSpeed nor turns it faster
    // than penetrationMaxAngularSpeed (deep overlaps come out over several steps); a displacement
    // that turns bodies puts their joints back by displacement too (restoreJoints). Moves `state`
    // and the step's start-of-step pose `start` alike; the step's `rows` are the factored
    // start-of-step rows.
    void apply(StepContext& step, State& state, ContactProblem& problem);

    // What carries over from one step to the next (core/step_memory.h), and what a step taken
    // again from its start puts back: the last step's displacement was capped (a recovery under way).
    struct Memory
    {
        bool capped = false;
    };
    const Memory& memory() const { return mMemory; }
    void restore(const Memory& memory) { mMemory = memory; }

  private:
    // The steps of apply().
    double excess(const ExtraBlock& block, double dt) const;
    bool overlapsAfterStep(const StepContext& step, const ContactProblem& problem);
    bool gatherRows(const StepContext& step, ContactProblem& problem);
    double solveDisplacement(const StepContext& step, ContactProblem& problem);
    void restoreJoints(State& state, std::vector<BodyState>& start, double driveStep,
                       const Actuation& actuation);

    // A penetration displacement that recovers a deep defect (capped, or the one after a capped
    // step) or turns a body by more than this (rad) puts the joints back by restoreJoints. Below it
    // their second-order gap (theta^2 L / 2, under 5e-5 m at L = 1 m) is left to the drift
    // correction as before (the bundled scenes turn bodies by up to 4.7e-3 rad a step at 1 ms).
    static constexpr double cRestoreRotation = 0.01;

    const Model& mModel;
    const StepOptions& mOptions;
    const FrontierLayout& mLayout;
    ImpulseSolver& mSolver;
    Memory mMemory;
    // Scratch: the rows' velocities J_x u; the projection's blocks, their rows in the step's G,
    // their G, free velocity and impulses, and the rows each block can move.
    Eigen::VectorXd mRowVelocity;
    std::vector<ExtraBlock> mBlocks;
    std::vector<int> mRows;
    DelassusMatrix mG; // the step's G on the rows projected
    Eigen::VectorXd mFree, mImpulse;
    BlockVector mDisplacement, mRhs;     // m, rad; the joints' conditions
    RowSystem mMovedRows;                // rows at the displaced pose (restoreJoints)
    std::vector<Vec6> mJointErrorBefore; // restoreJoints: C per joint before the displacement
};

} // namespace frontier::core
