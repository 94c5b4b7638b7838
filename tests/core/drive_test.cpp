// tests/core/drive_test.cpp: drive rows in the joint blocks (core/joints/drive.cpp). A joint with
// damping has one more row per coordinate and no other joint changes; the linear solver with
// compliant rows agrees with the dense one to round-off on random trees, and its solution meets
// the equations written out here (momentum, joint conditions, J u + E lambda = 0 with E = 1/(c h));
// pgs converges to it; over no time (h = 0) a drive gives no impulse at all.
#include "core/joints/drive.h"
#include "core/tree_solver.h"
#include "random_model.h"

#include <cmath>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

using core::JointType;

RandomTreeOptions treeOptions(int bodies, bool attachToWorld)
{
    RandomTreeOptions options;
    options.bodies = bodies;
    options.attachToWorld = attachToWorld;
    return options;
}

// Random damping (N m s/rad or N s/m) on every joint that has a coordinate, over six decades.
void dampEveryJoint(core::Model& model, Rng& rng)
{
    for (core::Joint& joint : model.joints)
    {
        joint.damping = rng.logUniform(1e-3, 1e3);
    }
}

TEST(DriveRows, DampedJointsGainOneRowPerCoordinateAndNoOtherJointChanges)
{
    core::Model model = randomTree(3, treeOptions(40, true));
    const core::FrontierLayout plain = core::buildFrontierLayout(model);
    Rng rng(3);
    dampEveryJoint(model, rng);
    const core::FrontierLayout damped = core::buildFrontierLayout(model);
    ASSERT_EQ(plain.blocks.size(), damped.blocks.size());
    int added = 0;
    for (std::size_t b = 0; b < plain.blocks.size(); ++b)
    {
        const core::LayoutBlock& before = plain.blocks[b];
        const core::LayoutBlock& after = damped.blocks[b];
        ASSERT_EQ(before.index, after.index);
        EXPECT_EQ(before.driveRows, 0);
        if (before.kind == core::LayoutBlock::Kind::Node)
        {
            continue;
        }
        const JointType type = model.joints[static_cast<std::size_t>(after.index)].type;
        // Written out: revolute and prismatic one coordinate, cylindrical two, the others none.
        const int coordinates = type == JointType::Revolute || type == JointType::Prismatic ? 1
                                : type == JointType::Cylindrical                            ? 2
                                                                                            : 0;
        EXPECT_EQ(after.driveRows, coordinates) << core::jointTypeName(type);
        EXPECT_EQ(after.dim, before.dim + coordinates);
        EXPECT_LE(after.dim, 6);
        added += coordinates;
    }
    EXPECT_GT(added, 0);
    EXPECT_EQ(damped.size, plain.size + added);
}

struct Solved
{
    std::unique_ptr<core::Model> model;
    std::unique_ptr<Problem> problem;
    core::BlockVector rhs, linear, dense;
};

Solved solveDamped(unsigned seed, int bodies)
{
    Solved out;
    Rng rng(seed);
    out.model = std::make_unique<core::Model>(randomTree(seed, treeOptions(bodies, (seed % 2) == 0)));
    dampEveryJoint(*out.model, rng);
    out.problem = makeProblem(*out.model);
    out.rhs = momentumRhs(*out.model, out.problem->state, out.problem->system);
    for (auto [kind, solution] :
         {std::pair{core::SolverKind::Linear, &out.linear}, std::pair{core::SolverKind::Dense, &out.dense}})
    {
        auto solver = core::makeSolver(kind);
        solver->factor(out.problem->system);
        solver->solve(out.rhs, *solution);
    }
    return out;
}

TEST(DriveRows, LinearAgreesWithDenseOnDampedRandomTrees)
{
    for (unsigned seed = 1; seed <= 12; ++seed)
    {
        const Solved s = solveDamped(seed, 3 + 7 * static_cast<int>(seed));
        const double velocity = bodyDiff(s.linear, s.dense) / bodyNorm(s.dense);
        const double impulse =
            jointDiff(s.problem->system, s.linear, s.dense) / jointNorm(s.problem->system, s.dense);
        EXPECT_LT(velocity, 1e-9) << "seed " << seed;
        EXPECT_LT(impulse, 1e-9) << "seed " << seed;
    }
}

// M_i u_i - sum_k J_ki^T lambda_k = p_i for every body, J u = 0 on condition rows and
// J u + lambda / (c h) = 0 on drive rows, assembled here from the rows.
TEST(DriveRows, LinearSolutionMeetsTheDampedEquations)
{
    for (unsigned seed = 20; seed <= 25; ++seed)
    {
        const Solved s = solveDamped(seed, 30);
        const core::Model& model = *s.model;
        const core::RowSystem& system = s.problem->system;
        const double h = model.simulation.dt;
        std::vector<Vec6> momentum(model.bodies.size(), Vec6::Zero());
        double scale = 0.0;
        double worstRow = 0.0;
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            momentum[i].head<3>() = system.mass[i] * s.linear.body[i].head<3>();
            momentum[i].tail<3>() = system.inertia_W[i] * s.linear.body[i].tail<3>();
            scale = std::max(scale, s.rhs.body[i].cwiseAbs().maxCoeff());
        }
        for (std::size_t k = 0; k < model.joints.size(); ++k)
        {
            const core::Joint& joint = model.joints[k];
            const core::JointRows& rows = system.joints[k];
            const Vec6& lambda = s.linear.joint[k];
            const bool parentMoves = !core::jointToWorld(model, joint);
            ASSERT_EQ(rows.count, rows.constraintRows + core::blockDriveRows(joint));
            for (int r = 0; r < rows.count; ++r)
            {
                double v = rows.J_b.row(r).dot(s.linear.body[static_cast<std::size_t>(joint.child)]);
                momentum[static_cast<std::size_t>(joint.child)] -= rows.J_b.row(r).transpose() * lambda(r);
                if (parentMoves)
                {
                    v += rows.J_a.row(r).dot(s.linear.body[static_cast<std::size_t>(joint.parent)]);
                    momentum[static_cast<std::size_t>(joint.parent)] -=
                        rows.J_a.row(r).transpose() * lambda(r);
                }
                const double compliance = r < rows.constraintRows ? 0.0 : 1.0 / (joint.damping * h);
                worstRow = std::max(worstRow, std::abs(v + compliance * lambda(r)));
            }
        }
        double worstMomentum = 0.0;
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            worstMomentum = std::max(worstMomentum, (momentum[i] - s.rhs.body[i]).cwiseAbs().maxCoeff());
        }
        const double speed = bodyNorm(s.linear);
        EXPECT_LT(worstMomentum, 1e-9 * scale) << "seed " << seed;
        EXPECT_LT(worstRow, 1e-9 * speed) << "seed " << seed;
    }
}

TEST(DriveRows, PgsConvergesToLinearOnADampedChain)
{
    core::Model model = straightChain({1.0, 2.0, 1.0, 3.0}, JointType::Revolute, true);
    model.bodies[3].angularVelocity_W = Vec3(0.0, 0.0, 2.0);
    model.bodies[2].velocity_W = Vec3(0.0, 1.0, 0.0);
    for (core::Joint& joint : model.joints)
    {
        joint.damping = 5.0;
    }
    const auto problem = makeProblem(model);
    const core::BlockVector rhs = momentumRhs(model, problem->state, problem->system);
    core::BlockVector linear, pgs;
    auto tree = core::makeSolver(core::SolverKind::Linear);
    tree->factor(problem->system);
    tree->solve(rhs, linear);
    auto sweeps = core::makeSolver(core::SolverKind::Pgs, 5000);
    sweeps->factor(problem->system);
    sweeps->solve(rhs, pgs);
    EXPECT_LT(bodyDiff(linear, pgs), 1e-9 * bodyNorm(linear));
    EXPECT_LT(jointDiff(problem->system, linear, pgs), 1e-8 * jointNorm(problem->system, linear));
}

// h = 0: the drive rows are there (the layout is the damped one) but carry no impulse, so every
// velocity is the undamped model's.
TEST(DriveRows, NoTimeMeansNoDriveImpulse)
{
    for (const core::SolverKind kind :
         {core::SolverKind::Linear, core::SolverKind::Dense, core::SolverKind::Pgs})
    {
        core::Model plainModel = randomTree(31, treeOptions(12, true));
        core::Model dampedModel = plainModel;
        Rng rng(31);
        dampEveryJoint(dampedModel, rng);
        core::BlockVector solutions[2];
        for (int m = 0; m < 2; ++m)
        {
            const core::Model& model = m == 0 ? plainModel : dampedModel;
            const core::FrontierLayout layout = core::buildFrontierLayout(model);
            const core::State state = core::initialState(model);
            core::RowSystem system;
            core::assembleRows(model, layout, state, 0.0, system);
            auto solver = core::makeSolver(kind, 200);
            solver->factor(system);
            solver->solve(momentumRhs(model, state, system), solutions[m]);
            if (m == 1)
            {
                for (std::size_t k = 0; k < model.joints.size(); ++k)
                {
                    const core::JointRows& rows = system.joints[k];
                    for (int r = rows.constraintRows; r < rows.count; ++r)
                    {
                        EXPECT_EQ(solutions[m].joint[k](r), 0.0) << core::solverName(kind) << ", joint " << k;
                    }
                }
            }
        }
        EXPECT_LT(bodyDiff(solutions[0], solutions[1]), 1e-12 * bodyNorm(solutions[0]))
            << core::solverName(kind);
    }
}

} // namespace
} // namespace frontier::test
