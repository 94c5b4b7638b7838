// tests/core/pgs_solver_test.cpp: the `pgs` baseline (docs/method.md §3): converges to the exact
// answer on an easy chain; documents how far it stays on a long chain with a large mass ratio.
#include "core/pgs_solver.h"
#include "core/tree_solver.h"
#include "random_model.h"

#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

using core::BlockVector;
using core::JointType;
using core::Model;

struct Gap
{
    double velocity = 0.0;  // max |u_pgs - u_linear| / max |u_linear|
    double violation = 0.0; // max joint velocity residual of the pgs answer / its scale
};

Gap pgsGap(const Model& model, int iterations)
{
    const auto problem = makeProblem(model);
    const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
    core::TreeSolver exact;
    exact.factor(problem->system);
    BlockVector x, y;
    exact.solve(rhs, x);
    core::PgsSolver pgs(iterations);
    pgs.factor(problem->system);
    pgs.solve(rhs, y);
    const JointResidual residual = jointResidual(model, problem->system, y);
    return {bodyDiff(x, y) / bodyNorm(x), residual.maxResidual / residual.scale};
}

// A chain along x, every body moving with a different random velocity (a hard start for pgs).
Model movingChain(const std::vector<double>& masses, JointType type, unsigned seed)
{
    Model model = straightChain(masses, type, false);
    Rng rng(seed);
    for (core::Body& body : model.bodies)
    {
        body.velocity_W = rng.gaussianVec();
        body.angularVelocity_W = rng.gaussianVec();
    }
    return model;
}

TEST(PgsSolver, ConvergesToLinearOnAShortEvenChain)
{
    const Model model = movingChain({1.0, 1.0, 1.0, 1.0, 1.0}, JointType::Ball, 1);
    const Gap gap = pgsGap(model, 500);
    RecordProperty("relative_velocity_error_500", std::to_string(gap.velocity));
    std::printf("pgs, 5 equal links, 500 sweeps: velocity error %.3g, joint violation %.3g\n", gap.velocity,
                gap.violation);
    // Measured 4e-16 and 9e-17: converged to round-off.
    EXPECT_LT(gap.velocity, 1e-12);
    EXPECT_LT(gap.violation, 1e-12);
    // And it is an iteration: 2 sweeps are not enough.
    EXPECT_GT(pgsGap(model, 2).velocity, 1e-3);
}

TEST(PgsSolver, ZeroSweepsIsTheUnconstrainedVelocity)
{
    const Model model = movingChain({1.0, 2.0, 3.0}, JointType::Revolute, 2);
    const auto problem = makeProblem(model);
    const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
    core::PgsSolver pgs(0);
    pgs.factor(problem->system);
    BlockVector y;
    pgs.solve(rhs, y);
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        Vec6 u;
        u << model.bodies[i].velocity_W, model.bodies[i].angularVelocity_W;
        EXPECT_LT((y.body[i] - u).cwiseAbs().maxCoeff(), 1e-12);
    }
}

// 100 links, light (1 kg) except a heavy tip (1000 kg) and alternating 1000:1 links. At a game
// engine's sweep counts pgs stays far from the exact answer: this records how far.
TEST(PgsSolver, StaysFarFromLinearOnALongChainWithALargeMassRatio)
{
    std::vector<double> heavyTip(100, 1.0);
    heavyTip.back() = 1000.0;
    std::vector<double> alternating(100);
    for (std::size_t i = 0; i < alternating.size(); ++i)
    {
        alternating[i] = i % 2 == 0 ? 1000.0 : 1.0;
    }
    for (const auto& [label, masses] :
         {std::pair{"heavy_tip", heavyTip}, std::pair{"alternating", alternating}})
    {
        const Model model = movingChain(masses, JointType::Ball, 3);
        for (int sweeps : {20, 100})
        {
            const Gap gap = pgsGap(model, sweeps);
            const std::string key = std::string(label) + "_" + std::to_string(sweeps);
            RecordProperty("relative_velocity_error_" + key, std::to_string(gap.velocity));
            RecordProperty("joint_violation_" + key, std::to_string(gap.violation));
            std::printf(
                "pgs, 100 links %s, %d sweeps: velocity error %.3g, joint violation %.3g (relative)\n", label,
                sweeps, gap.velocity, gap.violation);
            EXPECT_GT(gap.velocity, 1e-3) << key;
            EXPECT_GT(gap.violation, 1e-3) << key;
        }
    }
}

} // namespace
} // namespace frontier::test
