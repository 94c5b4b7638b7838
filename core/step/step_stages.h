// core/step/step_stages.h: the named stages a step is made of, and the data a Simulator keeps from
// step to step. The steppers of core/steppers/ (one per integrator) list the stages in the order
// of their scheme; each stage is one call into a unit of core/step/ with the step's context
// (core/step/step_context.h). Private to the library: core/simulator.h holds it behind a pointer.
#pragma once

#include "core/actuation.h"
#include "core/contact.h"
#include "core/impulse_solver.h"
#include "core/step/blow_up_check.h"
#include "core/step/contact_problem.h"
#include "core/step/drift_correction.h"
#include "core/step/penetration_projection.h"
#include "core/step/rattle_projection.h"
#include "core/step/step_context.h"
#include "core/step_memory.h"
#include "core/step_options.h"
#include "core/step_stats.h"

#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace frontier::core
{

class StepStages
{
  public:
    // contacts may be null: no contact detection.
    StepStages(const Model& model, const StepOptions& options, ContactSource* contacts);

    StepContext& context() { return mStep; }
    const StepContext& context() const { return mStep; }
    StepStats& stats() { return mStats; }
    const StepStats& stats() const { return mStats; }

    // Stages, in the order the steppers take them (core/steppers/).
    void beginStep(StepScheme scheme); // stats cleared, h = dt, the scheme of the step
    void checkState(const State& state, const char* where) const;
    void detectContacts(const State& state);
    void computeFreeVelocities(State& state, double h);
    void rowsAtStart(const State& state); // euler: reuses the last step's end rows at the same pose
    void stiffenLoadedBodies(const State& state);
    void buildExtraRows(const State& state);
    void setMomentumRhs(const State& state, double tEnd);
    void predictDrift(const State& state);
    void carryImpulses();
    void factorAndSolve();
    void factorAtStart(const State& state);
    void solve();
    void solveContactImpulses(State& state);
    bool actuatorsWithinLimits(State& state);
    void predictDriftAfterExtraRows(State& state);
    void integratePositions(State& state);
    void removePenetration(State& state);
    bool stabilizeJoints(State& state); // false: a rattle step stalled
    void recordJointLoads(State& state) const;
    void carryAngularMomentum(State& state);
    void kickByGravity(State& state, double h);
    void applyForces(State& state, double tBegin, double tEnd);
    void projectVelocities(State& state);
    void finishStep(State& state);  // joint angles, clock by dt, check
    void finishStage(State& state); // a composed step's stage: joint angles, clock by h, check
    void finishComposedStep(State& state, double start); // its clock: by dt from `start` (s)
    void keepEndRows(const State& state);                // euler: the end rows serve the next step's start
    bool hasOneSidedRows() const;

    // A step taken again from its start (another scheme): what the first attempt changed put back.
    struct Restart
    {
        State state;
        PenetrationProjection::Memory penetration;
    };
    void saveRestart(const State& state);
    void restart(State& state);
    void forgetFactoredPose() { mRattle.forgetFactoredPose(); }
    void forgetEndRows() { mEndRowsValid = false; }

    // rattle4: the impulses of its first stages, summed for the step's report.
    void clearStageImpulses();
    void keepStageImpulses();
    void setComposedStep(bool composed) { mComposedStep = composed; }

    // After step(): actuators back in their blocks make the rows built for the next step stale.
    void finishActuation();

    // Simulator's queries (core/simulator.h).
    const FrontierLayout& layout() const { return mLayout; }
    const LargeVector<Vec6>& jointImpulses() const { return mStep.solution.joint; }
    Actuation& actuation() { return mActuation; }
    const Actuation& actuation() const { return mActuation; }
    std::pair<double, double> jointErrors(const State& state);
    void jointChildImpulses(const State& state, std::vector<Vec6>& out) const; // core/step_report.cpp
    void contactImpulses(std::vector<ContactImpulse>& out) const;              // core/step_report.cpp
    int pushingLimitRows() const;                                              // core/step_report.cpp
    StepMemory memory() const;                                                 // core/step_memory.cpp
    void restoreMemory(const StepMemory& memory);                              // core/step_memory.cpp

  private:
    void recordStartDefects(const State& state);
    void keepFreeVelocities(const State& state);
    bool predictsDrift() const;
    void addRowImpulses(const State& state, std::vector<Vec6>& out) const; // core/step_report.cpp

    const Model& mModel;
    StepOptions mOptions;
    ContactSource* mContactSource;
    FrontierLayout mLayout;
    Actuation mActuation;
    std::unique_ptr<ImpulseSolver> mSolver;
    StepContext mStep;                  // the step under way and what its stages pass on
    ContactProblem mProblem;            // contacts, loops, limits, joint friction: the extra rows (§5)
    PenetrationProjection mPenetration; // overlaps and limit overruns out by displacement (§5)
    DriftCorrection mDrift;             // the joints' position conditions back to zero (§7)
    RattleProjection mRattle;           // rattle: the velocity projection at the end of the step (§4)
    BlowUpCheck mBlowUp;                // runaway states, joints come apart: SimulationError
    std::vector<BodyState> mFree;       // the free velocities of the step (actuators may solve again)
    std::vector<std::uint8_t> mHeldInRotation; // per body: a joint holds its rotation (§4, eq. (8a))
    // euler: the end pose of the last step, at which rowsAfter holds the rows (reused as the next
    // step's rows when it starts there).
    std::vector<BodyState> mEndPose;
    bool mEndRowsValid = false;
    Restart mRestart;
    bool mComposedStep = false;    // the last step was a composed rattle4 step
    LargeVector<Vec6> mStageJoint; // its first two stages' joint-block impulses, summed
    std::vector<std::pair<std::vector<ExtraBlock>, Eigen::VectorXd>> mStageExtras; // ... extra rows
    StepStats mStats;
};

} // namespace frontier::core
