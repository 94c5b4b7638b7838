// tests/core/extra_rows_solve_test.cpp: the block Gauss-Seidel of the extra rows
// (core/extra_rows_solve.cpp) on Delassus matrices of random forests: G stored by tree
// (core/delassus.h) is G computed one row at a time, with nothing left out; islands are solved as
// the separate problems they are; a lone sticking contact is solved exactly; the stated velocity
// tolerance is what the result satisfies; a stalled sweep stops.
#include "core/delassus.h"
#include "core/extra_rows.h"
#include "core/tree_solver.h"
#include "random_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

struct ContactProblem
{
    std::unique_ptr<core::Model> model; // problem->system points into it: kept at one address
    std::unique_ptr<Problem> problem;
    std::vector<core::ExtraBlock> blocks;
    Eigen::MatrixXd G;           // dense, one O(n) solve per row (the oracle)
    core::DelassusMatrix byTree; // by tree, from the tree solver's paths
    Eigen::VectorXd freeVelocity;
    int rows = 0;
};

// The matrix as one part (every row coupled to every other): what the by-tree storage is checked
// against.
core::DelassusMatrix whole(const std::vector<core::ExtraBlock>& blocks, const Eigen::MatrixXd& G)
{
    core::DelassusMatrix matrix;
    matrix.setDense(blocks, G);
    return matrix;
}

// G = J H^-1 J^T one column at a time: the response to a unit impulse on each row, through the
// whole problem (no tree structure used).
Eigen::MatrixXd delassusByColumns(core::ImpulseSolver& solver, const core::Model& model,
                                  const std::vector<core::ExtraBlock>& blocks, int rows)
{
    Eigen::MatrixXd G(rows, rows);
    core::BlockVector response;
    response.resize(model.bodies.size(), model.joints.size());
    Eigen::VectorXd column;
    for (int r = 0; r < rows; ++r)
    {
        response.setZero();
        solver.applyExtraImpulses(blocks, Eigen::VectorXd::Unit(rows, r), response);
        core::extraRowVelocities(blocks, response, column);
        G.col(r) = column;
    }
    return G;
}

// Rows n, t1, t2 (n a unit normal) of a contact at `arm` (m) from body A's centre: J_A rows
// [d, arm x d] with sign `sideA`, and for body B (when bodyB >= 0) the opposite at -arm.
void setContactRows(core::ExtraBlock& block, const Vec3& n, const Vec3& arm, double sideA)
{
    const Vec3 t1 = n.unitOrthogonal();
    const Vec3 directions[3] = {n, t1, n.cross(t1)};
    for (int r = 0; r < 3; ++r)
    {
        const Vec3& d = directions[r];
        block.J_A.row(r).head<3>() = sideA * d.transpose();
        block.J_A.row(r).tail<3>() = sideA * arm.cross(d).transpose();
        if (block.bodyB >= 0)
        {
            block.J_B.row(r).head<3>() = -sideA * d.transpose();
            block.J_B.row(r).tail<3>() = -sideA * (-arm).cross(d).transpose();
        }
    }
}

// `contacts` random contact blocks (normal + two tangents, mu 0.5) on a forest of `trees`
// trees: against the world, within a tree, and (acrossTrees) across trees; free velocities
// approaching.
ContactProblem makeContacts(unsigned seed, int trees, int contacts, bool acrossTrees = true)
{
    ContactProblem out;
    Rng rng(seed);
    out.model = std::make_unique<core::Model>(randomForest(seed, trees, 12));
    const core::Model& model = *out.model;
    out.problem = makeProblem(model);
    const int nb = static_cast<int>(out.problem->state.bodies.size());
    for (int c = 0; c < contacts; ++c)
    {
        core::ExtraBlock block;
        block.kind = core::ExtraBlock::Kind::Contact;
        block.count = 3;
        block.friction = 0.5;
        block.bodyA = rng.integer(0, nb - 1);
        block.bodyB = rng.coin(0.4) ? -1 : rng.integer(0, nb - 1);
        const std::vector<int>& treeOf = out.problem->layout.treeOfBody;
        if (block.bodyB == block.bodyA ||
            (!acrossTrees && block.bodyB >= 0 &&
             treeOf[static_cast<std::size_t>(block.bodyB)] != treeOf[static_cast<std::size_t>(block.bodyA)]))
        {
            block.bodyB = -1;
        }
        const Vec3 n = rng.unitVec();
        setContactRows(block, n, 0.1 * rng.gaussianVec(), -1.0);
        out.blocks.push_back(block);
    }
    out.rows = core::layoutExtraRows(out.blocks);
    core::TreeSolver solver;
    solver.factor(out.problem->system);
    out.G = delassusByColumns(solver, model, out.blocks, out.rows);
    solver.delassus(out.blocks, out.byTree);
    // Free velocities as the simulator has them: the tree solve of M u for the random state's
    // body velocities (joint-consistent), seen through the rows. The problem is then the KKT
    // system of a projection, which has a solution.
    core::BlockVector freeSolution;
    solver.solve(momentumRhs(model, out.problem->state, out.problem->system), freeSolution);
    core::extraRowVelocities(out.blocks, freeSolution, out.freeVelocity);
    return out;
}

} // namespace

// G by tree is G: its parts summed give the matrix computed one row at a time, so every entry
// it does not store is an exact zero of G; and with several trees the parts hold well under the
// square of the rows (what makes a sweep cheaper than O(rows^2)).
TEST(ExtraRowsSolve, PartsByTreeHoldAllOfG)
{
    const ContactProblem p = makeContacts(71, 8, 60);
    Eigen::MatrixXd assembled;
    p.byTree.toDense(assembled);
    ASSERT_EQ(assembled.rows(), p.rows);
    const double scale = p.G.cwiseAbs().maxCoeff();
    EXPECT_LE((assembled - p.G).cwiseAbs().maxCoeff(), 1e-10 * scale); // masses span 1e4 in these forests
    long stored = 0;
    for (int part = 0; part < p.byTree.parts(); ++part)
    {
        stored += static_cast<long>(p.byTree.part(part).rows) * p.byTree.part(part).rows;
    }
    const double fraction = static_cast<double>(stored) / (static_cast<double>(p.rows) * p.rows);
    std::printf("8 trees, %d rows, %d parts, %d islands: the parts store %.2f of rows^2\n", p.rows,
                p.byTree.parts(), p.byTree.islands(), fraction);
    EXPECT_LT(fraction, 0.6);
    for (int r = 0; r < p.rows; ++r) // entry() reads the same sums
    {
        EXPECT_LE(std::abs(p.byTree.entry(r, (7 * r) % p.rows) - p.G(r, (7 * r) % p.rows)), 1e-10 * scale);
    }
}

// Islands are separate problems: solving the forest by tree gives each island's blocks exactly the
// impulses that solving that island alone (its blocks, its part of G as one matrix) gives.
TEST(ExtraRowsSolve, IslandsAreSolvedAsSeparateProblems)
{
    const ContactProblem p = makeContacts(72, 8, 60, false);
    ASSERT_GT(p.byTree.islands(), 1);
    core::ExtraSolveSettings settings;
    core::ExtraSolveScratch scratch;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(p.rows);
    core::solveExtraRows(p.blocks, p.byTree, p.freeVelocity, settings, lambda, scratch);
    int islandsSolved = 0;
    for (int island = 0; island < p.byTree.islands(); ++island)
    {
        // No block here spans two trees: an island is one tree's part. Alone: its blocks laid out
        // anew (in the part's order), its part's matrix, its rows of the free velocities.
        ASSERT_EQ(p.byTree.islandParts(island).size(), 1u);
        const core::DelassusMatrix::Part& part = p.byTree.part(p.byTree.islandParts(island)[0]);
        std::vector<core::ExtraBlock> blocks;
        for (int b : part.blocks)
        {
            blocks.push_back(p.blocks[static_cast<std::size_t>(b)]);
        }
        const int n = core::layoutExtraRows(blocks);
        ASSERT_EQ(n, part.rows);
        Eigen::VectorXd free(n);
        for (int i = 0; i < n; ++i)
        {
            free(i) = p.freeVelocity(part.global[static_cast<std::size_t>(i)]);
        }
        core::ExtraSolveScratch alone;
        Eigen::VectorXd expected = Eigen::VectorXd::Zero(n);
        core::DelassusMatrix matrix = whole(blocks, part.G);
        matrix.part(0).free = part.free; // the rows' scales on free bodies, as the tree solver gave them
        core::solveExtraRows(blocks, matrix, free, settings, expected, alone);
        for (int i = 0; i < n; ++i)
        {
            EXPECT_EQ(lambda(part.global[static_cast<std::size_t>(i)]), expected(i)) << "island " << island;
        }
        islandsSolved += expected.cwiseAbs().maxCoeff() > 0.0;
    }
    EXPECT_GT(islandsSolved, 1);
}

// One contact that can stick (mu large) is solved by its sticking trial (docs/method.md §1: try
// sticking first): all three rows reach their targets. The trial's pivot carries the solve's
// 1e-9 relative regularization, so the first sweep is exact to about 1e-8 and the second, an
// iterative refinement, to round-off.
TEST(ExtraRowsSolve, LoneStickingContactIsSolvedByItsStickingTrial)
{
    // A free box (1 kg, 0.4 x 0.2 x 0.1 m) struck at a corner-like point.
    core::Model model;
    model.bodies.push_back(boxBody("box", 1.0, Vec3(0.4, 0.2, 0.1), Vec3::Zero(), Rng(73).rotation()));
    ContactProblem p;
    p.problem = makeProblem(model);
    core::ExtraBlock block;
    block.count = 3;
    block.bodyA = 0;
    const Vec3 arm(0.2, -0.1, 0.05);
    const Vec3 n = Vec3(0.1, 0.2, 1.0).normalized();
    setContactRows(block, n, arm, 1.0);
    p.blocks.push_back(block);
    p.rows = core::layoutExtraRows(p.blocks);
    core::TreeSolver solver;
    solver.factor(p.problem->system);
    p.G = delassusByColumns(solver, model, p.blocks, p.rows);
    p.freeVelocity = Eigen::Vector3d(-1.0, 0.4, -0.2); // approaching at 1 m/s, slipping
    p.blocks[0].friction = 100.0;
    p.blocks[0].target(0) = 0.3; // restitution-like target, m/s
    // The sticking impulse, independently: G lambda = target - v_free on all three rows.
    const Eigen::Vector3d target(0.3, 0.0, 0.0);
    const Eigen::Vector3d expected = p.G.ldlt().solve(target - p.freeVelocity);
    ASSERT_GT(expected(0), 0.0) << "this seed's contact would need to pull to stick";
    ASSERT_LT(expected.tail<2>().norm(), 100.0 * expected(0));
    core::ExtraSolveSettings settings;
    settings.maxSweeps = 2;
    settings.tolerance = 0.0;
    settings.velocityTolerance = 0.0;
    core::ExtraSolveScratch scratch;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(p.rows);
    core::solveExtraRows(p.blocks, whole(p.blocks, p.G), p.freeVelocity, settings, lambda, scratch);
    const Eigen::Vector3d v = p.freeVelocity + p.G * lambda;
    const double scale = p.freeVelocity.cwiseAbs().maxCoeff() + 0.3;
    std::printf("lone sticking contact: impulse %.6g %.6g %.6g N s, velocity error %.3g m/s\n", lambda(0),
                lambda(1), lambda(2), (v - target).cwiseAbs().maxCoeff());
    EXPECT_LE((lambda - expected).cwiseAbs().maxCoeff(),
              1e-8 * expected.cwiseAbs().maxCoeff()); // G + 1e-9 diag(G)
    EXPECT_LE((v - target).cwiseAbs().maxCoeff(), 1e-12 * scale);
}

// The stated tolerance: after the solve stops on it, every normal row satisfies its
// complementarity conditions (pushing rows at their target, others at or above it) and every
// sticking friction pair its zero slip, to the velocity tolerance (checked here from G lambda,
// not from the solver's running velocities).
TEST(ExtraRowsSolve, ResultHoldsTheStatedVelocityTolerance)
{
    const ContactProblem p = makeContacts(74, 3, 40);
    for (double tolerance : {1e-4, 1e-5, 1e-6})
    {
        core::ExtraSolveSettings settings;
        settings.velocityTolerance = tolerance;
        settings.tolerance = 0.0; // stop on velocities only
        settings.maxSweeps = 100000;
        settings.stallSweeps = 0;
        core::ExtraSolveScratch scratch;
        Eigen::VectorXd lambda = Eigen::VectorXd::Zero(p.rows);
        const core::ExtraSolveStats stats =
            core::solveExtraRows(p.blocks, p.byTree, p.freeVelocity, settings, lambda, scratch);
        ASSERT_LT(stats.sweeps, settings.maxSweeps);
        const Eigen::VectorXd v = p.freeVelocity + p.G * lambda;
        double worst = 0.0;
        for (const core::ExtraBlock& block : p.blocks)
        {
            const int o = block.offset;
            EXPECT_GE(lambda(o), 0.0);
            EXPECT_LE(lambda.segment<2>(o + 1).norm(), block.friction * lambda(o) * (1 + 1e-12) + 1e-15);
            // normal row: v >= target, and v = target where it pushes
            worst = std::max(worst, std::max(0.0, -v(o)));
            if (lambda(o) > 0.0)
            {
                worst = std::max(worst, std::abs(v(o)));
            }
            // inside the cone: sticking, zero slip
            if (lambda.segment<2>(o + 1).norm() < 0.999 * block.friction * lambda(o))
            {
                worst = std::max(worst, v.segment<2>(o + 1).cwiseAbs().maxCoeff());
            }
        }
        std::printf("velocity tolerance %.0e: %d sweeps, worst condition %.3g m/s\n", tolerance, stats.sweeps,
                    worst);
        EXPECT_LE(worst, tolerance * (1.0 + 1e-6));
    }
}

// Pivots kept for the same matrix (DelassusMatrix::version): a second solve on the same G with
// other targets, from other impulses, gives bit for bit what a solve computing its pivots afresh
// gives (the targets are read anew), and a solve on another matrix is not misled by them.
TEST(ExtraRowsSolve, PivotsKeptForTheSameMatrixGiveTheSameImpulses)
{
    ContactProblem p = makeContacts(75, 4, 40);
    core::ExtraSolveSettings settings;
    core::ExtraSolveScratch kept;
    Eigen::VectorXd first = Eigen::VectorXd::Zero(p.rows);
    kept.velocity = p.freeVelocity;
    core::solveExtraRowsFrom(p.blocks, p.byTree, settings, first, kept);
    ASSERT_GT(first.cwiseAbs().maxCoeff(), 0.0);
    for (core::ExtraBlock& block : p.blocks)
    {
        block.target(0) = 1e-3; // a separating target: other impulses than before
    }
    Eigen::VectorXd again = 0.5 * first;
    kept.velocity = p.freeVelocity + p.G * again;
    core::solveExtraRowsFrom(p.blocks, p.byTree, settings, again, kept);
    core::ExtraSolveScratch fresh;
    Eigen::VectorXd reference = 0.5 * first;
    fresh.velocity = kept.velocity = p.freeVelocity + p.G * reference;
    core::solveExtraRowsFrom(p.blocks, p.byTree, settings, reference, fresh);
    ASSERT_EQ(again.size(), reference.size());
    for (Eigen::Index i = 0; i < again.size(); ++i)
    {
        EXPECT_EQ(again(i), reference(i)) << "row " << i;
    }
    EXPECT_GT((again - first).cwiseAbs().maxCoeff(), 0.0); // the new targets changed the result
    // Another matrix (scaled G, as one part): pivots recomputed, so the result is that of a fresh
    // scratch.
    const core::DelassusMatrix other = whole(p.blocks, 2.0 * p.G);
    Eigen::VectorXd scaled = Eigen::VectorXd::Zero(p.rows);
    kept.velocity = p.freeVelocity;
    core::solveExtraRowsFrom(p.blocks, other, settings, scaled, kept);
    core::ExtraSolveScratch fresh2;
    Eigen::VectorXd scaledReference = Eigen::VectorXd::Zero(p.rows);
    fresh2.velocity = p.freeVelocity;
    core::solveExtraRowsFrom(p.blocks, other, settings, scaledReference, fresh2);
    EXPECT_EQ((scaled - scaledReference).cwiseAbs().maxCoeff(), 0.0);
}

// conditionsMet is conditionResidual <= tolerance, decided at the first unmet block: the two agree
// on every sweep's iterate of a solve (and with the solve's own `converged`), the residual itself
// is met and the next smaller number is not, and a NaN velocity is never met (the largest
// residual passes over a NaN).
TEST(ExtraRowsSolve, ConditionsMetAgreesWithTheLargestResidual)
{
    const ContactProblem p = makeContacts(74, 3, 40); // the problem of the tolerance test above
    core::ExtraSolveSettings settings;
    settings.maxSweeps = 1; // one sweep per call: every iterate is checked
    settings.tolerance = 0.0;
    settings.velocityTolerance = 1e-4;
    core::ExtraSolveScratch scratch;
    scratch.velocity = p.freeVelocity;
    const core::DelassusMatrix G = whole(p.blocks, p.G); // one island: one sweep is one sweep of all
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(p.rows);
    int unmet = 0;
    int met = 0;
    for (int sweep = 0; sweep < 100000 && met == 0; ++sweep)
    {
        const core::ExtraSolveStats stats = core::solveExtraRowsFrom(p.blocks, G, settings, lambda, scratch);
        const double residual = core::conditionResidual(p.blocks, scratch.velocity, lambda);
        EXPECT_EQ(stats.converged, residual <= settings.velocityTolerance) << "sweep " << sweep;
        EXPECT_EQ(core::conditionsMet(p.blocks, scratch.velocity, lambda, settings.velocityTolerance),
                  residual <= settings.velocityTolerance);
        EXPECT_TRUE(core::conditionsMet(p.blocks, scratch.velocity, lambda, residual));
        if (residual > 0.0)
        {
            EXPECT_FALSE(
                core::conditionsMet(p.blocks, scratch.velocity, lambda, std::nextafter(residual, 0.0)));
        }
        (residual <= settings.velocityTolerance ? met : unmet) += 1;
    }
    EXPECT_GT(unmet, 0); // the loop saw both outcomes
    EXPECT_EQ(met, 1);
    Eigen::VectorXd broken = scratch.velocity;
    broken(p.blocks.back().offset) = std::nan("");
    EXPECT_FALSE(core::conditionsMet(p.blocks, broken, lambda, 1e300));
    EXPECT_TRUE(std::isnan(core::conditionResidual(p.blocks, broken, lambda)));
}

// The carried impulses in the right-hand side of the step's first solve (ContactProblem::carryImpulses):
// H^-1 (p + J_x^T lambda) in one solve equals H^-1 p plus applyExtraImpulses(lambda) to
// round-off, and its row velocities are v_free + G lambda.
TEST(ExtraRowsSolve, ImpulsesInTheRightHandSideEqualAppliedImpulses)
{
    const ContactProblem p = makeContacts(77, 3, 30);
    core::TreeSolver solver;
    solver.factor(p.problem->system);
    Rng rng(77);
    Eigen::VectorXd lambda(p.rows);
    for (Eigen::Index i = 0; i < p.rows; ++i)
    {
        lambda(i) = rng.uniform(0.0, 1.0);
    }
    const core::BlockVector momentum = momentumRhs(*p.model, p.problem->state, p.problem->system);
    core::BlockVector applied;
    solver.solve(momentum, applied);
    solver.applyExtraImpulses(p.blocks, lambda, applied);
    core::BlockVector rhs = momentum;
    core::ImpulseSolver::addExtraImpulses(p.blocks, lambda, rhs);
    core::BlockVector once;
    solver.solve(rhs, once);
    double scale = 0.0;
    double difference = 0.0;
    for (std::size_t i = 0; i < once.body.size(); ++i)
    {
        scale = std::max(scale, applied.body[i].cwiseAbs().maxCoeff());
        difference = std::max(difference, (once.body[i] - applied.body[i]).cwiseAbs().maxCoeff());
    }
    for (std::size_t j = 0; j < once.joint.size(); ++j)
    {
        difference = std::max(difference, (once.joint[j] - applied.joint[j]).cwiseAbs().maxCoeff());
    }
    ASSERT_GT(scale, 0.0);
    EXPECT_LE(difference, 1e-12 * scale);
    Eigen::VectorXd velocity;
    core::extraRowVelocities(p.blocks, once, velocity);
    const Eigen::VectorXd expected = p.freeVelocity + p.G * lambda;
    EXPECT_LE((velocity - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
}

// Drive rows (joint friction, core/joints/drive.h): one row J u + E lambda = target with
// |lambda| <= bound. Alone, its impulse is the closed form clamp((target - v_free) / (G + E),
// -bound, bound), after one sweep; coupled to others (two rows of one body), the result meets each
// row's condition: inside its bound exactly, on it from the side it pushes.
TEST(ExtraRowsSolve, DriveRowsTakeTheClampedClosedFormImpulse)
{
    struct Case
    {
        double compliance, target, free, bound;
    };
    const double g = 0.7; // (rad/s) / (N m s)
    for (const Case c : {Case{0.0, 0.0, 2.0, 10.0}, Case{0.0, 0.0, 2.0, 1.0}, Case{0.0, 0.0, -2.0, 1.0},
                         Case{0.5, 0.3, -1.0, 10.0}, Case{0.5, 0.3, -1.0, 0.2}})
    {
        std::vector<core::ExtraBlock> blocks(1);
        blocks[0].kind = core::ExtraBlock::Kind::Drive;
        blocks[0].count = 1;
        blocks[0].bodyB = 0;
        blocks[0].compliance(0) = c.compliance;
        blocks[0].target(0) = c.target;
        blocks[0].bound = c.bound;
        core::layoutExtraRows(blocks);
        const Eigen::MatrixXd G = Eigen::MatrixXd::Constant(1, 1, g);
        const Eigen::VectorXd free = Eigen::VectorXd::Constant(1, c.free);
        Eigen::VectorXd lambda = Eigen::VectorXd::Zero(1);
        core::ExtraSolveScratch scratch;
        const core::ExtraSolveStats stats =
            core::solveExtraRows(blocks, whole(blocks, G), free, core::ExtraSolveSettings{}, lambda, scratch);
        const double expected = std::clamp((c.target - c.free) / (g + c.compliance), -c.bound, c.bound);
        EXPECT_NEAR(lambda(0), expected, 1e-15 * std::abs(expected))
            << "free " << c.free << ", bound " << c.bound;
        EXPECT_TRUE(stats.converged);
        EXPECT_EQ(stats.sweeps, 1);
        EXPECT_LE(core::conditionResidual(blocks, scratch.velocity, lambda), 1e-15);
    }
}

TEST(ExtraRowsSolve, CoupledDriveRowsMeetTheirConditions)
{
    // Two drive rows of one body with G = [[2, 1], [1, 3]]: the first sticks (its bound is large),
    // the second slides on its bound.
    std::vector<core::ExtraBlock> blocks(2);
    for (core::ExtraBlock& block : blocks)
    {
        block.kind = core::ExtraBlock::Kind::Drive;
        block.count = 1;
        block.bodyB = 0;
    }
    blocks[0].bound = 100.0;
    blocks[1].bound = 0.25;
    core::layoutExtraRows(blocks);
    Eigen::MatrixXd G(2, 2);
    G << 2.0, 1.0, 1.0, 3.0;
    const Eigen::VectorXd free = Eigen::Vector2d(1.0, 4.0);
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(2);
    core::ExtraSolveScratch scratch;
    core::ExtraSolveSettings settings;
    settings.velocityTolerance = 1e-13;
    settings.tolerance = 0.0;
    settings.maxSweeps = 200;
    const core::ExtraSolveStats stats =
        core::solveExtraRows(blocks, whole(blocks, G), free, settings, lambda, scratch);
    ASSERT_TRUE(stats.converged);
    // Row 1 on its lower bound; row 0 then sticks: 2 l0 + 1 (-0.25) = -1.
    EXPECT_DOUBLE_EQ(lambda(1), -0.25);
    EXPECT_NEAR(lambda(0), (-1.0 + 0.25) / 2.0, 1e-13);
    const Eigen::VectorXd v = free + G * lambda;
    EXPECT_NEAR(v(0), 0.0, 1e-13);
    EXPECT_GT(v(1), 0.0) << "still sliding forward, against the friction";
}

} // namespace frontier::test
