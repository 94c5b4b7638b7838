// core/actuation.cpp: servos and motors as drive rows (in their joints' blocks or bounded extra
// rows), effort actuators and loads as applied forces.
#include "core/actuation.h"

#include "core/impulse_solver.h"
#include "core/joints/coordinates.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace frontier::core
{

namespace
{
bool drivesRow(const Actuator& actuator)
{
    return actuator.kind != ActuatorKind::Effort;
}

// The actuator's own spring and damper (without the joint's damping).
DriveGains actuatorGains(const Actuator& actuator)
{
    DriveGains gains;
    gains.stiffness = actuator.kind == ActuatorKind::Position ? actuator.kp : 0.0;
    gains.damping = actuator.kd;
    gains.rigid = actuator.kind == ActuatorKind::Velocity && actuator.kd == 0.0;
    return gains;
}

// u += M^-1 [p; L] for a moving body at its pose in `state` (p in N s, L in N m s, world frame).
void addImpulse(const Model& model, State& state, int body, const Vec3& linear, const Vec3& angular)
{
    const Body& b = model.bodies[static_cast<std::size_t>(body)];
    BodyState& s = state.bodies[static_cast<std::size_t>(body)];
    s.velocity_W += linear / b.mass;
    s.angularVelocity_W += worldInertia(b, s).ldlt().solve(angular);
}

// A model built in code gets the checks io makes of a scene file.
void checkActuator(const Model& model, const Actuator& actuator)
{
    if (actuator.joint < 0 || actuator.joint >= static_cast<int>(model.joints.size()))
    {
        throw std::invalid_argument("an actuator names joint index " + std::to_string(actuator.joint) +
                                    ", which does not exist");
    }
    const Joint& joint = model.joints[static_cast<std::size_t>(actuator.joint)];
    const bool gainsValid = actuator.kp >= 0.0 && actuator.kd >= 0.0 && std::isfinite(actuator.kp) &&
                            std::isfinite(actuator.kd) && actuator.effortLimit > 0.0;
    if (coordinateIndex(joint.type, actuator.coordinate) < 0 || !gainsValid)
    {
        throw std::invalid_argument("the actuator on joint '" + joint.name +
                                    "' needs a coordinate its joint has, gains >= 0 and an effort limit > 0");
    }
}

// The length of [t0, t1) n [from, to) (s), 0 when they do not meet.
double overlap(double t0, double t1, double from, double to)
{
    return std::max(0.0, std::min(t1, to) - std::max(t0, from));
}
} // namespace

Actuation::Actuation(const Model& model, const FrontierLayout& layout) : mModel(model)
{
    const std::size_t n = model.actuators.size();
    mRow.resize(n);
    mLoop.assign(n, 0);
    mMemory.bounded.assign(n, 0);
    for (std::size_t a = 0; a < n; ++a)
    {
        const Actuator& actuator = model.actuators[a];
        checkActuator(model, actuator);
        const Joint& joint = model.joints[static_cast<std::size_t>(actuator.joint)];
        mRow[a] = jointRowCount(joint.type) + coordinateIndex(joint.type, actuator.coordinate);
        if (drivesRow(actuator))
        {
            ++mDriveActuators;
            mLoop[a] = layout.jointBlock[static_cast<std::size_t>(actuator.joint)] < 0 ? 1 : 0;
            mMemory.bounded[a] = mLoop[a];
        }
    }
    for (const Load& load : model.loads)
    {
        if (!isMovingBody(model, load.body))
        {
            throw std::invalid_argument("a load acts on a moving body, not body index " +
                                        std::to_string(load.body));
        }
    }
    mStepImpulse.assign(n, 0.0);
    mStepAtLimit.assign(n, 0);
    mMemory.lastFraction.assign(n, 0.0);
    mMemory.efforts.assign(n, ActuatorEffort{});
    mMemory.targets.resize(n);
    updateGains();
}

void Actuation::setTarget(std::size_t actuator, TimeFunction target)
{
    mMemory.targets.at(actuator) = std::move(target);
}

const TimeFunction& Actuation::targetOf(std::size_t a) const
{
    return mMemory.targets[a] ? *mMemory.targets[a] : mModel.actuators[a].target;
}

void Actuation::updateGains()
{
    if (mDriveActuators == 0)
    {
        return;
    }
    mMemory.gains.resize(mModel.joints.size());
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        mMemory.gains[k] = dampingGains(mModel.joints[k]);
    }
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (!drivesRow(actuator) || mMemory.bounded[a])
        {
            continue;
        }
        const Joint& joint = mModel.joints[static_cast<std::size_t>(actuator.joint)];
        DriveGains& row = mMemory.gains[static_cast<std::size_t>(actuator.joint)]
                                       [static_cast<std::size_t>(mRow[a] - jointRowCount(joint.type))];
        const DriveGains own = actuatorGains(actuator);
        row.stiffness += own.stiffness;
        row.damping += own.damping;
        row.rigid = own.rigid;
    }
}

void Actuation::addWrench(int body, const Vec3& force_N, const Vec3& torque_Nm)
{
    if (body < 0 || body >= static_cast<int>(mModel.bodies.size()))
    {
        throw std::out_of_range("a wrench on body index " + std::to_string(body) + ", which does not exist");
    }
    if (!isMovingBody(mModel, body))
    {
        throw std::invalid_argument("a wrench on the static body '" +
                                    mModel.bodies[static_cast<std::size_t>(body)].name +
                                    "', which nothing moves");
    }
    if (!force_N.allFinite() || !torque_Nm.allFinite())
    {
        throw std::invalid_argument("a wrench on body '" +
                                    mModel.bodies[static_cast<std::size_t>(body)].name +
                                    "' needs a finite force (N) and torque (N m)");
    }
    const auto same = std::find_if(mMemory.wrenches.begin(), mMemory.wrenches.end(),
                                   [body](const Wrench& wrench) { return wrench.body == body; });
    if (same == mMemory.wrenches.end())
    {
        mMemory.wrenches.push_back({body, force_N, torque_Nm});
        return;
    }
    same->force += force_N;
    same->torque += torque_Nm;
}

void Actuation::beginStep(double start, double dt)
{
    mStepFrom = start;
    mStepTo = start + dt;
    clearStepImpulses();
}

void Actuation::clearStepImpulses()
{
    std::fill(mStepImpulse.begin(), mStepImpulse.end(), 0.0);
    std::fill(mStepAtLimit.begin(), mStepAtLimit.end(), 0);
}

void Actuation::applyForces(State& state, double t0, double t1)
{
    // A backward interval (t1 < t0: the middle stage of rattle4, docs/method.md §11) takes the
    // loads of [t1, t0) with the opposite sign, so the stages of a step add up to its interval.
    const double sign = t1 < t0 ? -1.0 : 1.0;
    const double from = std::min(t0, t1);
    const double to = std::max(t0, t1);
    for (const Load& load : mModel.loads)
    {
        const double duration = load.instant ? 0.0 : overlap(from, to, load.from, load.to);
        const bool now = load.instant && *load.instant >= from && *load.instant < to;
        if (!(duration > 0.0) && !now)
        {
            continue;
        }
        const double scale = sign * (now ? 1.0 : duration); // an impulse as it is, a force times its time
        const BodyState& s = state.bodies[static_cast<std::size_t>(load.body)];
        const bool bodyFrame = load.frame == LoadFrame::Body;
        const Vec3 force = bodyFrame ? Vec3(s.orientation_WB * load.force) : load.force;
        const Vec3 torque = bodyFrame ? Vec3(s.orientation_WB * load.torque) : load.torque;
        Vec3 lever = Vec3::Zero(); // from the centre of mass to the point of application (m)
        if (load.point)
        {
            lever = bodyFrame ? Vec3(s.orientation_WB * *load.point) : Vec3(*load.point - s.position_W);
        }
        addImpulse(mModel, state, load.body, scale * force, scale * (torque + lever.cross(force)));
    }
    const double wrenchScale = sign * overlap(from, to, mStepFrom, mStepTo); // s
    for (const Wrench& wrench : mMemory.wrenches)
    {
        addImpulse(mModel, state, wrench.body, wrenchScale * wrench.force, wrenchScale * wrench.torque);
    }
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (actuator.kind != ActuatorKind::Effort)
        {
            continue;
        }
        const double commanded = valueAt(targetOf(a), t0); // N m or N
        const double effort = std::clamp(commanded, -actuator.effortLimit, actuator.effortLimit);
        mStepAtLimit[a] = mStepAtLimit[a] || std::abs(commanded) > actuator.effortLimit;
        const double impulse = effort * (t1 - t0);
        mStepImpulse[a] += impulse;
        const Joint& joint = mModel.joints[static_cast<std::size_t>(actuator.joint)];
        const CoordinateRow row =
            coordinateRow(joint, detail::jointGeometry(joint, jointPose(state, joint)), actuator.coordinate);
        addImpulse(mModel, state, joint.child, impulse * row.J_b.head<3>(), impulse * row.J_b.tail<3>());
        if (isMovingBody(mModel, joint.parent))
        {
            addImpulse(mModel, state, joint.parent, impulse * row.J_a.head<3>(), impulse * row.J_a.tail<3>());
        }
    }
}

Actuation::Command Actuation::command(std::size_t a, const State& state, double tEnd) const
{
    const Actuator& actuator = mModel.actuators[a];
    Command c;
    if (actuator.kind == ActuatorKind::Velocity)
    {
        c.speed = valueAt(targetOf(a), tEnd);
        c.force = actuator.kd * c.speed;
        return c;
    }
    const Joint& joint = mModel.joints[static_cast<std::size_t>(actuator.joint)];
    const double target = valueAt(targetOf(a), tEnd) - joint.initialPosition; // from the initial pose
    const double q = jointCoordinate(mModel, state, actuator.joint, actuator.coordinate);
    c.speed = rateAt(targetOf(a), tEnd);
    c.force = actuator.kd * c.speed - actuator.kp * (q - target);
    return c;
}

void Actuation::setRowTargets(const State& state, double tEnd, double h, BlockVector& rhs) const
{
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (!drivesRow(actuator) || mMemory.bounded[a])
        {
            continue;
        }
        const Joint& joint = mModel.joints[static_cast<std::size_t>(actuator.joint)];
        const std::size_t k = static_cast<std::size_t>(actuator.joint);
        const Command c = command(a, state, tEnd);
        const DriveGains& gains =
            mMemory.gains[k][static_cast<std::size_t>(mRow[a] - jointRowCount(joint.type))];
        rhs.joint[k](mRow[a]) = driveRow(gains, h, c.force, c.speed).target;
    }
}

void Actuation::appendBoundedRows(const State& state, double tEnd, double h,
                                  std::vector<ExtraBlock>& out) const
{
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (!drivesRow(actuator) || !mMemory.bounded[a])
        {
            continue;
        }
        const Command c = command(a, state, tEnd);
        const DriveRow drive = driveRow(actuatorGains(actuator), h, c.force, c.speed);
        if (!drive.active)
        {
            continue;
        }
        ExtraBlock& block = appendDriveBlock(mModel, state, actuator.joint, actuator.coordinate, out);
        block.compliance(0) = drive.compliance;
        block.target(0) = drive.target;
        block.bound = actuator.effortLimit * h;
        block.actuator = static_cast<int>(a);
    }
}

bool Actuation::acceptSolve(const RowSystem& rows, const BlockVector& solution,
                            const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda, double h)
{
    mSolveImpulse.assign(mModel.actuators.size(), 0.0);
    bool beyond = false;
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (!drivesRow(actuator) || mMemory.bounded[a])
        {
            continue;
        }
        // The row's impulse less the joint damping's share of it, -d h (J u').
        const std::size_t k = static_cast<std::size_t>(actuator.joint);
        const Joint& joint = mModel.joints[k];
        const JointRowsView r = rows.joints[k];
        double speed = r.J_b.row(mRow[a]).dot(solution.body[static_cast<std::size_t>(joint.child)]);
        if (isMovingBody(mModel, joint.parent))
        {
            speed += r.J_a.row(mRow[a]).dot(solution.body[static_cast<std::size_t>(joint.parent)]);
        }
        const double impulse = solution.joint[k](mRow[a]) + joint.damping * h * speed;
        if (std::abs(impulse) > actuator.effortLimit * h)
        {
            mMemory.bounded[a] = 1; // out of the block: a bounded extra row from now on
            beyond = true;
        }
        mSolveImpulse[a] = impulse;
    }
    if (beyond)
    {
        updateGains();
        return false;
    }
    for (const ExtraBlock& block : blocks)
    {
        if (block.kind == ExtraBlock::Kind::Drive && block.actuator >= 0)
        {
            mSolveImpulse[static_cast<std::size_t>(block.actuator)] = lambda(block.offset);
        }
    }
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (!drivesRow(actuator))
        {
            continue;
        }
        const double bound = actuator.effortLimit * h;
        const double fraction = std::abs(mSolveImpulse[a]) / bound; // 0 without a limit
        mMemory.lastFraction[a] = fraction;
        mStepAtLimit[a] = mStepAtLimit[a] || fraction >= 1.0;
        mStepImpulse[a] += mSolveImpulse[a];
    }
    return true;
}

bool Actuation::finishStep(double dt)
{
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        mMemory.efforts[a] = {mStepImpulse[a] / dt, mStepAtLimit[a] != 0};
    }
    bool changed = false;
    for (std::size_t a = 0; a < mModel.actuators.size(); ++a)
    {
        if (mMemory.bounded[a] && !mLoop[a] && mMemory.lastFraction[a] < cReleaseFraction)
        {
            mMemory.bounded[a] = 0;
            changed = true;
        }
    }
    if (changed)
    {
        updateGains();
    }
    clearStepImpulses();
    mMemory.wrenches.clear();
    return changed;
}

void Actuation::restore(const Memory& memory)
{
    mMemory = memory;
    clearStepImpulses();
}

} // namespace frontier::core
