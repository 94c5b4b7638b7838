// tests/sim/geometric_stiffness_test.cpp: the geometric stiffness of joints under large tension
// (docs/method.md §7a). A 1e6:1 heavy tip on light links holds at dt = 1 ms with euler and follows
// a 50x finer step; linear and dense agree with it to round-off; a copied state steps on bit for
// bit; a scene below the ratio is left alone.
#include "core/step/geometric_stiffness.h"
#include "sim_test_util.h"

#include <algorithm>
#include <cstddef>

namespace frontier::sim::test
{
namespace
{

core::Model heavyTip(double dt, core::SolverKind solver = core::SolverKind::Linear)
{
    core::Model model = loadBundled("stability/heavy_tip_1e6.yaml");
    model.simulation.dt = dt;
    model.simulation.solver = solver;
    return model;
}

std::size_t tipIndex(const core::Model& model)
{
    return static_cast<std::size_t>(model.findBody("tip"));
}

// 1 s from release (the bottom of the swing, where the chain carries three times the tip's
// weight, 3e6 N, is at 0.85 s): every joint held to the projection's tolerance after every step,
// the total energy never above its start, and less than 2% of it lost to the damping of the
// links' sideways mode (measured 0.76%).
TEST(GeometricStiffness, HeavyTip1e6HoldsAtOneMillisecond)
{
    const core::Model model = heavyTip(1e-3);
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    const double e0 = core::totalEnergy(model, state);
    double highest = e0;
    double worstGapM = 0.0;
    long stiffenedSteps = 0;
    for (int i = 0; i < 1000; ++i)
    {
        simulator.step(state);
        worstGapM = std::max(worstGapM, simulator.lastStep().maxJointErrorM);
        highest = std::max(highest, core::totalEnergy(model, state));
        stiffenedSteps += simulator.lastStep().stiffenedBodies > 0 ? 1 : 0;
    }
    EXPECT_LT(worstGapM, 1e-6);
    EXPECT_LE(highest, e0 * (1.0 + 1e-9));
    EXPECT_GT(core::totalEnergy(model, state), 0.98 * e0);
    EXPECT_GT(stiffenedSteps, 500) << "the links are stiffened while the chain is taut";
}

// The same swing at dt = 20 us (where the explicit step resolves the links' mode, no stiffness
// needed) is the reference: at 0.5 s the tip, 1.3 m along its arc, is within 5 mm of it
// (measured 1.8 mm).
TEST(GeometricStiffness, HeavyTipFollowsAFiftyTimesFinerStep)
{
    const auto tipAt = [](double dt, int steps)
    {
        const core::Model model = heavyTip(dt);
        core::Simulator simulator(model);
        core::State state = core::initialState(model);
        for (int i = 0; i < steps; ++i)
        {
            simulator.step(state);
        }
        return state.bodies[tipIndex(model)].position_W;
    };
    const core::Vec3 coarse = tipAt(1e-3, 500);
    const core::Vec3 fine = tipAt(2e-5, 25000);
    EXPECT_GT((coarse - core::Vec3(2.05, 0, 3)).norm(), 1.0) << "the tip has swung";
    EXPECT_LT((coarse - fine).norm(), 5e-3) << coarse.transpose() << " vs " << fine.transpose();
}

// The stiffened bodies' inertia enters every solver's factorization alike: linear (O(n)) and
// dense (Gaussian elimination of the whole system) agree to round-off through 300 stiffened steps.
TEST(GeometricStiffness, LinearAndDenseAgreeWhileStiffened)
{
    const core::Model linear = heavyTip(1e-3);
    const core::Model dense = heavyTip(1e-3, core::SolverKind::Dense);
    core::Simulator a(linear);
    core::Simulator b(dense);
    core::State sa = core::initialState(linear);
    core::State sb = core::initialState(dense);
    int stiffened = 0;
    for (int i = 0; i < 300; ++i)
    {
        a.step(sa);
        b.step(sb);
        stiffened = std::max(stiffened, a.lastStep().stiffenedBodies);
        EXPECT_EQ(a.lastStep().stiffenedBodies, b.lastStep().stiffenedBodies) << "step " << i;
    }
    EXPECT_GT(stiffened, 0);
    EXPECT_LT(stateDifference(sa, sb), 1e-9);
}

// The joints' loads are part of the state: a copy stepped by a new simulator goes on bit for bit
// with the original.
TEST(GeometricStiffness, CopiedStateStepsOnBitForBit)
{
    const core::Model model = heavyTip(1e-3);
    core::Simulator original(model);
    core::State state = core::initialState(model);
    for (int i = 0; i < 200; ++i)
    {
        original.step(state);
    }
    ASSERT_EQ(state.jointLoads.size(), 2 * model.joints.size());
    core::State copy = state;
    core::Simulator fresh(model);
    for (int i = 0; i < 100; ++i)
    {
        original.step(state);
        fresh.step(copy);
    }
    EXPECT_TRUE(bitIdentical(state, copy));
}

// chain30 swinging down under its own weight is far below the ratio: no body is stiffened.
TEST(GeometricStiffness, ChainUnderItsOwnWeightIsLeftAlone)
{
    const core::Model model = loadBundled("chain30.yaml");
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    for (int i = 0; i < 2000; ++i)
    {
        simulator.step(state);
        ASSERT_EQ(simulator.lastStep().stiffenedBodies, 0) << "step " << i;
    }
}

} // namespace
} // namespace frontier::sim::test
