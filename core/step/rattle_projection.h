// core/step/rattle_projection.h: the last stage of the RATTLE scheme (docs/method.md §4, §7): the
// velocity projection J(q_{n+1}) u_{n+1} = 0 with the factorization at q_{n+1}, which the next
// step's first stage reuses when it starts at that pose.
#pragma once

#include "core/actuation.h"
#include "core/impulse_solver.h"
#include "core/step/contact_problem.h"
#include "core/step/step_context.h"
#include "core/step_options.h"

#include <Eigen/Dense>
#include <utility>
#include <vector>

namespace frontier::core
{

class RattleProjection
{
  public:
    explicit RattleProjection(const StepContext& step);

    // Rows and factorization at the start-of-step pose into the step's `rows`; the last projection
    // left them factored at exactly this pose unless the state was changed between steps.
    void factorAtStart(StepContext& step, const State& state);

    // The second half of RATTLE's velocity update: u_{n+1} = u - M^-1 J^T mu with
    // J(q_{n+1}) u_{n+1} = 0, M and J at q_{n+1} (`rowsAfter`, the rows the last Newton iteration
    // assembled, which become `rows`). Loop joints join as bilateral rows (rebuilt into
    // `loopBlocks`); contacts and limits that pushed in this step's impulse stage (`problem`) as
    // one-sided normal rows with target 0 (they may separate, never pull); joint friction and
    // actuators at their limits act in this half too. The step's `rhs` is scratch; the joint
    // impulses are added to its `solution`.
    void project(StepContext& step, State& state, ContactProblem& problem);

    // The rows factored by the last projection no longer stand for the next step's start.
    void forgetFactoredPose() { mFactoredPoseValid = false; }

    // The projection's extra rows and their impulses (N s, N m s), for the step's report.
    const std::vector<ExtraBlock>& blocks() const { return mEndBlocks; }
    const Eigen::VectorXd& impulses() const { return mEndLambda; }

  private:
    const Model& mModel;
    const StepOptions& mOptions;
    const FrontierLayout& mLayout;
    ImpulseSolver& mSolver;
    // The pose at which the rows were factored by the last projection.
    std::vector<BodyState> mFactoredPose;
    bool mFactoredPoseValid = false;
    BlockVector mCorrection; // the projected velocities and joint impulses (empty until the first projection)
    std::vector<ExtraBlock> mEndBlocks;
    DelassusMatrix mEndG;
    Eigen::VectorXd mEndVelocity, mEndLambda;
};

} // namespace frontier::core
