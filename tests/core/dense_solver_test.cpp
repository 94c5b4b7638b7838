// tests/core/dense_solver_test.cpp: the `dense` baseline (Moore's solve, docs/method.md §3): its
// assembled KKT matrix, its solution against a KKT system the test builds itself in body order,
// and degenerate joints.
#include "core/dense_solver.h"
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

// [M J^T; J 0] [u; -lambda] = [p; c] in body-index order, then tree joints in joint order,
// built without the layout's offsets; solved by full-pivoting LU.
BlockVector solveIndependently(const Model& model, const core::RowSystem& system, const BlockVector& rhs)
{
    const int nb = static_cast<int>(model.bodies.size());
    std::vector<int> jointRow(model.joints.size(), -1);
    int n = 6 * nb;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (system.layout->jointBlock[k] >= 0)
        {
            jointRow[k] = n;
            n += system.joints[k].count;
        }
    }
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < nb; ++i)
    {
        const std::size_t ui = static_cast<std::size_t>(i);
        a.block<3, 3>(6 * i, 6 * i) = system.mass[ui] * Mat3::Identity();
        a.block<3, 3>(6 * i + 3, 6 * i + 3) = system.inertia_W[ui];
        b.segment<6>(6 * i) = rhs.body[ui];
    }
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (jointRow[k] < 0)
        {
            continue;
        }
        const core::Joint& joint = model.joints[k];
        const core::JointRows& rows = system.joints[k];
        const int r = rows.count;
        a.block(jointRow[k], 6 * joint.child, r, 6) = rows.J_b.topRows(r);
        a.block(6 * joint.child, jointRow[k], 6, r) = rows.J_b.topRows(r).transpose();
        if (joint.parent != core::cWorld)
        {
            a.block(jointRow[k], 6 * joint.parent, r, 6) = rows.J_a.topRows(r);
            a.block(6 * joint.parent, jointRow[k], 6, r) = rows.J_a.topRows(r).transpose();
        }
        b.segment(jointRow[k], r) = rhs.joint[k].head(r);
    }
    const Eigen::VectorXd x = Eigen::FullPivLU<Eigen::MatrixXd>(a).solve(b);
    BlockVector out;
    out.resize(model.bodies.size(), model.joints.size());
    out.setZero();
    for (int i = 0; i < nb; ++i)
    {
        out.body[static_cast<std::size_t>(i)] = x.segment<6>(6 * i);
    }
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (jointRow[k] >= 0)
        {
            out.joint[k].head(system.joints[k].count) = -x.segment(jointRow[k], system.joints[k].count);
        }
    }
    return out;
}

TEST(DenseSolver, AssembledMatrixHasTheMassesAndJacobiansInLayoutOrder)
{
    RandomTreeOptions options;
    options.bodies = 12;
    options.attachToWorld = true;
    const Model model = randomTree(3, options);
    const auto problem = makeProblem(model);
    const Eigen::MatrixXd a = core::DenseSolver::assemble(problem->system);
    ASSERT_EQ(a.rows(), problem->layout.size);
    ASSERT_EQ(a.cols(), problem->layout.size);
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const int o = problem->layout.blocks[static_cast<std::size_t>(problem->layout.bodyBlock[i])].offset;
        EXPECT_EQ((a.block<3, 3>(o, o) - model.bodies[i].mass * Mat3::Identity()).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ((a.block<3, 3>(o + 3, o + 3) - problem->system.inertia_W[i]).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ((a.block<3, 3>(o, o + 3).cwiseAbs().maxCoeff()), 0.0);
    }
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const core::Joint& joint = model.joints[k];
        const core::LayoutBlock& edge =
            problem->layout.blocks[static_cast<std::size_t>(problem->layout.jointBlock[k])];
        const int r = edge.dim;
        EXPECT_EQ(a.block(edge.offset, edge.offset, r, r).cwiseAbs().maxCoeff(), 0.0); // zero diagonal
        const int ob = problem->layout
                           .blocks[static_cast<std::size_t>(
                               problem->layout.bodyBlock[static_cast<std::size_t>(joint.child)])]
                           .offset;
        const Eigen::MatrixXd jb = problem->system.joints[k].J_b.topRows(r);
        EXPECT_EQ((a.block(edge.offset, ob, r, 6) - jb).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ((a.block(ob, edge.offset, 6, r) - jb.transpose()).cwiseAbs().maxCoeff(), 0.0);
    }
}

TEST(DenseSolver, MatchesAnIndependentlyAssembledSystem)
{
    double worst = 0.0;
    for (unsigned seed = 50; seed < 60; ++seed)
    {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const Model model = randomForest(seed, 3, 25);
        const auto problem = makeProblem(model);
        BlockVector rhs = momentumRhs(model, problem->state, problem->system);
        Rng rng(seed);
        for (std::size_t k = 0; k < model.joints.size(); ++k)
        {
            for (int r = 0; r < problem->system.joints[k].count; ++r)
            {
                rhs.joint[k](r) = 0.1 * rng.normal(); // exercise c as well
            }
        }
        auto dense = core::makeSolver(core::SolverKind::Dense);
        EXPECT_STREQ(dense->name(), "dense");
        dense->factor(problem->system);
        BlockVector x;
        dense->solve(rhs, x);
        const BlockVector y = solveIndependently(model, problem->system, rhs);
        const double ev = bodyDiff(x, y) / bodyNorm(y);
        const double el = jointDiff(problem->system, x, y) / jointNorm(problem->system, y);
        EXPECT_LT(ev, 2e-10); // measured up to 1.7e-11 (masses over six decades)
        EXPECT_LT(el, 2e-10);
        worst = std::max({worst, ev, el});
    }
    RecordProperty("max_relative_difference", std::to_string(worst));
    std::printf("dense vs independent full-pivot KKT: %.3g (relative)\n", worst);
}

TEST(DenseSolver, DependentJointRowsAreReportedByName)
{
    Model model = straightChain({1.0, 2.0, 3.0, 4.0}, JointType::Revolute, true);
    model.joints[2].name = "bad_hinge";
    model.joints[2].perpParent2 = model.joints[2].perpParent1;
    const auto problem = makeProblem(model);
    core::DenseSolver solver;
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

TEST(DenseSolver, WellPosedExtremeMassRatiosAreNotReportedSingular)
{
    // Masses over six decades must not trip the singularity test.
    std::vector<double> masses;
    for (int i = 0; i < 12; ++i)
    {
        masses.push_back(i % 2 == 0 ? 1e-3 : 1e3);
    }
    const Model model = straightChain(masses, JointType::Revolute, true);
    const auto problem = makeProblem(model);
    core::DenseSolver solver;
    EXPECT_NO_THROW(solver.factor(problem->system));
}

} // namespace
} // namespace frontier::test
