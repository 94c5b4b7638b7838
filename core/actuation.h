// core/actuation.h: the model's actuators and external loads within a step (Model::actuators,
// Model::loads).
//
// Position servos and velocity motors are drive rows (core/joints/drive.h). Below its effort limit
// an actuator shares the drive row of its coordinate in the joint's block of the O(n)
// factorization (with the joint's damping: stiffness kp, damping d + kd, implicit, so any gain is
// stable); its right-hand side c = f0 / (h kp + d + kd), f0 = kd v* - kp (q - q*), with q the
// coordinate at the start of the solve and the targets q*, v* = dq*/dt at its end (a velocity
// motor: f0 = kd v*, or the rigid row J u = v* when kd = 0). Its impulse in a solve is the row's
// impulse less the damping's, lambda + d h (J u'). When that goes beyond limit * h, the solve is
// taken again with the actuator out of the block (its row there damps only) and as a bounded extra
// row (ExtraBlock::Kind::Drive: J u + E lambda = c with its own E, c and |lambda| <= limit * h,
// clamped exactly by the contact problem's Gauss-Seidel), where it stays while it pushes at
// more than cReleaseFraction of its limit. So the impulse of every actuator in a solve is at most
// limit * h, and a scene whose actuators stay below their limits keeps the joint tree's exact
// O(n) solve. An actuator of a loop-closing joint is always an extra row.
//
// Effort actuators (clamped to their limit), loads and the external wrenches given for the next
// step (addWrench) are applied forces: each solve starts from u* = u + M^-1 (their impulse over the
// solve), as gravity. A force over [from, to) gives the impulse F |[t0, t1) n [from, to)| over a
// solve [t0, t1), so the total is F (to - from) whatever the step; an impulse load lands in the one
// solve whose [t0, t1) holds its instant. An external wrench acts over the step it was given for,
// [from, to) = the step's [t, t + dt): its impulse over the step is F dt for every integrator.
//
// The drift correction moves drive rows too (their compliance is part of the factorization it
// reuses); those impulses keep the joints together and are not counted as the actuator's.
#pragma once

#include "core/extra_rows.h"
#include "core/frontier_order.h"
#include "core/joints/drive.h"
#include "core/state.h"

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace frontier::core
{

struct RowSystem;
struct BlockVector;

// What an actuator did in the last step.
struct ActuatorEffort
{
    double effort = 0.0;  // N or N m along its coordinate: its impulse over the step / dt
    bool atLimit = false; // it pushed at its effort limit (an effort actuator: its command was clipped)
};

class Actuation
{
  public:
    // Throws std::invalid_argument for an actuator on a coordinate its joint lacks, negative gains,
    // a limit <= 0, or a load on a static body (io refuses these in scene files with file:line).
    Actuation(const Model& model, const FrontierLayout& layout);

    // Per joint, the gains of its drive rows with the actuators now in the joints' blocks (for
    // assembleRows); empty when no actuator can be in a block.
    std::span<const JointDriveGains> gains() const { return mMemory.gains; }
    // Some position or velocity actuator: solves are measured and may be taken again.
    bool hasDriveRows() const { return mDriveActuators > 0; }

    // Replaces the target of Model::actuators[actuator] from the next solve on (the model's own
    // target is no longer read; units as Actuator::target). Throws std::out_of_range for an index
    // beyond Model::actuators.
    void setTarget(std::size_t actuator, TimeFunction target);

    // Adds a force through body's centre of mass and a torque (world frame; N, N m) to what acts on
    // it over the next step only (wrenches given twice add up); finishStep() forgets them. Throws
    // std::out_of_range for an index beyond Model::bodies, std::invalid_argument for a static body
    // or a value that is not finite.
    void addWrench(int body, const Vec3& force_N, const Vec3& torque_Nm);

    // A new step over [start, start + dt) (s), the interval of the external wrenches: forgets the
    // impulses of an earlier attempt of it.
    void beginStep(double start, double dt);
    // Effort actuators and loads over [t0, t1) (s) at the pose of `state`: its moving bodies'
    // velocities change by M^-1 times their impulse. t1 < t0 (a backward stage of rattle4) gives
    // the opposite of the impulse over [t1, t0).
    void applyForces(State& state, double t0, double t1);
    // The right-hand side c of the in-block rows of a solve of duration h (s) ending at tEnd (s), at
    // the pose of `state` (rhs.joint: per joint, rows as in JointRows).
    void setRowTargets(const State& state, double tEnd, double h, BlockVector& rhs) const;
    // Bounded extra rows of the actuators out of their blocks, for the same solve.
    void appendBoundedRows(const State& state, double tEnd, double h, std::vector<ExtraBlock>& out) const;
    // After a solve of duration h: `rows` as factored, `solution` its velocities and joint impulses,
    // `blocks` and `lambda` its extra rows. False when an actuator in its block went beyond its
    // limit: it is now out of the block (gains() changed) and the solve must be taken again with
    // rows assembled anew. True: the solve's actuator impulses count for the step.
    bool acceptSolve(const RowSystem& rows, const BlockVector& solution,
                     const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda, double h);
    // The step of duration dt (s) is done: efforts() gives its efforts. Actuators out of their
    // blocks that no longer push near their limit go back in; true when gains() changed.
    bool finishStep(double dt);

    // Per Model::actuators entry, after finishStep.
    std::span<const ActuatorEffort> efforts() const { return mMemory.efforts; }

    // An out-of-block actuator returns to its block when its impulse fell below this fraction of its
    // bound (a margin, so one near its limit does not go in and out every step).
    static constexpr double cReleaseFraction = 0.9;

  private:
    struct Wrench // an external wrench for the next step, world frame
    {
        int body = 0;
        Vec3 force = Vec3::Zero();  // N, through the centre of mass
        Vec3 torque = Vec3::Zero(); // N m
    };

  public:
    // What carries over from one step to the next (core/step_memory.h), kept in one member: a
    // field added here is saved and restored with the rest.
    struct Memory
    {
        std::vector<std::uint8_t> bounded;   // per actuator: out of its block (a bounded extra row)
        std::vector<JointDriveGains> gains;  // per joint; empty without drive actuators
        std::vector<double> lastFraction;    // per actuator: |impulse| / bound in its last solve
        std::vector<ActuatorEffort> efforts; // the last finished step
        // Per actuator: the target given to setTarget, or none (the model's).
        std::vector<std::optional<TimeFunction>> targets;
        std::vector<Wrench> wrenches; // for the next step, one per body, in the order first given
    };
    const Memory& memory() const { return mMemory; }
    void restore(const Memory& memory); // the memory of an Actuation of the same model

  private:
    void clearStepImpulses();
    void updateGains();
    // f0 (N or N m) and the targets of a servo or motor for a solve ending at tEnd, at `state`.
    struct Command
    {
        double force = 0.0; // f0 = kd v* - kp (q - q*)
        double speed = 0.0; // v* (m/s or rad/s)
    };
    Command command(std::size_t a, const State& state, double tEnd) const;
    // The target actuator a follows: one given to setTarget, else the model's.
    const TimeFunction& targetOf(std::size_t a) const;

    const Model& mModel;
    std::vector<int> mRow;            // per actuator: its drive row in the joint's block
    std::vector<std::uint8_t> mLoop;  // per actuator: its joint closes a loop (always bounded)
    int mDriveActuators = 0;          // position and velocity actuators
    std::vector<double> mStepImpulse; // per actuator, this step (N s or N m s)
    std::vector<std::uint8_t> mStepAtLimit;
    std::vector<double> mSolveImpulse; // scratch of acceptSolve
    Memory mMemory;                    // what carries over to the next step
    double mStepFrom = 0.0;            // the step under way: [mStepFrom, mStepTo) (s)
    double mStepTo = 0.0;
};

} // namespace frontier::core
