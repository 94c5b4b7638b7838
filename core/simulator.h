// core/simulator.h: the fixed-step integrator and its step pipeline.
//
// One stepper per integrator (core/steppers/stepper.h) takes a step as a list of named stages that
// reads like the physics: euler in core/steppers/euler_stepper.h, rattle in
// core/steppers/rattle_stepper.h, rattle4 in core/steppers/rattle4_stepper.h, each header listing
// its pipeline (stage timings: StepStage, core/step_stats.h). The Simulator picks the stepper of
// the model's IntegratorKind and keeps what carries from step to step; the stages
// (core/step/step_stages.h) are calls into units of core/step/ with the step's context
// (core/step/step_context.h): the contact problem (contact_problem.h, with the warm start of
// impulse_memory.h), positions (positions.h), the penetration projection
// (penetration_projection.h), the drift correction (drift_correction.h), RATTLE's projection
// (rattle_projection.h), and the checks that stop a run that blew up (blow_up_check.h,
// core/simulation_error.h). None of them is part of the installed API: this header holds them
// behind a pointer.
//
// The first-order scheme (`euler`, core/steppers/euler_stepper.h): symplectic Euler with a
// SHAKE-type projection.
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
// The second-order scheme (`rattle`, core/steppers/rattle_stepper.h) is RATTLE on the bodies'
// positions and rotations. That is: half kick h/2 g; impulses along J(q_n)^T chosen so that the drifted
// positions satisfy C(q_{n+1}) = 0 (Newton iterations to stabilizationTolerance with the O(n) factorization);
// a drift at constant momenta (straight lines, and the split free rigid-body rotation of
// core/free_rotation.h on SO(3)); half kick; the velocity projection J(q_{n+1}) u_{n+1} = 0
// with the factorization at q_{n+1}, which the next step reuses. Contacts, limits and impacts
// are impulses of the first stage (first order across an impact, as any impulse method); contacts
// and limits that pushed in the first stage keep pushing (one-sided) in the final projection.
// Joint damping and friction, servos and motors act in both velocity stages, each over h/2 (a
// servo's spring at the stage's start pose, its targets at the stage's end), as do effort actuators
// and loads with gravity's half kicks.
//
// The fourth-order scheme (`rattle4`, core/steppers/rattle4_stepper.h, docs/method.md §11) composes
// three RATTLE stages (the triple jump); a step whose stage meets contact or limit rows is taken
// again as one rattle step.
#pragma once

#include "core/actuation.h"
#include "core/contact.h"
#include "core/frontier_order.h"
#include "core/large_vector.h"
#include "core/model.h"
#include "core/simulation_error.h"
#include "core/state.h"
#include "core/step_memory.h"
#include "core/step_options.h"
#include "core/step_stats.h"
#include "core/time_function.h"

#include <cstddef>
#include <memory>
#include <span>
#include <utility>
#include <vector>

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

    const FrontierLayout& layout() const;
    const StepStats& lastStep() const;
    // Joint violations of a state (m, rad), without stepping.
    std::pair<double, double> jointErrors(const State& state);
    // Joint impulses of the last step (per joint index; N s or N m s), row by row as in JointRows:
    // the joint's conditions, then its drive rows (the damping impulse, core/joints/drive.h).
    const LargeVector<Vec6>& jointImpulses() const;
    // What each actuator did in the last step (Model::actuators order): its effort, the impulse it
    // applied over the step divided by dt (N or N m, along its coordinate; drift corrections not
    // counted), and whether it sat at its effort limit (core/actuation.h).
    std::span<const ActuatorEffort> actuatorEfforts() const;
    // Replaces the target of Model::actuators[actuator] from the next step on, by a constant (rad
    // or m for a servo in the model file's coordinate, rad/s or m/s for a motor, N m or N for an
    // effort; Actuator::target) or by any TimeFunction of the simulation time. Throws
    // std::out_of_range for an index beyond Model::actuators.
    void setActuatorTarget(std::size_t actuator, double value);
    void setActuatorTarget(std::size_t actuator, TimeFunction target);

    // Pushes moving body `body` during the next step only: a force through its centre of mass and
    // a torque, world frame (N, N m), applied as the model's loads are (core/actuation.h), so its
    // impulse over the step is force_N dt and torque_Nm dt with every integrator. Wrenches given
    // twice before a step add up; the step forgets them. Throws std::out_of_range for an index
    // beyond Model::bodies, std::invalid_argument for a static body or a value that is not finite.
    void applyWrench(int body, const Vec3& force_N, const Vec3& torque_Nm);
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
    struct Impl; // core/simulator.cpp: the stepper of the integrator and the stages it takes
    std::unique_ptr<Impl> mImpl;
};

} // namespace frontier::core
