// core/simulator.h: the fixed-step integrator and its step pipeline.
//
// One step of the first-order scheme (`euler`: symplectic Euler with a SHAKE-type projection)
// reads like the physics, in Simulator::stepEuler() (stage timings: StepStage, core/step/step_stats.h):
//   checkState -> detectContacts                                                       [Detect]
//   -> computeFreeVelocities -> rowsAtStart -> stiffenLoadedBodies -> buildExtraRows
//   -> setMomentumRhs -> predictDrift -> carryImpulses
//   -> factorAndSolve (O(n): elimination and the joint impulses in one pass)           [Factor]
//   -> solveContactImpulses                                                            [Solve]
//      (rowsAtStart .. solveContactImpulses again while an actuator went past its effort limit)
//   -> predictDriftAfterExtraRows
//   -> integratePositions -> removePenetration -> stabilizeJoints -> recordJointLoads
//   -> carryAngularMomentum -> finishStep (joint angles, time, checkState)             [Integrate]
// Each stage is a unit of core/step/: the contact problem (contact_problem.h, with the warm start
// of impulse_memory.h), positions (positions.h), the penetration projection
// (penetration_projection.h), the drift correction (drift_correction.h), RATTLE's projection
// (rattle_projection.h), and the checks that stop a run that blew up (blow_up_check.h,
// simulation_error.h).
// Contacts, loop-closing joints and joint limits are extra rows on top of the tree factorization
// (docs/method.md §5, core/extra_rows.h): contacts one-sided with a Coulomb friction cone and Newton
// restitution above StepOptions::restitutionSpeed; penetration beyond a slop is removed by a separate
// position projection (no velocity bias, so no bodies jump).
// Joint damping is a compliant drive row in the joint's block of the factorization (implicit, so
// stable for any value), Coulomb joint friction a bounded extra row (core/joints/drive.h). Position
// servos and velocity motors share those rows below their effort limits and become bounded extra
// rows at them (the step's first solve is then taken again); effort actuators and external loads
// join gravity in the free velocities (core/actuation.h). Each step ends by continuing the joints'
// angles across +-pi (State::jointAngles), which limits and servos read.
// Velocity level (docs/method.md §4): u* = u + h M^-1 f, then the joint impulses
// solve M u' = M u* + J^T lambda, J u' = 0 with the chosen solver. Positions: x += h v,
// R = exp(h w) R (a rotation-vector update, so orientations stay unit), or for a body whose angular
// momentum turns relative to it within the step the free rotation at constant angular momentum
// (docs/method.md §4, eq. (8a); core/step/positions.h).
// Geometric stiffness (docs/method.md §7a): a body whose joints pull on it hard enough that the
// explicit directions would let its sideways mode grow gets h^2 k added to its rotational inertia
// in the factorization (core/step/geometric_stiffness.h); all other bodies step as without it.
// Drift (docs/method.md §7): the joint position conditions C(q) are driven back to zero by a
// further impulse along J^T, solved with the same factorization (a quasi-Newton iteration: J at
// the start of the step stands for J at the end; re-factored once when that is slow); the impulse changes
// velocities and positions together (SHAKE), so it is internal: momentum is conserved and no
// energy is injected by a bias velocity.
// Gyroscopic term: each body's world angular momentum I_W w is carried through the rotation
// update (w = I_W(R_new)^-1 I_W(R_old) w), so a free body's angular momentum is exact.
//
// The second-order scheme (`rattle`, Simulator::stepRattle) is RATTLE on the bodies' positions
// and rotations:
//   checkState -> detectContacts                                                       [Detect]
//   -> computeFreeVelocities (h/2) -> factorAtStart                                    [Factor]
//   -> buildExtraRows -> setMomentumRhs -> carryImpulses -> solve -> solveContactImpulses [Solve]
//      (factorAtStart .. solveContactImpulses again while an actuator went past its effort limit)
//   -> integratePositions -> removePenetration -> stabilizeJoints (stalled: the step is taken
//      again by euler) -> carryAngularMomentum -> kickByGravity (h/2) -> applyForces (h/2)
//   -> projectVelocities -> finishStep                                                 [Integrate]
// That is: half kick h/2 g; impulses along J(q_n)^T chosen so that the drifted positions
// satisfy C(q_{n+1}) = 0 (Newton iterations to stabilizationTolerance with the O(n) factorization);
// a drift at constant momenta (straight lines, and the split free rigid-body rotation of
// core/free_rotation.h on SO(3)); half kick; the velocity projection J(q_{n+1}) u_{n+1} = 0
// with the factorization at q_{n+1}, which the next step reuses. Contacts, limits and impacts
// are impulses of the first stage (first order across an impact, as any impulse method); contacts
// and limits that pushed in the first stage keep pushing (one-sided) in the final projection.
// Joint damping and friction, servos and motors act in both velocity stages, each over h/2 (a
// servo's spring at the stage's start pose, its targets at the stage's end), as do effort actuators
// and loads with gravity's half kicks.
#pragma once

#include "core/actuation.h"
#include "core/contact.h"
#include "core/free_rotation.h"
#include "core/impulse_solver.h"
#include "core/step/blow_up_check.h"
#include "core/step/contact_problem.h"
#include "core/step/drift_correction.h"
#include "core/step/penetration_projection.h"
#include "core/step/rattle_projection.h"
#include "core/step/simulation_error.h"
#include "core/step/step_options.h"
#include "core/step/step_stats.h"
#include "core/step_memory.h"

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

namespace frontier::core
{

class Simulator
{
  public:
    // contacts may be null: no contact detection (bodies pass through each other).
    explicit Simulator(const Model& model, const StepOptions& options = {},
                       ContactSource* contacts = nullptr);
    ~Simulator();

    // Advances the state by one time step of the model's dt (s). Throws SimulationError.
    void step(State& state);

    const FrontierLayout& layout() const { return mLayout; }
    const StepStats& lastStep() const { return mStats; }
    // Joint violations of a state (m, rad), without stepping.
    std::pair<double, double> jointErrors(const State& state);
    // Joint impulses of the last step (per joint index; N s or N m s), row by row as in JointRows:
    // the joint's conditions, then its drive rows (the damping impulse, core/joints/drive.h).
    const LargeVector<Vec6>& jointImpulses() const { return mSolution.joint; }
    // What each actuator did in the last step (Model::actuators order): its effort, the impulse it
    // applied over the step divided by dt (N or N m, along its coordinate; drift corrections not
    // counted), and whether it sat at its effort limit (core/actuation.h).
    std::span<const ActuatorEffort> actuatorEfforts() const { return mActuation.efforts(); }
    // Replaces the target of Model::actuators[actuator] from the next step on, by a constant (rad
    // or m for a servo in the model file's coordinate, rad/s or m/s for a motor, N m or N for an
    // effort; Actuator::target) or by any TimeFunction of the simulation time. Throws
    // std::out_of_range for an index beyond Model::actuators.
    void setActuatorTarget(std::size_t actuator, double value)
    {
        mActuation.setTarget(actuator, constantFunction(value));
    }
    void setActuatorTarget(std::size_t actuator, TimeFunction target)
    {
        mActuation.setTarget(actuator, std::move(target));
    }

    // Pushes moving body `body` during the next step only: a force through its centre of mass and
    // a torque, world frame (N, N m), applied as the model's loads are (core/actuation.h), so its
    // impulse over the step is force_N dt and torque_Nm dt with every integrator. Wrenches given
    // twice before a step add up; the step forgets them. Throws std::out_of_range for an index
    // beyond Model::bodies, std::invalid_argument for a static body or a value that is not finite.
    void applyWrench(int body, const Vec3& force_N, const Vec3& torque_Nm)
    {
        mActuation.addWrench(body, force_N, torque_Nm);
    }
    // The same for a force at world point point_W (m): the force through the centre of mass and
    // the torque (point_W - x) x force_N, x the centre of mass where `state` (the state the next step
    // starts from) has it.
    void applyForceAtPoint(const State& state, int body, const Vec3& force_N, const Vec3& point_W);

    // What the simulator carries from one step to the next besides the State (core/step_memory.h):
    // a State and this memory taken together and put back together (State assigned,
    // restoreMemory) make the next steps bit-identical to those taken from them the first time, in
    // this Simulator or another one of the same model. What the last step reported (lastStep(),
    // jointImpulses(), contactImpulses() ...) stays that of the step last taken; actuatorEfforts()
    // is restored. restoreMemory throws std::invalid_argument for an empty memory or that of a
    // model with other numbers of bodies, joints or actuators, and then changes nothing.
    StepMemory memory() const;
    void restoreMemory(const StepMemory& memory);

    // What the last step passed through its joints and contacts, worked out when asked
    // (core/step_report.cpp; nothing of it runs in step()).
    // Per joint, the impulse it gave its child body over the step, world frame: [linear (N s);
    // angular about the joint's anchor on the child (N m s)]. Every row of the joint counts: its
    // conditions, drive rows, limit, friction and loop rows, and the drift correction; the parent
    // received the opposite. The rows are taken at `state`, the state the step produced, so that a
    // ball joint passes no torque and a hinge none about its axis but through its limit or drives.
    void jointChildImpulses(const State& state, std::vector<Vec6>& out) const;
    // The contacts the step detected (at its start) with the impulse each passed; 0 for those
    // that got no row (a gap the bodies could not close within the step).
    void contactImpulses(std::vector<ContactImpulse>& out) const;
    // Joint-limit rows that pushed (impulse > 0) in the last step.
    int pushingLimitRows() const;

  private:
    void takeStep(State& state);
    void stepEuler(State& state);
    enum class RattleOutcome
    {
        Done,
        Stalled,  // the position iteration stalled; state partly stepped
        OneSided, // a rattle4 stage met contact or limit rows; state partly stepped
    };
    RattleOutcome stepRattle(State& state, bool firstStage);
    bool stepRattle4(State& state); // false: a stage met one-sided rows or stalled
    bool hasOneSidedRows() const;
    void addRowImpulses(const State& state, std::vector<Vec6>& out) const; // core/step_report.cpp
    void keepStageImpulses();
    bool mComposedStep = false;    // the last step was a composed rattle4 step
    LargeVector<Vec6> mStageJoint; // its first two stages' joint-block impulses, summed
    std::vector<std::pair<std::vector<ExtraBlock>, Eigen::VectorXd>> mStageExtras; // ... extra rows
    bool mRattleStep = false;     // the step under way is a rattle step (or a rattle4 stage)
    bool mRattle4Stage = false;   // ... a stage of a rattle4 step
    bool mHasBlockDrives = false; // some joint has drive rows in its block (damping, actuators)
    State mStepStart;             // the state a rattle or rattle4 step started from
    void checkState(const State& state, const char* where) const;
    void recordStartDefects(const State& state);
    void detectContacts(const State& state);
    void computeFreeVelocities(State& state, double h);
    void keepFreeVelocities(const State& state);
    bool actuatorsWithinLimits(State& state);
    std::vector<BodyState> mFree; // the free velocities of the step (actuators may solve again)
    void rowsAtStart(const State& state);
    void buildExtraRows(const State& state);
    void setMomentumRhs(const State& state, double tEnd);
    void stiffenLoadedBodies(const State& state);
    void recordJointLoads(State& state) const;
    bool predictsDrift() const;
    void predictDrift(const State& state);
    void predictDriftAfterExtraRows(State& state);
    void carryImpulses();
    void factorAtStart(const State& state);
    void projectVelocities(State& state);
    void kickByGravity(State& state, double h);
    void carryAngularMomentum(State& state);
    void finishStep(State& state);
    void solveContactImpulses(State& state);
    void integratePositions(State& state);
    void removePenetration(State& state);
    bool stabilizeJoints(State& state); // false: a rattle step stalled
    // Duration of one impulse solve (s): the step, or half of it for rattle, whose two velocity
    // stages each take half of the joints' damping and friction (core/joints/drive.h); for a
    // rattle4 stage half of its share of the step, always positive (docs/method.md §11).
    double driveStep() const { return mDriveStep; }

    const Model& mModel;
    StepOptions mOptions;
    ContactSource* mContactSource;
    std::vector<ExtraBlock> mLoopBlocks; // loop joints alone, at the factored rows (§5, §7)
    FrontierLayout mLayout;
    Actuation mActuation; // servos, motors, effort actuators and loads
    std::unique_ptr<ImpulseSolver> mSolver;
    ContactProblem mProblem;            // contacts, loops, limits, joint friction: the extra rows (§5)
    PenetrationProjection mPenetration; // overlaps and limit overruns out by displacement (§5)
    DriftCorrection mDrift;             // the joints' position conditions back to zero (§7)
    RattleProjection mRattle;           // rattle: the velocity projection at the end of the step (§4)
    BlowUpCheck mBlowUp;                // runaway states, joints come apart: SimulationError
    RowSystem mRows;                    // rows at the start of the step (the factored ones)
    RowSystem mRowsAfter;               // rows re-evaluated after the position update (errors only)
    BlockVector mRhs, mSolution;
    std::vector<BodyState> mStart;             // poses at the start of the step
    std::vector<PrincipalAxes> mPrincipal;     // principal axes per body (free rotation, momentum carry)
    std::vector<std::uint8_t> mFreeRotation;   // per body: the step turns it by the free rotation (§4)
    std::vector<std::uint8_t> mHeldInRotation; // per body: a joint holds its rotation (§4, eq. (8a))
    // euler: the end pose of the last step, at which mRowsAfter holds the rows (reused as the
    // next step's mRows when it starts there).
    std::vector<BodyState> mEndPose;
    bool mEndRowsValid = false;
    StepStats mStats;
    double mDt;
    double mH = 0.0;         // the (sub)step under way (s): mDt, or a rattle4 stage (< 0 in the middle)
    double mDriveStep = 0.0; // driveStep() (s)
};

} // namespace frontier::core
