// tests/sim/actuator_test.cpp: actuators (core/actuation.h) against closed forms. A position servo
// on a pendulum swinging in the horizontal plane follows the damped oscillator I e'' + kd e' + kp e
// = 0 (1 % at dt = 1e-4) and stays bounded at omega dt = 10 (implicit); a velocity motor that
// cannot lift its rod pushes at its effort limit exactly while the rod falls at (tau_g - limit) / I,
// one that can holds its speed; an effort actuator accelerates a known body at tau / I; no
// actuator's impulse exceeds limit * dt in a chain of saturating servos, on either integrator and
// solver; the O(n) solver and the dense one agree with servos in the joint blocks; a target set at
// run time (Simulator::setActuatorTarget) is followed from then on.
#include "core/joints/coordinates.h"
#include "joint_models.h"
#include "sim_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace frontier::sim::test
{
namespace
{

using core::IntegratorKind;

core::Actuator actuatorOn(int joint, core::ActuatorKind kind, double target)
{
    core::Actuator a;
    a.joint = joint;
    a.kind = kind;
    a.target = core::constantFunction(target);
    return a;
}

// A 1 kg rod 0.5 m long along +x on a hinge at (0, 0, 1) about +z, gravity -z: it swings in the
// horizontal plane, so gravity exerts no torque about the hinge. A position servo to `target` (rad)
// with natural frequency omega (rad/s) and damping ratio zeta on its inertia about the hinge.
core::Model servoPendulum(IntegratorKind integrator, double dt, double target, double omega, double zeta)
{
    core::Model model = emptyTestModel(core::Vec3(0.0, 0.0, -9.81), integrator, dt);
    const core::Body rod = jointTestBox("rod", 1.0, core::Vec3(0.5, 0.04, 0.04), core::Vec3(0.25, 0.0, 1.0));
    model.bodies.push_back(rod);
    addTestJoint(model, core::JointType::Revolute, core::cWorld, 0, core::Vec3(0.0, 0.0, 1.0),
                 core::Vec3::UnitZ());
    const double inertia = rod.inertia_B(2, 2) + rod.mass * 0.25 * 0.25; // kg m^2 about the hinge
    core::Actuator servo = actuatorOn(0, core::ActuatorKind::Position, target);
    servo.kp = inertia * omega * omega;
    servo.kd = 2.0 * zeta * omega * inertia;
    model.actuators.push_back(servo);
    return model;
}

// e(t) = theta - target of I e'' + 2 zeta w I e' + w^2 I e = 0 from e(0) = -target, e'(0) = 0,
// underdamped (zeta < 1).
double dampedOscillator(double target, double omega, double zeta, double t)
{
    const double decay = zeta * omega;
    const double omegaD = omega * std::sqrt(1.0 - zeta * zeta);
    return -target * std::exp(-decay * t) * (std::cos(omegaD * t) + decay / omegaD * std::sin(omegaD * t));
}

TEST(Actuators, PositionServoOnAPendulumIsTheClosedFormDampedOscillator)
{
    constexpr double target = 0.3;                   // rad
    constexpr double omega = 2.0 * std::numbers::pi; // rad/s
    constexpr double zeta = 0.2;
    constexpr double dt = 1e-4;
    for (const IntegratorKind integrator : cIntegrators)
    {
        const core::Model model = servoPendulum(integrator, dt, target, omega, zeta);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        double worst = 0.0;
        for (long k = 0; k < stepsFor(3.0, dt); ++k)
        {
            simulator.step(state);
            const double expected = target + dampedOscillator(target, omega, zeta, state.time);
            worst = std::max(worst, std::abs(state.jointAngles[0] - expected));
        }
        RecordProperty(std::string("worst_error_rad_") + core::integratorName(integrator), sci(worst));
        EXPECT_LT(worst, 0.01 * target) << core::integratorName(integrator);
    }
}

// Simulator::setActuatorTarget: a servo holding the pendulum at 0 and given the target 0.3 rad at
// T = 0.5 s follows the same damped oscillator from T (a constant target: no rate to damp towards).
TEST(Actuators, TargetSetAtRunTimeIsFollowedFromThen)
{
    constexpr double target = 0.3;                   // rad
    constexpr double omega = 2.0 * std::numbers::pi; // rad/s
    constexpr double zeta = 0.2;
    constexpr double dt = 1e-4;
    constexpr double switchTime = 0.5; // s
    for (const IntegratorKind integrator : cIntegrators)
    {
        const core::Model model = servoPendulum(integrator, dt, 0.0, omega, zeta);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (long k = 0; k < stepsFor(switchTime, dt); ++k)
        {
            simulator.step(state);
        }
        EXPECT_EQ(state.jointAngles[0], 0.0) << core::integratorName(integrator);
        simulator.setActuatorTarget(0, target);
        double worst = 0.0;
        for (long k = 0; k < stepsFor(2.5, dt); ++k)
        {
            simulator.step(state);
            const double expected = target + dampedOscillator(target, omega, zeta, state.time - switchTime);
            worst = std::max(worst, std::abs(state.jointAngles[0] - expected));
        }
        EXPECT_LT(worst, 0.01 * target) << core::integratorName(integrator);
        EXPECT_THROW(simulator.setActuatorTarget(1, 0.0), std::out_of_range);
    }
}

// omega dt = 10 at dt = 1 ms: an explicit spring of this stiffness grows by ~omega dt every step;
// the implicit servo settles on its target and never swings beyond its start.
TEST(Actuators, StiffServoAtOmegaDtTenStaysBounded)
{
    constexpr double target = 0.3;
    constexpr double dt = 1e-3;
    constexpr double omega = 10.0 / dt;
    for (const IntegratorKind integrator : cIntegrators)
    {
        for (const double zeta : {0.0, 1.0})
        {
            const core::Model model = servoPendulum(integrator, dt, target, omega, zeta);
            core::Simulator simulator(model);
            core::State state = core::initialState(model);
            double worst = 0.0;
            for (int k = 0; k < 1000; ++k)
            {
                simulator.step(state);
                worst = std::max(worst, std::abs(state.jointAngles[0] - target));
            }
            const std::string what = std::string(core::integratorName(integrator)) + ", zeta " + sci(zeta);
            RecordProperty("final_error_" + what, sci(state.jointAngles[0] - target));
            EXPECT_LE(worst, target * (1.0 + 1e-9)) << what;
            if (zeta > 0.0)
            {
                // Critically damped it settles (undamped it would swing on at 1e4 rad/s, which no
                // 1 ms step resolves: bounded is what it must be).
                EXPECT_LT(std::abs(state.jointAngles[0] - target), 1e-6) << what;
            }
            EXPECT_TRUE(state.bodies[0].angularVelocity_W.allFinite()) << what;
        }
    }
}

// hingedRod: gravity pulls the tip down (a positive angle) with tau_g = m g L/2 cos(theta).
constexpr double cRodGravityTorque = 1.0 * 9.81 * 0.25; // N m, horizontal

double rodInertia(const core::Model& model)
{
    return model.bodies[0].inertia_B(1, 1) + model.bodies[0].mass * 0.25 * 0.25; // about the hinge
}

TEST(Actuators, VelocityMotorTooWeakToLiftPushesAtItsLimitExactly)
{
    constexpr double limit = 1.0; // N m < tau_g
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = hingedRod(0.0, std::nullopt, core::Vec3(0.0, 0.0, -9.81), integrator);
        core::Actuator motor = actuatorOn(0, core::ActuatorKind::Velocity, -1.0); // lift: tip up
        motor.effortLimit = limit;
        model.actuators.push_back(motor);
        const double inertia = rodInertia(model);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (int k = 0; k < 20; ++k)
        {
            simulator.step(state);
            const core::ActuatorEffort effort = simulator.actuatorEfforts()[0];
            EXPECT_NEAR(effort.effort, -limit, 1e-12) << "step " << k;
            EXPECT_TRUE(effort.atLimit) << "step " << k;
        }
        // It falls at (tau_g - limit) / I (cos(theta) = 1 to 1e-5 over these 20 ms).
        const double expected = (cRodGravityTorque - limit) / inertia * state.time;
        EXPECT_NEAR(state.bodies[0].angularVelocity_W.y(), expected, 2e-3 * expected)
            << core::integratorName(integrator);
    }
}

TEST(Actuators, VelocityMotorStrongEnoughHoldsItsTargetSpeed)
{
    constexpr double limit = 5.0; // N m > tau_g
    constexpr double speed = -1.0;
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = hingedRod(0.0, std::nullopt, core::Vec3(0.0, 0.0, -9.81), integrator);
        core::Actuator motor = actuatorOn(0, core::ActuatorKind::Velocity, speed);
        motor.effortLimit = limit;
        model.actuators.push_back(motor);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        bool reached = false;
        for (int k = 0; k < 500; ++k)
        {
            simulator.step(state);
            const core::ActuatorEffort effort = simulator.actuatorEfforts()[0];
            EXPECT_LE(std::abs(effort.effort), limit * (1.0 + 1e-12));
            const double w = state.bodies[0].angularVelocity_W.y();
            if (reached) // the step after the one that reached the speed, and on
            {
                ASSERT_NEAR(w, speed, 1e-9) << "step " << k;
                // At a constant speed the motor carries gravity's torque.
                const double theta = state.jointAngles[0];
                EXPECT_NEAR(effort.effort, -cRodGravityTorque * std::cos(theta), 0.02 * cRodGravityTorque)
                    << "step " << k;
            }
            reached = reached || std::abs(w - speed) < 1e-9;
        }
        EXPECT_TRUE(reached) << core::integratorName(integrator);
    }
}

TEST(Actuators, EffortActuatorAcceleratesAtTauOverI)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        for (const double limit : {std::numeric_limits<double>::infinity(), 2.0})
        {
            core::Model model = spinningBox(0.0, integrator);
            core::Actuator effort = actuatorOn(0, core::ActuatorKind::Effort, 3.0); // N m
            effort.effortLimit = limit;
            model.actuators.push_back(effort);
            const double inertia = model.bodies[0].inertia_B(2, 2);
            const double torque = std::min(3.0, limit);
            core::Simulator simulator(model);
            core::State state = core::initialState(model);
            for (int k = 0; k < 100; ++k)
            {
                simulator.step(state);
                EXPECT_NEAR(simulator.actuatorEfforts()[0].effort, torque, 1e-12);
                EXPECT_EQ(simulator.actuatorEfforts()[0].atLimit, limit < 3.0);
            }
            EXPECT_NEAR(state.bodies[0].angularVelocity_W.z(), torque / inertia * state.time, 1e-10)
                << core::integratorName(integrator);
        }
    }
}

TEST(Actuators, EffortActuatorOnASliderAcceleratesAtFOverM)
{
    core::Model model = slidingBox(0.0, core::Vec3(1.0, 1.0, 0.0), core::Vec3::Zero());
    core::Actuator force = actuatorOn(0, core::ActuatorKind::Effort, 6.0); // N
    force.coordinate = core::JointCoordinate::Slide;
    model.actuators.push_back(force);
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    for (int k = 0; k < 100; ++k)
    {
        simulator.step(state);
    }
    const double speed = state.bodies[0].velocity_W.dot(core::Vec3(1.0, 1.0, 0.0).normalized());
    EXPECT_NEAR(speed, 6.0 / model.bodies[0].mass * state.time, 1e-12);
}

// Servos on a hanging chain of four rods, stiff, with a small effort limit, chasing targets that
// swing by a radian: some steps push at the limit (out of the joint blocks), some within it (in).
core::Model saturatingChain(IntegratorKind integrator, core::SolverKind solver)
{
    core::Model model = hingedChain(4, integrator);
    model.simulation.solver = solver;
    for (int k = 0; k < 4; ++k)
    {
        core::Actuator servo;
        servo.joint = k;
        servo.kp = 400.0;
        servo.kd = 5.0;
        servo.effortLimit = 6.0 - k;
        servo.target = core::sineFunction(1.0, 0.7 + 0.3 * k, 0.5 * k, 0.2);
        model.actuators.push_back(servo);
    }
    model.joints[1].damping = 0.3; // damping shares a servo's row
    return model;
}

TEST(Actuators, NoImpulseExceedsTheEffortLimit)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        for (const core::SolverKind solver : {core::SolverKind::Linear, core::SolverKind::Dense})
        {
            const core::Model model = saturatingChain(integrator, solver);
            core::Simulator simulator(model);
            core::State state = core::initialState(model);
            int atLimit = 0;
            int within = 0;
            for (int k = 0; k < 2000; ++k)
            {
                simulator.step(state);
                for (std::size_t a = 0; a < model.actuators.size(); ++a)
                {
                    const core::ActuatorEffort e = simulator.actuatorEfforts()[a];
                    const double limit = model.actuators[a].effortLimit;
                    ASSERT_LE(std::abs(e.effort) * model.simulation.dt,
                              limit * model.simulation.dt * (1.0 + 1e-15))
                        << "actuator " << a << ", step " << k;
                    atLimit += e.atLimit ? 1 : 0;
                    within += std::abs(e.effort) < 0.5 * limit ? 1 : 0;
                }
            }
            const std::string what =
                std::string(core::integratorName(integrator)) + "/" + core::solverName(solver);
            EXPECT_GT(atLimit, 100) << what;
            EXPECT_GT(within, 100) << what;
            EXPECT_LT(simulator.jointErrors(state).first, 1e-9) << what;
        }
    }
}

TEST(Actuators, LinearAndDenseSolversAgreeWithServos)
{
    const core::Model linear = saturatingChain(IntegratorKind::Euler, core::SolverKind::Linear);
    const core::Model dense = saturatingChain(IntegratorKind::Euler, core::SolverKind::Dense);
    core::Simulator a(linear);
    core::Simulator b(dense);
    core::State sa = core::initialState(linear);
    core::State sb = core::initialState(dense);
    for (int k = 0; k < 500; ++k)
    {
        a.step(sa);
        b.step(sb);
    }
    for (std::size_t i = 0; i < sa.bodies.size(); ++i)
    {
        EXPECT_LT((sa.bodies[i].position_W - sb.bodies[i].position_W).norm(), 1e-8) << "body " << i;
        EXPECT_LT((sa.bodies[i].angularVelocity_W - sb.bodies[i].angularVelocity_W).norm(), 1e-6)
            << "body " << i;
    }
}

TEST(Actuators, AModelBuiltInCodeIsCheckedLikeAScene)
{
    core::Model ball = emptyTestModel(core::Vec3::Zero(), IntegratorKind::Euler, 1e-3);
    ball.bodies.push_back(jointTestBox("b", 1.0, core::Vec3(0.1, 0.1, 0.1), core::Vec3::Zero()));
    addTestJoint(ball, core::JointType::Ball, core::cWorld, 0, core::Vec3::Zero(), core::Vec3::UnitZ());
    ball.actuators.push_back(
        actuatorOn(0, core::ActuatorKind::Effort, 1.0)); // a ball joint has no coordinate
    EXPECT_THROW(core::Simulator{ball}, std::invalid_argument);
    core::Model negative = spinningBox(0.0);
    negative.actuators.push_back(actuatorOn(0, core::ActuatorKind::Position, 0.0));
    negative.actuators.back().kd = -1.0;
    EXPECT_THROW(core::Simulator{negative}, std::invalid_argument);
}

} // namespace
} // namespace frontier::sim::test
