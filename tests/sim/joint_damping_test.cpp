// tests/sim/joint_damping_test.cpp: viscous damping and Coulomb friction of joints (core::Joint
// damping, friction; core/joints/drive.h) against closed forms. Damping is implicit: a box spinning
// on a damped hinge leaves each step at w / (1 + c h / I) exactly (rattle: two half steps), decays
// as exp(-c t / I) to first order in h, and stays monotone for any c. Friction f holds a rod whose
// gravity torque is smaller, lets a larger one accelerate at (tau - f) / I, and stops a wheel after
// I w0 / f seconds. The same for a prismatic joint, in N s/m and N. Energy never rises, and the
// solvers agree with damping in the factorization.
#include "joint_models.h"
#include "sim_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

namespace frontier::sim::test
{
namespace
{

using core::IntegratorKind;

constexpr double cGravity = 9.81; // m/s^2

// The box's inertia about its hinge (kg m^2).
double hingeInertia(const core::Model& model)
{
    return model.bodies[0].inertia_B(2, 2);
}

// How much one step of implicit damping keeps: 1 / (1 + c h / m) for euler; rattle damps in each of
// its two velocity stages over h / 2.
double keptPerStep(double c, double h, double inertia, IntegratorKind integrator)
{
    if (integrator == IntegratorKind::Euler)
    {
        return 1.0 / (1.0 + c * h / inertia);
    }
    const double half = 1.0 / (1.0 + 0.5 * c * h / inertia);
    return half * half;
}

// Steps a one-joint model with damping c for 1 s: the body's speed along the joint (`speed`, m/s or
// rad/s) loses the implicit factor of keptPerStep every step, to round-off. `inertia`: the mass or
// moment of inertia the joint moves (kg or kg m^2).
void expectImplicitDecay(core::Model model, double c, double inertia, double (*speed)(const core::State&))
{
    model.joints[0].damping = c;
    const IntegratorKind integrator = model.simulation.integrator;
    const double kept = keptPerStep(c, model.simulation.dt, inertia, integrator);
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    double expected = speed(state);
    const double scale = std::abs(expected);
    for (int k = 0; k < 1000; ++k)
    {
        simulator.step(state);
        expected *= kept;
        ASSERT_NEAR(speed(state), expected, 1e-12 * scale)
            << core::integratorName(integrator) << ", step " << k;
    }
}

TEST(JointDamping, SpinningBoxLosesTheImplicitEulerFactorEveryStep)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        const core::Model model = spinningBox(10.0, integrator);
        expectImplicitDecay(model, 0.02, hingeInertia(model),
                            [](const core::State& state) { return state.bodies[0].angularVelocity_W.z(); });
    }
}

TEST(JointDamping, SlidingBoxLosesTheImplicitEulerFactorEveryStep)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        const core::Model model = slidingBox(2.0, core::Vec3::UnitX(), core::Vec3::Zero(), integrator);
        expectImplicitDecay(model, 1.5, model.bodies[0].mass,
                            [](const core::State& state) { return state.bodies[0].velocity_W.x(); });
    }
}

// w(T) / w0 = (1 + c h / I)^-N = exp(-c T / I) (1 + (c / I)^2 T h / 2 + O(h^2)): the continuous
// decay to first order, with that leading error, at two step sizes.
TEST(JointDamping, SpinningBoxFollowsTheContinuousDecayToFirstOrder)
{
    const double w0 = 10.0;
    const double c = 0.02;
    const double seconds = 1.0;
    for (const double h : {1e-3, 5e-4})
    {
        core::Model model = spinningBox(w0, IntegratorKind::Euler, h);
        model.joints[0].damping = c;
        const double rate = c / hingeInertia(model); // 1/s
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (long k = 0; k < stepsFor(seconds, h); ++k)
        {
            simulator.step(state);
        }
        const double exact = w0 * std::exp(-rate * seconds);
        const double relative = state.bodies[0].angularVelocity_W.z() / exact - 1.0;
        const double leading = 0.5 * rate * rate * seconds * h;
        EXPECT_GT(relative, 0.95 * leading) << "h = " << h;
        EXPECT_LT(relative, 1.05 * leading) << "h = " << h;
    }
}

// c h / I = 1e6: an explicit damper would reverse the spin a million times over; the implicit row
// keeps w0 / (1 + 1e6) after one step, positive and falling.
TEST(JointDamping, HugeDampingIsStableAndMonotone)
{
    const double w0 = 10.0;
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = spinningBox(w0, integrator);
        const double inertia = hingeInertia(model);
        model.joints[0].damping = 1e6 * inertia / model.simulation.dt;
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        double previous = w0;
        for (int k = 0; k < 100; ++k)
        {
            simulator.step(state);
            const double w = state.bodies[0].angularVelocity_W.z();
            ASSERT_TRUE(std::isfinite(w));
            ASSERT_GE(w, 0.0) << "step " << k;
            ASSERT_LE(w, previous) << "step " << k;
            if (k == 0)
            {
                const double kept =
                    keptPerStep(model.joints[0].damping, model.simulation.dt, inertia, integrator);
                EXPECT_NEAR(w, w0 * kept, 1e-9 * w0 * kept) << core::integratorName(integrator);
            }
            previous = w;
        }
        EXPECT_LT(simulator.lastStep().maxJointErrorM, 1e-9);
    }
}

// The rod of joint_models.h held horizontal: gravity torque m g d about the hinge (d = 0.25 m).
double rodGravityTorque(const core::Model& model)
{
    return model.bodies[0].mass * cGravity * 0.25;
}

double rodHingeInertia(const core::Model& model)
{
    return model.bodies[0].inertia_B(1, 1) + model.bodies[0].mass * 0.25 * 0.25;
}

TEST(JointFriction, HoldsARodWhoseGravityTorqueIsSmaller)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = hingedRod(0.0, std::nullopt, core::Vec3(0.0, 0.0, -cGravity), integrator);
        model.joints[0].friction = 1.5 * rodGravityTorque(model);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (int k = 0; k < 1000; ++k)
        {
            simulator.step(state);
            // Round-off: one step of gravity alone would give tau h / I = 0.03 rad/s.
            ASSERT_LT(state.bodies[0].angularVelocity_W.norm(), 1e-12)
                << core::integratorName(integrator) << ", step " << k;
        }
        EXPECT_LT(std::abs(state.jointAngles[0]), 1e-12);
    }
}

TEST(JointFriction, RodWhoseGravityTorqueIsLargerAcceleratesAtTheNetTorque)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = hingedRod(0.0, std::nullopt, core::Vec3(0.0, 0.0, -cGravity), integrator);
        const double torque = rodGravityTorque(model);
        model.joints[0].friction = 0.4 * torque;
        const double acceleration = (torque - model.joints[0].friction) / rodHingeInertia(model); // rad/s^2
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (int k = 0; k < 5; ++k)
        {
            simulator.step(state);
        }
        // Over 5 ms the rod turns 2e-4 rad: the torque changes by a relative 2e-8.
        EXPECT_NEAR(state.bodies[0].angularVelocity_W.y(), acceleration * state.time,
                    1e-4 * acceleration * state.time)
            << core::integratorName(integrator);
    }
}

// Friction f takes f h of angular momentum every step until the wheel can stop within one: it
// stops at I w0 / f (to one step) and stays stopped.
TEST(JointFriction, SpinningBoxStopsAfterIw0OverF)
{
    const double w0 = 10.0;
    const double stopTime = 0.3337; // s, not a whole number of steps
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = spinningBox(w0, integrator);
        const double inertia = hingeInertia(model);
        const double h = model.simulation.dt;
        model.joints[0].friction = inertia * w0 / stopTime;
        const double loss = model.joints[0].friction * h / inertia; // rad/s per step
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        double stoppedAt = -1.0;
        double previous = w0;
        for (int k = 0; k < 500; ++k)
        {
            simulator.step(state);
            const double w = state.bodies[0].angularVelocity_W.z();
            if (stoppedAt < 0.0 && std::abs(w) <= 1e-12 * w0)
            {
                stoppedAt = state.time;
            }
            if (stoppedAt < 0.0)
            {
                ASSERT_NEAR(previous - w, loss, 1e-9 * loss)
                    << core::integratorName(integrator) << ", step " << k;
            }
            else
            {
                ASSERT_LE(std::abs(w), 1e-12 * w0) << "stays stopped, step " << k;
            }
            previous = w;
        }
        EXPECT_GE(stoppedAt, stopTime) << core::integratorName(integrator);
        EXPECT_LE(stoppedAt, stopTime + h + 1e-12) << core::integratorName(integrator);
    }
}

TEST(JointFriction, SlidingBoxStopsAfterMv0OverF)
{
    const double v0 = 1.5;
    const double stopTime = 0.2718;
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = slidingBox(v0, core::Vec3::UnitX(), core::Vec3::Zero(), integrator);
        const double h = model.simulation.dt;
        model.joints[0].friction = model.bodies[0].mass * v0 / stopTime; // N
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        double stoppedAt = -1.0;
        for (int k = 0; k < 400; ++k)
        {
            simulator.step(state);
            const double v = state.bodies[0].velocity_W.x();
            ASSERT_GE(v, -1e-12 * v0) << "friction never reverses the slide, step " << k;
            if (stoppedAt < 0.0 && std::abs(v) <= 1e-12 * v0)
            {
                stoppedAt = state.time;
            }
        }
        EXPECT_GE(stoppedAt, stopTime) << core::integratorName(integrator);
        EXPECT_LE(stoppedAt, stopTime + h + 1e-12) << core::integratorName(integrator);
    }
}

// A box on a rail 30 degrees below the horizontal: gravity pulls m g / 2 along it.
TEST(JointFriction, RailOnASlopeHoldsOrSlidesByTheFrictionForce)
{
    const core::Vec3 axis(std::cos(std::numbers::pi / 6.0), 0.0, -std::sin(std::numbers::pi / 6.0));
    for (const IntegratorKind integrator : cIntegrators)
    {
        for (const double ratio : {1.2, 0.5}) // friction / pull
        {
            core::Model model = slidingBox(0.0, axis, core::Vec3(0.0, 0.0, -cGravity), integrator);
            const double pull = 0.5 * model.bodies[0].mass * cGravity; // N
            model.joints[0].friction = ratio * pull;
            core::Simulator simulator(model);
            core::State state = core::initialState(model);
            for (int k = 0; k < 100; ++k)
            {
                simulator.step(state);
            }
            const double speed = state.bodies[0].velocity_W.dot(axis);
            const double expected =
                ratio >= 1.0 ? 0.0 : (pull - model.joints[0].friction) / model.bodies[0].mass * state.time;
            EXPECT_NEAR(speed, expected, 1e-12 + 1e-9 * expected)
                << core::integratorName(integrator) << ", friction / pull " << ratio;
        }
    }
}

// A hanging chain released straight out, damping and friction on every hinge: its energy never
// rises above where it started, and it ends below an undamped chain's.
TEST(JointDamping, ChainWithDampingAndFrictionNeverGainsEnergy)
{
    for (const IntegratorKind integrator : cIntegrators)
    {
        core::Model model = hingedChain(5, integrator);
        for (core::Joint& joint : model.joints)
        {
            joint.damping = 0.05;
            joint.friction = 0.02;
        }
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        const double e0 = core::totalEnergy(model, state);
        double highest = e0;
        for (long k = 0; k < stepsFor(3.0, model.simulation.dt); ++k)
        {
            simulator.step(state);
            highest = std::max(highest, core::totalEnergy(model, state));
        }
        const double end = core::totalEnergy(model, state);
        RecordProperty(std::string("energy_rise_") + core::integratorName(integrator), sci(highest - e0));
        EXPECT_LE(highest - e0, 1e-9) << core::integratorName(integrator);
        EXPECT_LT(end, e0 - 1.0) << core::integratorName(integrator) << ": the chain has lost energy";
        EXPECT_LT(simulator.lastStep().maxJointErrorM, 1e-6);
    }
}

// The four-bar linkage (scenes/four_bar.yaml) with damping c on the hinge that closes its loop (an
// extra row block whose drive row is compliant): the energy it loses is what that damper takes,
// the sum over steps of h c w^2 at the hinge's speed after the step, to the scheme's first-order
// error. (Were the drive row rigid, the linkage would lock; were it left out, nothing would be lost.)
TEST(JointDamping, FourBarLosesWhatItsLoopHingeDissipates)
{
    core::Model model = loadBundled("four_bar.yaml");
    const double c = 0.05; // N m s/rad
    core::Simulator probe(model);
    ASSERT_EQ(probe.layout().loopJoints.size(), 1u);
    const core::Joint& hinge = model.joints[static_cast<std::size_t>(probe.layout().loopJoints[0])];
    ASSERT_EQ(hinge.parent, core::cWorld);
    model.joints[static_cast<std::size_t>(probe.layout().loopJoints[0])].damping = c;
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    const double e0 = core::totalEnergy(model, state);
    const double h = model.simulation.dt;
    double dissipated = 0.0; // J
    for (long k = 0; k < stepsFor(2.0, h); ++k)
    {
        simulator.step(state);
        const double w = state.bodies[static_cast<std::size_t>(hinge.child)].angularVelocity_W.y();
        dissipated += h * c * w * w;
    }
    const double lost = e0 - core::totalEnergy(model, state);
    RecordProperty("lost", sci(lost));
    RecordProperty("dissipated", sci(dissipated));
    EXPECT_GT(dissipated, 0.5) << "J: the hinge moved";
    EXPECT_NEAR(lost, dissipated, 0.02 * dissipated);
}

// Damping rows in the factorization: the linear (O(n)) and dense (Moore's LU) solvers give the same
// trajectory to round-off; pgs with many sweeps comes close.
TEST(JointDamping, SolversAgreeOnADampedChain)
{
    auto run = [](core::SolverKind solver, int sweeps)
    {
        core::Model model = hingedChain(4);
        model.simulation.solver = solver;
        model.simulation.pgsIterations = sweeps;
        for (std::size_t k = 0; k < model.joints.size(); ++k)
        {
            model.joints[k].damping = 0.1 * static_cast<double>(k + 1);
        }
        core::Simulator simulator(model);
        std::vector<core::State> states{core::initialState(model)};
        for (int k = 0; k < 500; ++k)
        {
            states.push_back(states.back());
            simulator.step(states.back());
        }
        return states;
    };
    const std::vector<core::State> linear = run(core::SolverKind::Linear, 0);
    const std::vector<core::State> dense = run(core::SolverKind::Dense, 0);
    const std::vector<core::State> pgs = run(core::SolverKind::Pgs, 400);
    double denseDifference = 0.0;
    double pgsDifference = 0.0;
    for (std::size_t k = 0; k < linear.size(); ++k)
    {
        denseDifference = std::max(denseDifference, stateDifference(linear[k], dense[k]));
        pgsDifference = std::max(pgsDifference, stateDifference(linear[k], pgs[k]));
    }
    RecordProperty("dense_difference", sci(denseDifference));
    RecordProperty("pgs_difference", sci(pgsDifference));
    EXPECT_LT(denseDifference, 1e-10);
    EXPECT_GT(denseDifference, 0.0) << "two different solvers";
    EXPECT_LT(pgsDifference, 1e-6);
}

} // namespace
} // namespace frontier::sim::test
