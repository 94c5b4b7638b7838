// core/simulator.h: the fixed-step integrator and its step pipeline.
//
// One step of the first-order scheme (`euler`: symplectic Euler with a SHAKE-type projection)
// reads like the physics, in Simulator::step():
//   checkState -> detectContacts -> computeFreeVelocities -> assembleRows -> setMomentumRhs
//   -> factorAndSolve (O(n): elimination and the joint impulses in one pass) -> buildExtraRows
//   -> solveContactImpulses -> integratePositions -> removePenetration
//   -> stabilizeJoints -> carryAngularMomentum -> checkState
// Contacts, loop-closing joints and joint limits are extra rows on top of the tree factorization
// (docs/method.md §5, core/extra_rows.h): contacts one-sided with a Coulomb friction cone and Newton
// restitution above cRestitutionSpeed; penetration beyond a slop is removed by a separate
// position projection (no velocity bias, so no bodies jump).
// Joint damping is a compliant drive row in the joint's block of the factorization (implicit, so
// stable for any value), Coulomb joint friction a bounded extra row (core/joints/drive.h). Position
// servos and velocity motors share those rows below their effort limits and become bounded extra
// rows at them (the step's first solve is then taken again); effort actuators and external loads
// join gravity in the free velocities (core/actuation.h). Each step ends by continuing the joints'
// angles across +-pi (State::jointAngles), which limits and servos read.
// Velocity level (docs/method.md §4): u* = u + h M^-1 f, then the joint impulses
// solve M u' = M u* + J^T lambda, J u' = 0 with the chosen solver. Positions: x += h v,
// R = exp(h w) R (a rotation-vector update, so orientations stay unit).
// Drift (docs/method.md §7): the joint position conditions C(q) are driven back to zero by a
// further impulse along J^T, solved with the same factorization (a quasi-Newton iteration: J at
// the start of the step stands for J at the end; re-factored once when that is slow); the impulse changes
// velocities and positions together (SHAKE), so it is internal: momentum is conserved and no
// energy is injected by a bias velocity.
// Gyroscopic term: each body's world angular momentum I_W w is carried through the rotation
// update (w = I_W(R_new)^-1 I_W(R_old) w), so a free body's angular momentum is exact.
//
// The second-order scheme (`rattle`, Simulator::stepRattle) is RATTLE on the bodies' positions
// and rotations: half kick h/2 g; impulses along J(q_n)^T chosen so that the drifted positions
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
#include "core/failure_hint.h"
#include "core/free_rotation.h"
#include "core/impulse_solver.h"

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
    int stabilizationIterations = 40;
    double restitutionSpeed = 0.1; // m/s: slower impacts do not bounce, so things come to rest
    double penetrationSlop = 5e-4; // m: overlap left to the next steps' contacts, not projected
    // Bounds of the penetration projection (core/penetration.h): a step displaces no body by more
    // than penetrationMaxSpeed * dt nor turns it by more than penetrationMaxAngularSpeed * dt, so
    // deep overlaps come out over several steps (at 1 ms: 5 mm and 0.02 rad a step; the bundled
    // scenes' projections stay below 1 m/s and 4.7 rad/s at 1 ms, 2 m/s and 13.4 rad/s at 1/30 s).
    // A row whose Delassus diagonal is below penetrationHeldRatio of its bodies' free-body value is
    // held by the joints (round-off: a row they leave free is above 0.03 in those scenes) and left
    // alone.
    double penetrationMaxSpeed = 5.0;         // m/s
    double penetrationMaxAngularSpeed = 20.0; // rad/s
    double penetrationHeldRatio = 1e-9;
    double limitMargin = 0.02;       // rad or m: limit rows appear this close to a limit
    ExtraSolveSettings contactSolve; // tolerance of the contact problem
    // Resting contact may solve with the Delassus matrix of a recent step with the same rows, the
    // result checked exactly against this step's (Simulator::solveWithLastDelassus); false always
    // builds this step's matrix when the carried-over impulses do not hold.
    bool reuseDelassus = true;
};

// How a step's contact problem was solved.
enum class ContactRoute
{
    None,    // no extra rows
    Carried, // the last step's impulses still met every condition
    Reused,  // Gauss-Seidel on a recent step's G, checked exactly against this step's rows
    Built,   // this step's G, then Gauss-Seidel
};
inline constexpr std::size_t cContactRoutes = 4;

// Index of a route in per-route counts (arrays of cContactRoutes).
constexpr std::size_t routeIndex(ContactRoute route)
{
    return static_cast<std::size_t>(route);
}

// Stages of a step, timed (wall seconds): contact detection; free velocities, rows and the O(n)
// factorization; the impulse solve with the contact problem; positions, penetration and drift
// correction, momentum carry.
enum class StepStage
{
    Detect,
    Factor,
    Solve,
    Integrate,
};
inline constexpr std::size_t cStepStages = 4;

struct StepStats
{
    std::array<double, cStepStages> seconds{}; // wall time of each StepStage this step (s)
    double maxJointErrorM = 0.0;               // largest positional joint violation after the step (m)
    double maxJointErrorRad = 0.0;             // largest angular joint violation after the step (rad)
    int stabilizationIterations = 0;
    int contacts = 0;      // contact points found this step
    int extraRows = 0;     // contact, loop, limit and joint friction rows this step
    int contactSweeps = 0; // Gauss-Seidel sweeps of the contact problem
    ContactRoute contactRoute = ContactRoute::None;
    double maxPenetrationM = 0.0;    // deepest contact overlap at the start of the step (m)
    bool firstOrderFallback = false; // a rattle step that stalled and was taken by euler instead
};

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
    bool stepRattle(State& state); // false: stalled, state partly stepped
    bool mRattleStep = false;      // the step under way is a rattle step
    State mStepStart;              // the state a rattle step started from
    void checkState(const State& state, const char* where) const;
    void recordStartDefects(const State& state);
    std::string likelyCause(const State& state) const; // "; ..." for a failure message, or empty
    StartDefects mStartDefects;                        // what the first step found wrong with the start
    bool mStartRecorded = false;                       // mStartDefects is set
    void detectContacts(const State& state);
    void computeFreeVelocities(State& state, double h);
    void keepFreeVelocities(const State& state);
    bool actuatorsWithinLimits(State& state);
    std::vector<BodyState> mFree; // the free velocities of the step (actuators may solve again)
    void kickByGravity(State& state, double h);
    void factorAtStart(const State& state);
    void rowsAtStart(const State& state);
    bool samePose(const State& state, const std::vector<BodyState>& pose) const;
    void projectVelocities(State& state);
    void buildExtraRows(const State& state);
    void setMomentumRhs(const State& state, double tEnd);
    void solveContactImpulses(State& state);
    void integratePositions(State& state);
    void removePenetration(State& state);
    void restoreJoints(State& state);
    // A penetration displacement that recovers a deep defect (capped, or the one after a capped
    // step) or turns a body by more than this (rad) puts the joints back by restoreJoints. Below it
    // their second-order gap (theta^2 L / 2, under 5e-5 m at L = 1 m) is left to stabilizeJoints
    // as before (the bundled scenes turn bodies by up to 4.7e-3 rad a step at 1 ms).
    static constexpr double cRestoreRotation = 0.01;
    std::vector<Vec6> mJointErrorBefore; // restoreJoints: C per joint before the displacement
    bool mPenetrationCapped = false;     // the last step's penetration displacement was capped
    bool stabilizeJoints(State& state);  // false: a rattle step stalled
    void buildLoopRows(const RowSystem& rows);
    void correctLoops();
    Eigen::VectorXd mLoopCorrection; // loop impulses of this step's drift correction (N s, N m s)
    void addLoopCompliance();
    // Duration of one impulse solve (s): the step, or half of it for rattle, whose two velocity
    // stages each take half of the joints' damping and friction (core/joints/drive.h).
    double driveStep() const { return mRattleStep ? 0.5 * mDt : mDt; }
    void displacePositions(State& state, const BlockVector& displacement);
    void carryAngularMomentum(State& state);
    void measureJointErrors(const RowSystem& rows);

    const Model& mModel;
    StepOptions mOptions;
    ContactSource* mContactSource;
    std::vector<Contact> mContacts;
    std::vector<ExtraBlock> mExtra; // contacts, loops, limits, joint friction of this step
    Eigen::MatrixXd mG;             // their Delassus matrix
    Eigen::VectorXd mExtraVelocity, mExtraLambda;
    ExtraSolveScratch mExtraScratch;
    RowCoupling mCoupling;                                   // rows each extra block can move
    RowCoupling mPenetrationCoupling;                        // the same for removePenetration's rows
    RowCoupling mEndCoupling;                                // and for the rattle projection's
    std::vector<std::vector<std::pair<int, int>>> mTreeRuns; // scratch of coupleRowsByTree
    // Scratch of removePenetration: its blocks, their rows in mG, their G, free velocity, impulses.
    std::vector<ExtraBlock> mPenetrationBlocks;
    std::vector<int> mPenetrationRows;
    Eigen::MatrixXd mPenetrationG;
    Eigen::VectorXd mPenetrationFree, mPenetrationImpulse;
    std::vector<ExtraBlock> mLoopBlocks; // loop joints alone, for the stabilization
    Eigen::MatrixXd mLoopG;
    Eigen::LDLT<Eigen::MatrixXd> mLoopLdlt;
    Eigen::VectorXd mLoopError;       // C of the loop rows (m, rad)
    std::vector<int> mLimitedJoints;  // joints with limits (revolute, prismatic)
    std::vector<int> mFrictionJoints; // joints with Coulomb friction (a bounded drive row per coordinate)
    // Warm start: last step's contacts and their impulses (normal, two tangents; N s).
    std::vector<Contact> mPreviousContacts;
    std::vector<Vec3> mPreviousImpulses;
    // mPreviousContacts by body pair, then index: (bodyPairKey, index)
    std::vector<std::pair<std::uint64_t, int>> mPreviousOrder;
    static std::uint64_t bodyPairKey(const Contact& c);
    bool warmStart();
    void carryImpulses();
    void applyImpulseChange(BlockVector& solution);
    bool lastImpulsesStillHold();
    bool solveWithLastDelassus();
    void buildDelassus();
    // What identifies an extra block for reusing mG (contacts by bodies, point and normal).
    struct RowKey
    {
        ExtraBlock::Kind kind;
        int count, bodyA, bodyB, source;
        int actuator;   // drives: the actuator at its limit, -1 joint friction
        Vec3 point_W;   // contacts (m)
        Vec6 direction; // contacts: the normal; loops, limits: the first row of J
    };
    RowKey rowKey(const ExtraBlock& block) const;
    // Loops and limits: the same kind of block of the same joint, a limit on the same side.
    static bool sameJointRows(const RowKey& now, const RowKey& then);
    struct JointImpulse // last step's impulse of a loop or limit block
    {
        RowKey key;
        Vec6 lambda; // N s or N m s
    };
    std::vector<JointImpulse> mPreviousJointImpulses;
    bool sameRowsAsLastDelassus() const;
    static constexpr int cMaxDelassusAge = 50; // steps a G~ may stand in for the current G
    std::vector<RowKey> mDelassusRows;         // the blocks mG was built for
    int mDelassusAge = -1;                     // steps since mG was built, -1 none
    std::uint64_t mDelassusVersion = 0;        // counts the builds of mG (names it for solveExtraRowsFrom)
    void rememberImpulses();
    FrontierLayout mLayout;
    Actuation mActuation; // servos, motors, effort actuators and loads
    std::unique_ptr<ImpulseSolver> mSolver;
    RowSystem mRows;           // rows at the start of the step (the factored ones)
    RowSystem mRowsAfter;      // rows re-evaluated after the position update (errors only)
    RowSystem mRowsRefactored; // rows of a re-factorization when the quasi-Newton iteration is slow
    BlockVector mTrial;        // velocities with trial impulses (reuse rounds)
    // The warm-start impulses that the step's first solve included (mSolution = u(mBaseLambda));
    // mWarm: some impulse was carried from the last step.
    Eigen::VectorXd mBaseLambda, mImpulseChange;
    bool mWarm = false;
    bool mDelassusValid = false; // mG and mCoupling belong to this step's extra rows
    BlockVector mRhs, mSolution, mCorrection;
    std::vector<BodyState> mStart; // poses at the start of the step
    std::vector<Vec3> mMomentum;   // world angular momentum per body during the step
    // rattle: principal axes per body; the pose at which mRows was factored by the last step's
    // velocity projection (reused when the next step starts there); the projection's extra rows.
    std::vector<PrincipalAxes> mPrincipal;
    std::vector<BodyState> mFactoredPose;
    bool mFactoredPoseValid = false;
    // euler: the end pose of the last step, at which mRowsAfter holds the rows (reused as the
    // next step's mRows when it starts there).
    std::vector<BodyState> mEndPose;
    bool mEndRowsValid = false;
    std::vector<ExtraBlock> mEndBlocks;
    Eigen::MatrixXd mEndG;
    Eigen::VectorXd mEndVelocity, mEndLambda;
    StepStats mStats;
    int mWorstJoint = 0; // joint of the largest violation in the last measurement
    double mDt;
};

} // namespace frontier::core
