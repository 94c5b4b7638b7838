// tests/core/tree_solver_test.cpp: the `linear` solver (docs/method.md §3) against the dense oracle,
// the joint conditions it enforces, momentum conservation, a closed-form impact, degenerate
// joints, and the partial forward sweep used for Delassus entries.
#include "core/dense_solver.h"
#include "core/tree_solver.h"
#include "random_model.h"
#include "tests/soak.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

using core::BlockVector;
using core::JointType;
using core::Model;

struct Case
{
    unsigned seed;
    int bodies;
    bool world;
};

// Sizes 2 .. a few hundred, world-attached and free, every joint type mixed.
const Case cCases[] = {{1, 2, false},    {2, 2, true},    {3, 3, false},    {4, 5, true},   {5, 8, false},
                       {6, 13, true},    {7, 21, false},  {8, 34, true},    {9, 55, false}, {10, 89, true},
                       {11, 144, false}, {12, 233, true}, {13, 300, false}, {14, 300, true}};

// A BlockVector as one vector in layout order; joints as the KKT unknown -lambda when asked.
Eigen::VectorXd flatten(const core::FrontierLayout& layout, const BlockVector& v, bool kktUnknown)
{
    Eigen::VectorXd out(layout.size);
    for (const core::LayoutBlock& block : layout.blocks)
    {
        const std::size_t i = static_cast<std::size_t>(block.index);
        if (block.kind == core::LayoutBlock::Kind::Node)
        {
            out.segment<6>(block.offset) = v.body[i];
        }
        else
        {
            out.segment(block.offset, block.dim) = (kktUnknown ? -1.0 : 1.0) * v.joint[i].head(block.dim);
        }
    }
    return out;
}

// Solves p = M u* with both solvers; relative differences (max norms) and the linear solution's
// backward error |A x - b| / (|A| |x| + |b|).
double solveBoth(const Model& model, double& velocityError, double& impulseError, double& backwardError)
{
    const auto problem = makeProblem(model);
    const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
    BlockVector linear, dense;
    auto tree = core::makeSolver(core::SolverKind::Linear);
    auto oracle = core::makeSolver(core::SolverKind::Dense);
    tree->factor(problem->system);
    tree->solve(rhs, linear);
    oracle->factor(problem->system);
    oracle->solve(rhs, dense);
    // Backward error (condition-independent): the KKT residual of the linear solution.
    const Eigen::MatrixXd a = core::DenseSolver::assemble(problem->system);
    const Eigen::VectorXd b = flatten(problem->layout, rhs, false);
    const Eigen::VectorXd x = flatten(problem->layout, linear, true);
    backwardError = (a * x - b).cwiseAbs().maxCoeff() /
                    (a.cwiseAbs().maxCoeff() * x.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
    velocityError = bodyDiff(linear, dense) / bodyNorm(dense);
    const double lambdaNorm = jointNorm(problem->system, dense);
    impulseError = lambdaNorm > 0.0 ? jointDiff(problem->system, linear, dense) / lambdaNorm : 0.0;
    return bodyNorm(linear);
}

TEST(TreeSolver, MatchesDenseOnRandomTrees)
{
    FRONTIER_SOAK_TEST();
    double worstV = 0.0, worstL = 0.0, worstB = 0.0;
    for (const Case& c : cCases)
    {
        SCOPED_TRACE("seed " + std::to_string(c.seed) + ", " + std::to_string(c.bodies) + " bodies");
        RandomTreeOptions options;
        options.bodies = c.bodies;
        options.attachToWorld = c.world;
        options.branching = (c.seed % 3 == 0) ? 0.0 : 1.0; // some chains, some bushy trees
        const Model model = randomTree(c.seed, options);
        double ev = 0.0, el = 0.0, eb = 0.0;
        const double norm = solveBoth(model, ev, el, eb);
        EXPECT_TRUE(std::isfinite(norm));
        EXPECT_LT(ev, 1e-9);
        EXPECT_LT(el, 1e-9);
        EXPECT_LT(eb, 1e-12);
        worstV = std::max(worstV, ev);
        worstL = std::max(worstL, el);
        worstB = std::max(worstB, eb);
    }
    RecordProperty("max_relative_velocity_difference", std::to_string(worstV));
    RecordProperty("max_relative_impulse_difference", std::to_string(worstL));
    RecordProperty("max_backward_error", std::to_string(worstB));
    std::printf("linear vs dense, random trees: velocity %.3g, impulse %.3g (relative); linear backward "
                "error %.3g\n",
                worstV, worstL, worstB);
}

TEST(TreeSolver, MatchesDenseOnRandomForests)
{
    for (unsigned seed = 20; seed < 30; ++seed)
    {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const Model model = randomForest(seed, 4, 60);
        double ev = 0.0, el = 0.0, eb = 0.0;
        solveBoth(model, ev, el, eb);
        EXPECT_LT(ev, 1e-9);
        EXPECT_LT(el, 1e-9);
        EXPECT_LT(eb, 1e-12);
    }
}

TEST(TreeSolver, JointVelocityConditionsHoldAfterSolve)
{
    double worst = 0.0;
    for (const Case& c : cCases)
    {
        SCOPED_TRACE("seed " + std::to_string(c.seed));
        RandomTreeOptions options;
        options.bodies = c.bodies;
        options.attachToWorld = c.world;
        const Model model = randomTree(c.seed + 1000, options);
        const auto problem = makeProblem(model);
        const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
        // The unconstrained velocities violate the joints: the solve has work to do.
        BlockVector free;
        free.resize(model.bodies.size(), model.joints.size());
        free.setZero();
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            free.body[i] << problem->state.bodies[i].velocity_W, problem->state.bodies[i].angularVelocity_W;
        }
        const JointResidual before = jointResidual(model, problem->system, free);
        EXPECT_GT(before.maxResidual, 1e-2 * before.scale);

        core::TreeSolver solver;
        solver.factor(problem->system);
        BlockVector x;
        solver.solve(rhs, x);
        const JointResidual after = jointResidual(model, problem->system, x);
        ASSERT_GT(after.scale, 0.0);
        EXPECT_LT(after.maxResidual, 5e-11 * after.scale); // measured up to 3.8e-12
        worst = std::max(worst, after.maxResidual / after.scale);
    }
    RecordProperty("max_relative_joint_residual", std::to_string(worst));
    std::printf("linear: max joint velocity residual %.3g (relative)\n", worst);
}

// A non-zero joint right-hand side c (as drift correction uses it): J u = c.
TEST(TreeSolver, NonZeroJointRightHandSideIsMet)
{
    RandomTreeOptions options;
    options.bodies = 40;
    options.attachToWorld = true;
    const Model model = randomTree(77, options);
    const auto problem = makeProblem(model);
    BlockVector rhs = momentumRhs(model, problem->state, problem->system);
    Rng rng(78);
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        for (int r = 0; r < problem->system.joints[k].count; ++r)
        {
            rhs.joint[k](r) = rng.normal();
        }
    }
    core::TreeSolver solver;
    solver.factor(problem->system);
    BlockVector x, y;
    solver.solve(rhs, x);
    auto dense = core::makeSolver(core::SolverKind::Dense);
    dense->factor(problem->system);
    dense->solve(rhs, y);
    EXPECT_LT(bodyDiff(x, y), 1e-9 * bodyNorm(y));
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const core::Joint& joint = model.joints[k];
        const core::JointRows& rows = problem->system.joints[k];
        Eigen::VectorXd ju = rows.J_b.topRows(rows.count) * x.body[static_cast<std::size_t>(joint.child)];
        if (!core::jointToWorld(model, joint))
        {
            ju += rows.J_a.topRows(rows.count) * x.body[static_cast<std::size_t>(joint.parent)];
        }
        const Eigen::VectorXd c = rhs.joint[k].head(rows.count);
        EXPECT_LT((ju - c).cwiseAbs().maxCoeff(), 1e-9) << joint.name;
    }
}

struct Momenta
{
    Vec3 linear = Vec3::Zero();
    Vec3 angular = Vec3::Zero();
    double scale = 0.0; // sum of the magnitudes of the terms
};

Momenta momenta(const Model& model, const core::RowSystem& system, const core::State& state,
                const BlockVector& u)
{
    Momenta m;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const Vec3 p = system.mass[i] * u.body[i].head<3>();
        const Vec3 l = state.bodies[i].position_W.cross(p) + system.inertia_W[i] * u.body[i].tail<3>();
        m.linear += p;
        m.angular += l;
        m.scale += p.norm() + l.norm();
    }
    return m;
}

TEST(TreeSolver, InternalImpulsesConserveMomentumOfAFreeBody)
{
    double worst = 0.0;
    for (unsigned seed = 200; seed < 210; ++seed)
    {
        SCOPED_TRACE("seed " + std::to_string(seed));
        RandomTreeOptions options;
        options.bodies = 2 + static_cast<int>((seed * 37) % 200);
        options.attachToWorld = false;
        const Model model = randomTree(seed, options);
        const auto problem = makeProblem(model);
        const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
        BlockVector before;
        before.resize(model.bodies.size(), model.joints.size());
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            before.body[i] << problem->state.bodies[i].velocity_W, problem->state.bodies[i].angularVelocity_W;
        }
        core::TreeSolver solver;
        solver.factor(problem->system);
        BlockVector after;
        solver.solve(rhs, after);
        const Momenta m0 = momenta(model, problem->system, problem->state, before);
        const Momenta m1 = momenta(model, problem->system, problem->state, after);
        const double scale = std::max(m0.scale, m1.scale);
        const double err = std::max((m1.linear - m0.linear).norm(), (m1.angular - m0.angular).norm()) / scale;
        EXPECT_LT(err, 1e-12); // measured up to 6.6e-14
        // The joint impulses are not negligible: velocities changed a lot.
        EXPECT_GT(bodyDiff(before, after), 1e-2 * bodyNorm(before));
        worst = std::max(worst, err);
    }
    RecordProperty("max_relative_momentum_change", std::to_string(worst));
    std::printf("linear: max momentum change %.3g (relative)\n", worst);
}

// Two equal rods of length L along x, rod 0 on [0, L], rod 1 on [L, 2L], joined by a ball joint at
// x = L, at rest. Rod 0 is struck at its free end x = 0 by an impulse P along +y.
//
// Derivation. Each rod: mass m, inertia about z I = m (L^2 + t^2) / 12 (a box L x t x t). Let F
// be the joint impulse rod 1 receives from rod 0 (rod 0 receives -F); by symmetry of the problem
// about the x-y plane and along x, only F_y and motion in the x-y plane occur. Levers (z
// component of r x f = r_x f_y): the blow at r = -L/2 on rod 0, the joint at +L/2 on rod 0 and
// -L/2 on rod 1.
//   rod 0:  m v0 = P - F,             I w0 = -L/2 P - L/2 F = -L/2 (P + F)
//   rod 1:  m v1 = F,                 I w1 = -L/2 F
//   joint:  v0 + w0 L/2 = v1 - w1 L/2  (y velocity of the joint point on each rod)
// With k = m L^2 / (4 I): (P - F) - k (P + F) = F + k F, so
//   F = P (1 - k) / (2 (1 + k)),
// and then v0, w0, v1, w1 from the momentum equations. For a thin rod (t -> 0) k = 3, F = -P/4,
// v0 = 5P/(4m), v1 = -P/(4m).
TEST(TreeSolver, TwoRodsStruckAtTheEndMatchTheClosedForm)
{
    const double L = 1.3, t = 0.02, m = 2.5, P = 0.7;
    Model model;
    model.bodies.push_back(boxBody("rod0", m, Vec3(L, t, t), Vec3(0.5 * L, 0, 0)));
    model.bodies.push_back(boxBody("rod1", m, Vec3(L, t, t), Vec3(1.5 * L, 0, 0)));
    addJoint(model, "ball", JointType::Ball, 0, 1, Vec3(L, 0, 0), Vec3::UnitZ());
    const double I = m * (L * L + t * t) / 12.0;
    const double k = m * L * L / (4.0 * I);
    const double F = P * (1.0 - k) / (2.0 * (1.0 + k));
    const double v0 = (P - F) / m, w0 = -0.5 * L * (P + F) / I;
    const double v1 = F / m, w1 = -0.5 * L * F / I;

    for (core::SolverKind kind : {core::SolverKind::Linear, core::SolverKind::Dense})
    {
        SCOPED_TRACE(core::solverName(kind));
        const auto problem = makeProblem(model);
        BlockVector rhs = momentumRhs(model, problem->state, problem->system); // at rest: zero
        const Vec3 blow(0, P, 0);
        const Vec3 lever(-0.5 * L, 0, 0);
        rhs.body[0].head<3>() += blow;
        rhs.body[0].tail<3>() += lever.cross(blow);
        auto solver = core::makeSolver(kind);
        solver->factor(problem->system);
        BlockVector x;
        solver->solve(rhs, x);
        Vec6 e0, e1;
        e0 << 0, v0, 0, 0, 0, w0;
        e1 << 0, v1, 0, 0, 0, w1;
        const double scale = std::abs(w0); // the largest of the four
        EXPECT_LT((x.body[0] - e0).cwiseAbs().maxCoeff(), 1e-12 * scale) << x.body[0].transpose();
        EXPECT_LT((x.body[1] - e1).cwiseAbs().maxCoeff(), 1e-12 * scale) << x.body[1].transpose();
        // The child (rod 1) receives J_b^T lambda = lambda for a ball joint: lambda = (0, F, 0).
        EXPECT_LT((x.joint[0].head<3>() - Vec3(0, F, 0)).cwiseAbs().maxCoeff(), 1e-12 * P)
            << x.joint[0].transpose();
    }
    // Thin-rod limit sanity of the formula itself.
    EXPECT_NEAR(k, 3.0, 3.0 * (t * t) / (L * L) * 1.01);
}

// The Delassus matrix G = J_x H^-1 J_x^T of extra rows (docs/method.md §5) from the tree solver's
// partial forward sweeps equals the one built from one full solve per row (the base-class
// default, here through the dense solver), for blocks between bodies of one tree, of different
// trees, and with the world.
TEST(TreeSolver, DelassusFromPathSweepsMatchesOneSolvePerRow)
{
    Model model;
    Rng rng(31);
    RandomTreeOptions options;
    options.bodies = 40;
    options.attachToWorld = true;
    appendRandomTree(model, rng, options);
    options.bodies = 15;
    options.attachToWorld = false;
    appendRandomTree(model, rng, options);
    const int nb = static_cast<int>(model.bodies.size());
    const auto problem = makeProblem(model);

    std::vector<core::ExtraBlock> blocks;
    for (int b = 0; b < 12; ++b)
    {
        core::ExtraBlock block;
        block.kind = core::ExtraBlock::Kind::Loop;
        block.count = rng.integer(1, 6);
        block.bodyA = rng.integer(0, nb - 1);
        block.bodyB = b % 4 == 0 ? -1 : rng.integer(0, nb - 1); // some against the world
        for (int r = 0; r < block.count; ++r)
        {
            for (int c = 0; c < 6; ++c)
            {
                block.J_A(r, c) = rng.normal();
                block.J_B(r, c) = block.bodyB >= 0 ? rng.normal() : 0.0;
            }
        }
        blocks.push_back(block);
    }
    const int rows = core::layoutExtraRows(blocks);

    core::TreeSolver tree;
    tree.factor(problem->system);
    Eigen::MatrixXd g;
    tree.delassus(blocks, rows, g);
    core::DenseSolver dense;
    dense.factor(problem->system);
    Eigen::MatrixXd reference;
    dense.delassus(blocks, rows, reference);
    ASSERT_EQ(g.rows(), rows);
    ASSERT_EQ(g.cols(), rows);
    const double scale = reference.cwiseAbs().maxCoeff();
    const double diff = (g - reference).cwiseAbs().maxCoeff() / scale;
    std::printf("Delassus, path sweeps vs one solve per row: %.3g (relative)\n", diff);
    EXPECT_LT(diff, 1e-13); // measured 1.8e-15
    EXPECT_LT((g - g.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
    // Positive semidefinite (a mobility): no eigenvalue below round-off.
    const Eigen::VectorXd eig =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (g + g.transpose())).eigenvalues();
    EXPECT_GT(eig.minCoeff(), -1e-10 * scale);
}

TEST(TreeSolver, RefactorAtANewConfigurationReusesStorage)
{
    // One solver object, two different models in a row (different sizes): no stale state.
    core::TreeSolver solver;
    for (unsigned seed : {401u, 402u, 403u})
    {
        RandomTreeOptions options;
        options.bodies = static_cast<int>(seed % 400) * 10 + 3;
        options.attachToWorld = seed % 2 == 0;
        const Model model = randomTree(seed, options);
        const auto problem = makeProblem(model);
        const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
        solver.factor(problem->system);
        BlockVector x, y;
        solver.solve(rhs, x);
        auto dense = core::makeSolver(core::SolverKind::Dense);
        dense->factor(problem->system);
        dense->solve(rhs, y);
        EXPECT_LT(bodyDiff(x, y), 1e-9 * bodyNorm(y)) << "seed " << seed;
    }
}

// The block table is laid out once per layout (FrontierLayout::id): one solver alternating
// between two layouts of the same number of blocks but different shapes (a chain and a bushy
// tree) solves each exactly as a solver that only ever saw that one.
TEST(TreeSolver, AlternatingLayoutsOfOneSizeSolveAsFreshSolvers)
{
    RandomTreeOptions chain;
    chain.bodies = 40;
    chain.branching = 0.0;
    RandomTreeOptions bushy = chain;
    bushy.branching = 1.0;
    const Model a = randomTree(601, chain);
    const Model b = randomTree(602, bushy);
    const auto pa = makeProblem(a);
    const auto pb = makeProblem(b);
    ASSERT_EQ(pa->layout.blocks.size(), pb->layout.blocks.size());
    ASSERT_NE(pa->layout.id, pb->layout.id);
    const BlockVector ra = momentumRhs(a, pa->state, pa->system);
    const BlockVector rb = momentumRhs(b, pb->state, pb->system);
    BlockVector freshA, freshB;
    core::TreeSolver onlyA, onlyB, both;
    onlyA.factorAndSolve(pa->system, ra, freshA);
    onlyB.factorAndSolve(pb->system, rb, freshB);
    for (int round = 0; round < 2; ++round)
    {
        BlockVector x, y;
        both.factorAndSolve(pa->system, ra, x);
        both.factorAndSolve(pb->system, rb, y);
        EXPECT_EQ(bodyDiff(x, freshA), 0.0) << "round " << round;
        EXPECT_EQ(jointDiff(pa->system, x, freshA), 0.0) << "round " << round;
        EXPECT_EQ(bodyDiff(y, freshB), 0.0) << "round " << round;
        EXPECT_EQ(jointDiff(pb->system, y, freshB), 0.0) << "round " << round;
    }
    EXPECT_GT(bodyNorm(freshA), 0.0);
}

// factorAndSolve (the forward sweep fused into the elimination) computes exactly what factor()
// then solve() do, in the same order: bit-identical results, also for later solves with the
// same factorization.
TEST(TreeSolver, FusedFactorAndSolveIsBitIdenticalToFactorThenSolve)
{
    for (unsigned seed : {501u, 502u, 503u})
    {
        const Model model = randomForest(seed, 4, 60);
        const auto problem = makeProblem(model);
        const BlockVector rhs = momentumRhs(model, problem->state, problem->system);
        core::TreeSolver separate, fused;
        BlockVector x, y, x2, y2;
        separate.factor(problem->system);
        separate.solve(rhs, x);
        fused.factorAndSolve(problem->system, rhs, y);
        ASSERT_EQ(x.body.size(), y.body.size());
        for (std::size_t i = 0; i < x.body.size(); ++i)
        {
            EXPECT_EQ(x.body[i], y.body[i]) << "seed " << seed << " body " << i;
        }
        for (std::size_t k = 0; k < x.joint.size(); ++k)
        {
            EXPECT_EQ(x.joint[k], y.joint[k]) << "seed " << seed << " joint " << k;
        }
        BlockVector second = rhs;
        for (Vec6& p : second.body)
        {
            p = -0.5 * p;
        }
        separate.solve(second, x2);
        fused.solve(second, y2);
        EXPECT_EQ(bodyDiff(x2, y2), 0.0);
        EXPECT_GT(bodyNorm(y), 0.0);
    }
}

// Well-posed pivots that span many decades are not singular. A light link (1 g) nailed to the
// world carries 100 heavy revolute links (1 t each): the light link's pivot has its own tiny
// inertia about the hinge axis next to the subtree's huge inertia about the other axes. (The
// first version of the pivot test compared against the block's largest diagonal entry and
// rejected this as "mass matrix is not positive definite"; the dense solver accepts it.)
TEST(TreeSolver, LightBodyCarryingAHeavySubtreeIsNotSingular)
{
    std::vector<double> masses(101, 1e3);
    masses[0] = 1e-3;
    Model model = straightChain(masses, JointType::Revolute, true);
    model.bodies[0].inertia_B *= 0.01;
    Rng rng(5);
    for (core::Body& body : model.bodies)
    {
        body.velocity_W = rng.gaussianVec();
        body.angularVelocity_W = rng.gaussianVec();
    }
    double ev = 0.0, el = 0.0, eb = 0.0;
    ASSERT_NO_THROW(solveBoth(model, ev, el, eb));
    std::printf("light link + heavy subtree: linear vs dense velocity %.3g, impulse %.3g, backward %.3g\n",
                ev, el, eb);
    EXPECT_LT(ev, 1e-9);
    EXPECT_LT(el, 1e-9);
    EXPECT_LT(eb, 1e-12);
}

// A long revolute chain (8000 links, 1 kg, 1 m): the articulated inertia about the constrained
// axes grows like k^3 along the chain (1e11 here) while the free axis keeps 0.08 kg m^2.
TEST(TreeSolver, LongRevoluteChainFactors)
{
    Model model = straightChain(std::vector<double>(8000, 1.0), JointType::Revolute, true);
    Rng rng(6);
    for (core::Body& body : model.bodies)
    {
        body.velocity_W = rng.gaussianVec();
        body.angularVelocity_W = rng.gaussianVec();
    }
    const auto problem = makeProblem(model);
    core::TreeSolver solver;
    ASSERT_NO_THROW(solver.factor(problem->system));
    BlockVector x;
    solver.solve(momentumRhs(model, problem->state, problem->system), x);
    const JointResidual residual = jointResidual(model, problem->system, x);
    std::printf("8000-link revolute chain: joint residual %.3g (relative)\n",
                residual.maxResidual / residual.scale);
    EXPECT_LT(residual.maxResidual, 1e-10 * residual.scale);
}

// A revolute joint whose two perpendicular directions coincide has two equal rows (3 and 4): its
// edge pivot -J D^-1 J^T is singular. The solver must name the joint, not return NaN.
Model degenerateRevoluteChain()
{
    Model model = straightChain({1.0, 2.0, 3.0, 4.0}, JointType::Revolute, true);
    model.joints[1].name = "bad_hinge";
    model.joints[1].perpParent2 = model.joints[1].perpParent1;
    return model;
}

TEST(TreeSolver, DependentJointRowsAreReportedByName)
{
    const Model model = degenerateRevoluteChain();
    const auto problem = makeProblem(model);
    const core::JointRows& rows = problem->system.joints[1];
    ASSERT_EQ(rows.count, 5);
    EXPECT_EQ((rows.J_b.row(3) - rows.J_b.row(4)).cwiseAbs().maxCoeff(), 0.0);
    core::TreeSolver solver;
    try
    {
        solver.factor(problem->system);
        FAIL() << "factor() accepted dependent joint rows";
    }
    catch (const core::SingularJointError& error)
    {
        EXPECT_EQ(error.jointName(), "bad_hinge");
        EXPECT_NE(std::string(error.what()).find("bad_hinge"), std::string::npos) << error.what();
    }
}

TEST(TreeSolver, NearlyDependentRowsAreReportedNotNaN)
{
    // Rows 3 and 4 differ by 1e-14 rad: numerically dependent. Either a clear error or a finite
    // answer, never NaN.
    Model model = degenerateRevoluteChain();
    const Model good = straightChain({1.0, 2.0, 3.0, 4.0}, JointType::Revolute, true);
    model.joints[1].perpParent2 =
        (good.joints[1].perpParent1 + 1e-14 * good.joints[1].perpParent2).normalized();
    const auto problem = makeProblem(model);
    core::TreeSolver solver;
    EXPECT_THROW(solver.factor(problem->system), core::SingularJointError);
}

TEST(TreeSolver, MasslessBodyIsReportedByName)
{
    Model model = straightChain({1.0, 1.0, 1.0}, JointType::Ball, false);
    model.bodies[2].name = "ghost";
    model.bodies[2].mass = 0.0;
    model.bodies[2].inertia_B.setZero();
    const auto problem = makeProblem(model);
    core::TreeSolver solver;
    try
    {
        solver.factor(problem->system);
        FAIL() << "factor() accepted a massless body";
    }
    catch (const core::SingularJointError& error)
    {
        EXPECT_EQ(error.jointName(), "ghost");
    }
}

} // namespace
} // namespace frontier::test
