// tests/core/joint_rows_test.cpp: each joint type's rows are the exact time derivative of its
// position error (docs/method.md §2), checked by central finite differences of C along a random motion;
// row counts, satisfaction at the initial pose, world parents; a RowSystem keeps each block as
// evaluated, at its size (JointRowsTable).
#include "core/joints/coordinates.h"
#include "core/joints/joint_rows.h"
#include "core/state.h"
#include "random_model.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

using core::JointPose;
using core::JointRows;
using core::JointType;
using core::Model;

const JointType cAllTypes[] = {JointType::Ball,  JointType::Nail,        JointType::Revolute,
                               JointType::Angle, JointType::Cylindrical, JointType::Prismatic,
                               JointType::Fixed};

// Rigid motion for time h with world-frame velocities: x + h v, exp(h w) q.
void advance(const Vec3& v, const Vec3& w, double h, Vec3& x, Quat& q)
{
    x += h * v;
    if (w.norm() > 0.0)
    {
        q = (Quat(Eigen::AngleAxisd(w.norm() * h, w.normalized())) * q).normalized(); // h may be < 0
    }
}

// max |C| over the used rows (a plain loop: GCC 12 warns falsely on head(n) of fixed vectors).
double maxAbsError(const JointRows& rows)
{
    double m = 0.0;
    for (int r = 0; r < rows.count; ++r)
    {
        m = std::max(m, std::abs(rows.error(r)));
    }
    return m;
}

// Two random bodies and a joint of `type` between them (body 0 the parent, or the world for Nail).
struct Pair
{
    Model model;
    core::Joint joint;
    bool parentMoves = true;
};

Pair randomPair(JointType type, Rng& rng)
{
    Pair pair;
    // One draw per statement (argument order is the compiler's): the rotation first, then the position.
    const Quat qa = rng.rotation();
    pair.model.bodies.push_back(boxBody("a", 1.0, Vec3(0.5, 0.3, 0.2), rng.gaussianVec(), qa));
    const Quat qb = rng.rotation();
    pair.model.bodies.push_back(boxBody("b", 2.0, Vec3(0.4, 0.4, 0.2), rng.gaussianVec(), qb));
    pair.parentMoves = type != JointType::Nail;
    pair.joint.name = "j";
    pair.joint.type = type;
    pair.joint.parent = pair.parentMoves ? 0 : core::cWorld;
    pair.joint.child = 1;
    const Vec3 anchor =
        0.5 * (pair.model.bodies[0].position_W + pair.model.bodies[1].position_W) + 0.3 * rng.gaussianVec();
    core::setJointFrames(pair.model, pair.joint, anchor, rng.unitVec());
    return pair;
}

JointPose poseOf(const Pair& pair)
{
    JointPose pose;
    if (pair.parentMoves)
    {
        pose.x_a = pair.model.bodies[0].position_W;
        pose.q_a = pair.model.bodies[0].orientation_WB;
    }
    pose.x_b = pair.model.bodies[1].position_W;
    pose.q_b = pair.model.bodies[1].orientation_WB;
    return pose;
}

// max |dC/dt (central difference) - (J_a u_a + J_b u_b)| / max |J u| at `pose`.
double derivativeMismatch(const Pair& pair, const JointPose& pose, Rng& rng, double* jacobianNorm = nullptr)
{
    const Vec3 va = pair.parentMoves ? rng.gaussianVec() : Vec3::Zero();
    const Vec3 wa = pair.parentMoves ? rng.gaussianVec() : Vec3::Zero();
    const Vec3 vb = rng.gaussianVec();
    const Vec3 wb = rng.gaussianVec();
    JointRows rows;
    core::evaluateJoint(pair.joint, pose, pair.parentMoves, rows);
    Vec6 ua, ub;
    ua << va, wa;
    ub << vb, wb;
    const Eigen::VectorXd ju = rows.J_a.topRows(rows.count) * ua + rows.J_b.topRows(rows.count) * ub;

    constexpr double h = 1e-6;
    auto errorAt = [&](double t)
    {
        JointPose moved = pose;
        if (pair.parentMoves)
        {
            advance(va, wa, t, moved.x_a, moved.q_a);
        }
        advance(vb, wb, t, moved.x_b, moved.q_b);
        JointRows r;
        core::evaluateJoint(pair.joint, moved, pair.parentMoves, r);
        return Vec6(r.error);
    };
    const Vec6 fd = (errorAt(h) - errorAt(-h)) / (2.0 * h);
    const double scale = ju.cwiseAbs().maxCoeff();
    if (jacobianNorm != nullptr)
    {
        *jacobianNorm = scale;
    }
    double worst = 0.0;
    for (int r = 0; r < rows.count; ++r)
    {
        worst = std::max(worst, std::abs(fd(r) - ju(r)));
    }
    return worst / scale;
}

TEST(JointRows, RowCountsMatchTheTable)
{
    Rng rng(1);
    for (JointType type : cAllTypes)
    {
        const Pair pair = randomPair(type, rng);
        JointRows rows;
        core::evaluateJoint(pair.joint, poseOf(pair), pair.parentMoves, rows);
        EXPECT_EQ(rows.count, core::jointRowCount(type)) << core::jointTypeName(type);
        EXPECT_GT(rows.positionRows, 0);
        EXPECT_LE(rows.positionRows, rows.count);
        // Unused rows stay zero, so a 6-row product never leaks into the solve.
        for (int r = rows.count; r < 6; ++r)
        {
            EXPECT_EQ(rows.J_a.row(r).cwiseAbs().maxCoeff(), 0.0);
            EXPECT_EQ(rows.J_b.row(r).cwiseAbs().maxCoeff(), 0.0);
        }
        // The rows are independent at a generic pose.
        Eigen::MatrixXd j(rows.count, 12);
        j << rows.J_a.topRows(rows.count), rows.J_b.topRows(rows.count);
        EXPECT_EQ(Eigen::FullPivLU<Eigen::MatrixXd>(j).rank(), rows.count) << core::jointTypeName(type);
    }
    EXPECT_EQ(core::jointRowCount(JointType::Ball), 3);
    EXPECT_EQ(core::jointRowCount(JointType::Nail), 3);
    EXPECT_EQ(core::jointRowCount(JointType::Revolute), 5);
    EXPECT_EQ(core::jointRowCount(JointType::Angle), 4);
    EXPECT_EQ(core::jointRowCount(JointType::Cylindrical), 4);
    EXPECT_EQ(core::jointRowCount(JointType::Prismatic), 5);
    EXPECT_EQ(core::jointRowCount(JointType::Fixed), 6);
}

TEST(JointRows, SetJointFramesSatisfiesEveryJointAtTheInitialPose)
{
    Rng rng(2);
    for (int trial = 0; trial < 20; ++trial)
    {
        for (JointType type : cAllTypes)
        {
            const Pair pair = randomPair(type, rng);
            JointRows rows;
            core::evaluateJoint(pair.joint, poseOf(pair), pair.parentMoves, rows);
            EXPECT_LT(maxAbsError(rows), 1e-14) << core::jointTypeName(type);
        }
    }
}

TEST(JointRows, WorldParentHasNoParentJacobian)
{
    Rng rng(3);
    const Pair pair = randomPair(JointType::Nail, rng);
    JointRows rows;
    core::evaluateJoint(pair.joint, poseOf(pair), false, rows);
    EXPECT_EQ(rows.J_a.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_GT(rows.J_b.cwiseAbs().maxCoeff(), 0.0);
    // A moved child shows up as a position error equal to the displacement.
    JointPose moved = poseOf(pair);
    moved.x_b += Vec3(0.01, -0.02, 0.03);
    core::evaluateJoint(pair.joint, moved, false, rows);
    EXPECT_LT((rows.error.head<3>() - Vec3(0.01, -0.02, 0.03)).norm(), 1e-14);
}

// At the satisfied pose (C = 0), for every type.
TEST(JointRows, RowsAreTheDerivativeOfTheErrorAtTheSatisfiedPose)
{
    Rng rng(4);
    for (JointType type : cAllTypes)
    {
        double worst = 0.0;
        for (int trial = 0; trial < 20; ++trial)
        {
            const Pair pair = randomPair(type, rng);
            const double mismatch = derivativeMismatch(pair, poseOf(pair), rng);
            EXPECT_LT(mismatch, 1e-8) << core::jointTypeName(type) << ", trial " << trial;
            worst = std::max(worst, mismatch);
        }
        RecordProperty(std::string("fd_mismatch_satisfied_") + core::jointTypeName(type),
                       std::to_string(worst));
        std::printf("%-12s satisfied pose: max |dC/dt - J u| / |J u| = %.3g\n", core::jointTypeName(type),
                    worst);
    }
}

// Away from C = 0 (bodies moved off the joint by a finite amount). The ball, axis-alignment,
// sliding and twist rows are exact derivatives everywhere; the weld rotation rows (fixed,
// prismatic) use J = w_b - w_a, which is the derivative of the rotation-vector error only at
// C = 0, so they are checked near it (0.1 mrad): the mismatch is of the order of the error.
TEST(JointRows, RowsAreTheDerivativeOfTheErrorAwayFromTheSatisfiedPose)
{
    Rng rng(5);
    for (JointType type : cAllTypes)
    {
        const bool weld = type == JointType::Fixed || type == JointType::Prismatic;
        const double offset = weld ? 1e-4 : 0.3;
        double worst = 0.0;
        for (int trial = 0; trial < 20; ++trial)
        {
            const Pair pair = randomPair(type, rng);
            JointPose pose = poseOf(pair);
            pose.x_b += offset * rng.gaussianVec();
            pose.q_b = (Quat(Eigen::AngleAxisd(offset, rng.unitVec())) * pose.q_b).normalized();
            JointRows rows;
            core::evaluateJoint(pair.joint, pose, pair.parentMoves, rows);
            ASSERT_GT(maxAbsError(rows), 1e-2 * offset); // really violated
            const double mismatch = derivativeMismatch(pair, pose, rng);
            EXPECT_LT(mismatch, weld ? 10.0 * offset : 1e-8)
                << core::jointTypeName(type) << ", trial " << trial;
            worst = std::max(worst, mismatch);
        }
        RecordProperty(std::string("fd_mismatch_violated_") + core::jointTypeName(type),
                       std::to_string(worst));
        std::printf("%-12s violated pose: max |dC/dt - J u| / |J u| = %.3g\n", core::jointTypeName(type),
                    worst);
    }
}

// The check itself can fail: a wrong lever arm (a's own anchor instead of the material point of
// a at p_b, docs/method.md §2) is caught for a sliding joint pulled apart along its axis.
TEST(JointRows, FiniteDifferenceCheckDetectsAWrongLeverArm)
{
    Rng rng(6);
    const Pair pair = randomPair(JointType::Cylindrical, rng);
    JointPose pose = poseOf(pair);
    const Vec3 axis_W = pose.q_a * pair.joint.axisParent;
    pose.x_b += 0.5 * axis_W; // slide along the axis: C stays 0, p_b != p_a
    JointRows rows;
    core::evaluateJoint(pair.joint, pose, true, rows);
    EXPECT_LT(maxAbsError(rows), 1e-14);
    EXPECT_LT(derivativeMismatch(pair, pose, rng), 1e-8);
    // Spin a alone: the finite difference of row 0 matches the row (lever p_b - x_a) and not the
    // row with a's own anchor as lever (r_a).
    const core::detail::JointGeometry g = core::detail::jointGeometry(pair.joint, pose);
    const Vec3 d = g.R_a * pair.joint.perpParent1;
    const Vec3 wa = rng.gaussianVec();
    auto rowError = [&](double t)
    {
        JointPose moved = pose;
        advance(Vec3::Zero(), wa, t, moved.x_a, moved.q_a);
        JointRows r;
        core::evaluateJoint(pair.joint, moved, true, r);
        return r.error(0);
    };
    constexpr double h = 1e-6;
    const double fd = (rowError(h) - rowError(-h)) / (2.0 * h);
    const double right = rows.J_a.block<1, 3>(0, 3).dot(wa);
    const double wrong = -g.r_a.cross(d).dot(wa);
    EXPECT_NEAR(fd, right, 1e-7 * std::abs(right));
    EXPECT_GT(std::abs(fd - wrong), 1e-2 * std::abs(right));
}

// A RowSystem keeps every joint's block (random forests of every joint type, damped joints with
// drive rows) exactly as evaluateJointBlock writes it into a JointRows, bit for bit, at the size
// the block needs; the conditions alone (assembleJointConditions) update the counts and errors and
// leave the Jacobians and compliances of the last full assembly.
TEST(JointRowsTable, KeepsEachBlockAsEvaluatedAtItsSize)
{
    for (unsigned seed = 1; seed <= 6; ++seed)
    {
        Model model = randomForest(seed, 3, 8);
        Rng rng(seed);
        for (core::Joint& joint : model.joints)
        {
            joint.damping =
                rng.coin() ? rng.logUniform(1e-2, 1e2) : 0.0; // drive rows where it has a coordinate
        }
        const auto problem = makeProblem(model);
        const core::RowSystem& system = problem->system;
        ASSERT_EQ(system.joints.size(), model.joints.size());
        std::size_t neededValues = 0;
        std::vector<JointRows> full;
        for (std::size_t k = 0; k < model.joints.size(); ++k)
        {
            SCOPED_TRACE("seed " + std::to_string(seed) + ", joint " + std::to_string(k));
            JointRows expected;
            core::evaluateJointBlock(model, problem->layout, problem->state, static_cast<int>(k),
                                     model.simulation.dt, {}, expected);
            const JointRows got = system.joints[k];
            EXPECT_EQ(got.count, expected.count);
            EXPECT_EQ(got.constraintRows, expected.constraintRows);
            EXPECT_EQ(got.positionRows, expected.positionRows);
            EXPECT_TRUE(got.J_a == expected.J_a);
            EXPECT_TRUE(got.J_b == expected.J_b);
            EXPECT_TRUE(got.error == expected.error);
            for (int r = expected.constraintRows; r < expected.count; ++r)
            {
                EXPECT_EQ(got.compliance(r), expected.compliance(r));
            }
            neededValues += 13 * static_cast<std::size_t>(expected.count) +
                            static_cast<std::size_t>(expected.count - expected.constraintRows);
            full.push_back(got);
        }
        EXPECT_EQ(system.joints.storedValues(), neededValues); // J_a, J_b, errors; compliances of drive rows

        // The conditions at another pose: new errors, the rest as the full assembly left it.
        core::State moved = problem->state;
        for (core::BodyState& body : moved.bodies)
        {
            body.position_W += 0.01 * rng.gaussianVec();
            body.orientation_WB =
                (Quat(Eigen::AngleAxisd(0.02, rng.unitVec())) * body.orientation_WB).normalized();
        }
        core::RowSystem conditions = system;
        core::assembleJointConditions(model, moved, conditions);
        for (std::size_t k = 0; k < model.joints.size(); ++k)
        {
            JointRows expected;
            core::evaluateJoint(model.joints[k], core::jointPose(moved, model.joints[k]),
                                !core::jointToWorld(model, model.joints[k]), expected);
            const JointRows got = conditions.joints[k];
            EXPECT_EQ(got.count, expected.constraintRows);
            for (int r = 0; r < 6; ++r)
            {
                EXPECT_EQ(got.error(r), r < got.count ? expected.error(r) : 0.0)
                    << "joint " << k << " row " << r;
            }
            for (int r = full[k].constraintRows; r < full[k].count; ++r)
            {
                EXPECT_EQ(got.compliance(r), full[k].compliance(r));
                EXPECT_TRUE(got.J_b.row(r) == full[k].J_b.row(r));
            }
        }
    }
}

} // namespace
} // namespace frontier::test
