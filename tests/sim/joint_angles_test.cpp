// tests/sim/joint_angles_test.cpp: revolute angles beyond +-pi. A rod on a hinge spins past the
// half turn into a limit at +-4.5 rad: the limit holds there (the angle, unwrapped here from the
// rod's direction step by step, never passes it) and adds no energy (the run never rises above its
// start by more than the same run without the limit does: the scheme's own error); a wheel with no
// limit keeps counting its turns. With the angle taken by atan2 alone (wrapping at +-pi), the rod passed
// 4.5 rad as if there were no limit.
#include "core/joints/coordinates.h"
#include "joint_models.h"
#include "sim_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numbers>

namespace frontier::sim::test
{
namespace
{

constexpr double cPi = std::numbers::pi;
constexpr double cInf = std::numeric_limits<double>::infinity();

// The rod's angle about +y from its start, continued step by step by the test itself: the rod's
// direction R x_B = (cos theta, 0, -sin theta).
class RodAngle
{
  public:
    void update(const core::State& state)
    {
        const core::Vec3 d = state.bodies[0].orientation_WB * core::Vec3::UnitX();
        const double wrapped = std::atan2(-d.z(), d.x());
        mAngle += std::remainder(wrapped - mWrapped, 2.0 * cPi);
        mWrapped = wrapped;
    }
    double angle() const { return mAngle; }

  private:
    double mAngle = 0.0;
    double mWrapped = 0.0;
};

struct LimitRun
{
    double lowest = 0.0;       // rad
    double highest = 0.0;      // rad
    double energyRise = -cInf; // J: largest E(t) - E(0)
    double finalAngle = 0.0;   // rad
    double trackedError = 0.0; // rad: |State::jointAngles - the test's angle|, largest
};

LimitRun runRod(const core::Model& model, double seconds)
{
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    const double e0 = core::totalEnergy(model, state);
    RodAngle angle;
    LimitRun run;
    for (long k = 0; k < stepsFor(seconds, model.simulation.dt); ++k)
    {
        simulator.step(state);
        angle.update(state);
        run.lowest = std::min(run.lowest, angle.angle());
        run.highest = std::max(run.highest, angle.angle());
        run.energyRise = std::max(run.energyRise, core::totalEnergy(model, state) - e0);
        run.trackedError = std::max(run.trackedError, std::abs(state.jointAngles[0] - angle.angle()));
    }
    run.finalAngle = angle.angle();
    return run;
}

constexpr double cLimitTolerance = 2e-3;  // rad past a limit (the loop-limits tests hold 1e-3)
constexpr double cEnergyTolerance = 1e-9; // J

// The largest energy rise of the same rod without limits: the integrator's own (J).
double freeRise(const core::Model& limited, double seconds)
{
    core::Model free = limited;
    free.joints[0].limits.reset();
    return runRod(free, seconds).energyRise;
}

// Thrown down at 10 rad/s, the rod swings through the bottom and past the half turn (it has the
// energy to go over the top at 3 pi / 2), so it reaches +4.5 rad on its way up and stops there.
TEST(JointAngles, RodThrownForwardStopsAtAnUpperLimitBeyondPi)
{
    const core::Vec3 g(0.0, 0.0, -9.81);
    for (const auto limits : {std::array<double, 2>{-4.5, 4.5}, std::array<double, 2>{-cInf, 4.5}})
    {
        for (const core::IntegratorKind integrator :
             {core::IntegratorKind::Euler, core::IntegratorKind::Rattle})
        {
            const core::Model model = hingedRod(10.0, limits, g, integrator);
            const LimitRun run = runRod(model, 2.0);
            SCOPED_TRACE(std::string(core::integratorName(integrator)) + ", lower " +
                         std::to_string(limits[0]));
            EXPECT_GT(run.highest, 4.5 - 0.02) << "the rod reaches the limit";
            EXPECT_LT(run.highest, 4.5 + cLimitTolerance);
            EXPECT_LE(run.energyRise, freeRise(model, 2.0) + cEnergyTolerance);
            EXPECT_LT(run.trackedError, 1e-9);
        }
    }
}

// Thrown up at -10 rad/s, the rod goes over the top (-pi / 2) and falls to -4.5 rad, just short of
// the bottom (-3 pi / 2): gravity keeps it pressed on the lower limit.
TEST(JointAngles, RodThrownBackwardRestsOnALowerLimitBeyondPi)
{
    const core::Vec3 g(0.0, 0.0, -9.81);
    for (const auto limits : {std::array<double, 2>{-4.5, 4.5}, std::array<double, 2>{-4.5, cInf}})
    {
        for (const core::IntegratorKind integrator :
             {core::IntegratorKind::Euler, core::IntegratorKind::Rattle})
        {
            const core::Model model = hingedRod(-10.0, limits, g, integrator);
            const LimitRun run = runRod(model, 2.0);
            SCOPED_TRACE(std::string(core::integratorName(integrator)) + ", upper " +
                         std::to_string(limits[1]));
            EXPECT_GT(run.lowest, -4.5 - cLimitTolerance);
            EXPECT_NEAR(run.finalAngle, -4.5, cLimitTolerance) << "pressed on the limit by gravity";
            EXPECT_LE(run.energyRise, freeRise(model, 2.0) + cEnergyTolerance);
            EXPECT_LT(run.trackedError, 1e-9);
        }
    }
}

// Without gravity, spinning at 20 rad/s in either direction: the rod turns 4.5 rad and stops.
TEST(JointAngles, SpinningRodStopsAtALimitBeyondPiEitherWay)
{
    for (const double w0 : {20.0, -20.0})
    {
        const core::Model model = hingedRod(w0, std::array<double, 2>{-4.5, 4.5}, core::Vec3::Zero());
        const LimitRun run = runRod(model, 1.0);
        SCOPED_TRACE("w0 = " + std::to_string(w0));
        EXPECT_NEAR(run.finalAngle, std::copysign(4.5, w0), cLimitTolerance);
        EXPECT_LT(run.highest, 4.5 + cLimitTolerance);
        EXPECT_GT(run.lowest, -4.5 - cLimitTolerance);
        EXPECT_LE(run.energyRise, freeRise(model, 1.0) + cEnergyTolerance);
    }
}

// A continuous joint (no limits) spinning at 20 rad/s for 2 s, either scheme: the angle counts
// past 6 turns, and nothing slows the rod. Each step turns it by h w up to the schemes' phase error,
// (h w)^2 / 8 = 5e-5 relative.
TEST(JointAngles, ContinuousJointKeepsCountingTurns)
{
    const double w0 = 20.0;
    for (const core::IntegratorKind integrator : {core::IntegratorKind::Euler, core::IntegratorKind::Rattle})
    {
        const core::Model model = hingedRod(w0, std::nullopt, core::Vec3::Zero(), integrator);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        RodAngle angle;
        const long steps = stepsFor(2.0, model.simulation.dt);
        for (long k = 0; k < steps; ++k)
        {
            simulator.step(state);
            angle.update(state);
            ASSERT_NEAR(state.jointAngles[0], angle.angle(), 1e-9) << "step " << k;
        }
        EXPECT_GT(state.jointAngles[0], 6.0 * 2.0 * cPi);
        EXPECT_NEAR(state.jointAngles[0], w0 * state.time, 1e-4 * w0 * state.time);
        EXPECT_NEAR(state.bodies[0].angularVelocity_W.y(), w0, 1e-4 * w0);
        EXPECT_NEAR(core::jointCoordinate(model, state, 0), state.jointAngles[0], 1e-12);
    }
}

// A copy of the state carries the angle: a second simulator stepping a copy from the middle of a
// run ends with the same angle, bit for bit, as the run itself.
TEST(JointAngles, CopiedStateContinuesTheSameCount)
{
    const core::Model model = hingedRod(20.0, std::array<double, 2>{-4.5, 20.0}, core::Vec3(0.0, 0.0, -9.81));
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    for (int k = 0; k < 400; ++k)
    {
        simulator.step(state);
    }
    ASSERT_GT(state.jointAngles[0], cPi) << "past the half turn at the copy";
    core::State copy = state;
    core::Simulator second(model);
    for (int k = 0; k < 400; ++k)
    {
        simulator.step(state);
        second.step(copy);
    }
    EXPECT_TRUE(bitIdentical(state, copy));
    EXPECT_EQ(state.jointAngles[0], copy.jointAngles[0]);
}

} // namespace
} // namespace frontier::sim::test
