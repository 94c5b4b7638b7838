// tests/core/collision_response_test.cpp: the paper's one-collision response (docs/method.md §1):
// a sphere hitting the floor (closed forms for sticking and sliding), a chain struck at its end
// (linear against dense, and against one dense KKT system with the three collision rows).
#include "core/contact_rows.h"
#include "core/dense_solver.h"
#include "random_model.h"
#include "tests/support/collision_response.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

using core::CollisionEvent;
using core::CollisionOutcome;
using core::JointType;
using core::Model;
using core::SolverKind;

Vec6 velocityOf(const core::BodyState& s)
{
    Vec6 u;
    u << s.velocity_W, s.angularVelocity_W;
    return u;
}

TEST(ContactRows, RowsMeasureTheRelativeVelocityOfTheContactPoint)
{
    Model model = straightChain({1.0, 2.0}, JointType::Ball, false);
    model.bodies[0].velocity_W = Vec3(0.1, 0.2, 0.3);
    model.bodies[0].angularVelocity_W = Vec3(-1.0, 0.5, 2.0);
    model.bodies[1].velocity_W = Vec3(-0.4, 0.0, 0.7);
    model.bodies[1].angularVelocity_W = Vec3(0.3, -0.2, 0.1);
    const core::State state = core::initialState(model);
    const Vec3 point(1.0, 0.05, -0.02);
    const Vec3 normal = Vec3(0.3, -1.0, 0.2).normalized();
    const core::ContactRows rows = core::contactRows(model, state, 0, 1, point, normal);
    EXPECT_LT((rows.directions.transpose() * rows.directions - Mat3::Identity()).cwiseAbs().maxCoeff(),
              1e-15);
    EXPECT_LT((rows.directions.col(0) - normal).norm(), 1e-15);
    auto pointVelocity = [&](int i)
    {
        const core::BodyState& s = state.bodies[static_cast<std::size_t>(i)];
        return Vec3(s.velocity_W + s.angularVelocity_W.cross(point - s.position_W));
    };
    const Vec3 expected = rows.directions.transpose() * (pointVelocity(1) - pointVelocity(0));
    const Vec3 got = rows.J_A * velocityOf(state.bodies[0]) + rows.J_B * velocityOf(state.bodies[1]);
    EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-15);
    // A world B has no Jacobian.
    const core::ContactRows world = core::contactRows(model, state, 0, core::cWorld, point, normal);
    EXPECT_EQ(world.J_B.cwiseAbs().maxCoeff(), 0.0);
}

// A sphere (radius r, mass m, I = 2/5 m r^2) resting on nothing, hitting the floor z = 0 at
// its lowest point with velocity v (v_z < 0) and spin w. Contact lever r_c = -r z, normal from
// the sphere to the floor n = -z, B = the world.
//
// Derivation. The contact point's velocity is c = v + w x r_c. An impulse P at the contact point
// changes v by P/m and w by (r_c x P)/I, so c changes by P/m + ((r_c x P)/I) x r_c. For the
// normal part P_n z: r_c x z = 0, so only v_z changes: v_z' = -e v_z needs P_n = -m (1 + e) v_z.
// For a tangential part P_t (P_t . z = 0): (r_c x P_t) x r_c = r^2 P_t, so the tangential
// contact velocity changes by P_t (1/m + r^2/I) = 7 P_t / (2 m).
//   Sticking (c_t' = 0): P_t = -(2 m / 7) s, s = c_t the pre-impact slip; then
//     v_t' = v_t - (2/7) s = (5 v_t - 2 (w x r_c)_t) / 7,  w' = w + (r_c x P_t) / I.
//   In the plane (v_x, w_y only): s = v_x - r w_y, v_x' = (5 v_x + 2 r w_y) / 7, r w_y' = v_x'.
//   Valid when |P_t| <= mu P_n.
//   Sliding: P_t = -mu P_n s/|s| (against the pre-impact slip), same P_n.
struct SphereCase
{
    double r = 0.3, m = 2.0, e = 0.5;
    Vec3 v = Vec3(1.5, -0.4, -2.0);
    Vec3 w = Vec3(0.7, 3.0, -1.1);
};

Model sphereModel(const SphereCase& c)
{
    Model model;
    core::Body ball;
    ball.name = "ball";
    ball.mass = c.m;
    ball.inertia_B = 0.4 * c.m * c.r * c.r * Mat3::Identity();
    ball.position_W = Vec3(0.2, -0.1, c.r);
    ball.orientation_WB = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
    ball.velocity_W = c.v;
    ball.angularVelocity_W = c.w;
    model.bodies.push_back(ball);
    return model;
}

CollisionEvent floorHit(const Model& model, const SphereCase& c, double mu)
{
    CollisionEvent event;
    event.bodyA = 0;
    event.bodyB = core::cWorld;
    event.point_W = model.bodies[0].position_W - Vec3(0, 0, c.r);
    event.normal_W = -Vec3::UnitZ();
    event.restitution = c.e;
    event.friction = mu;
    return event;
}

TEST(CollisionResponse, SphereSticksWithTheClosedFormWhenFrictionIsLarge)
{
    const SphereCase c;
    const Model model = sphereModel(c);
    const core::State state = core::initialState(model);
    const double I = 0.4 * c.m * c.r * c.r;
    const Vec3 rc(0, 0, -c.r);
    const Vec3 slip = c.v + c.w.cross(rc);
    const Vec3 s(slip.x(), slip.y(), 0.0);
    const Vec3 pt = -(2.0 * c.m / 7.0) * s;
    const double pn = -c.m * (1.0 + c.e) * c.v.z();
    const Vec3 P = pt + Vec3(0, 0, pn);
    const Vec3 v1 = c.v + P / c.m;
    const Vec3 w1 = c.w + rc.cross(P) / I;
    // The planar formula of the derivation, as a cross-check of the vector form.
    EXPECT_NEAR(v1.x(), (5.0 * c.v.x() - 2.0 * (c.w.cross(rc)).x()) / 7.0, 1e-15);
    EXPECT_NEAR(v1.x(), (5.0 * c.v.x() + 2.0 * c.r * c.w.y()) / 7.0, 1e-15);
    EXPECT_NEAR(c.r * w1.y(), v1.x(), 1e-15); // rolls without slipping
    const double mu = 10.0;
    ASSERT_LE(pt.norm(), mu * pn);
    for (SolverKind kind : {SolverKind::Linear, SolverKind::Dense})
    {
        SCOPED_TRACE(core::solverName(kind));
        const CollisionOutcome out = core::respondToCollision(model, state, floorHit(model, c, mu), kind);
        EXPECT_FALSE(out.sliding);
        EXPECT_NEAR(out.approachSpeed, -c.v.z(), 1e-15);
        const core::BodyState& b = out.bodies[0];
        EXPECT_LT((b.velocity_W - v1).cwiseAbs().maxCoeff(), 1e-12 * c.v.norm()) << b.velocity_W.transpose();
        EXPECT_LT((b.angularVelocity_W - w1).cwiseAbs().maxCoeff(), 1e-12 * c.w.norm())
            << b.angularVelocity_W.transpose();
        EXPECT_LT((out.impulseOnA_W - P).cwiseAbs().maxCoeff(), 1e-12 * P.norm())
            << out.impulseOnA_W.transpose();
        // The conditions themselves: no slip after, normal velocity -e times before.
        const Vec3 after = b.velocity_W + b.angularVelocity_W.cross(rc);
        EXPECT_LT(std::abs(after.x()) + std::abs(after.y()), 1e-12 * c.v.norm());
        EXPECT_NEAR(after.z(), -c.e * slip.z(), 1e-12 * c.v.norm());
        EXPECT_NEAR(b.angularVelocity_W.z(), c.w.z(), 1e-12 * c.w.norm()); // no torque about the normal
    }
}

TEST(CollisionResponse, SphereSlidesWithFrictionMuTimesNormalWhenFrictionIsSmall)
{
    const SphereCase c;
    const Model model = sphereModel(c);
    const core::State state = core::initialState(model);
    const double I = 0.4 * c.m * c.r * c.r;
    const Vec3 rc(0, 0, -c.r);
    const Vec3 slip = c.v + c.w.cross(rc);
    const Vec3 s(slip.x(), slip.y(), 0.0);
    const double mu = 0.05;
    const double pn = -c.m * (1.0 + c.e) * c.v.z();
    ASSERT_GT((2.0 * c.m / 7.0) * s.norm(), mu * pn); // sticking would leave the cone
    const Vec3 P = Vec3(0, 0, pn) - mu * pn * s.normalized();
    const Vec3 v1 = c.v + P / c.m;
    const Vec3 w1 = c.w + rc.cross(P) / I;
    for (SolverKind kind : {SolverKind::Linear, SolverKind::Dense})
    {
        SCOPED_TRACE(core::solverName(kind));
        const CollisionOutcome out = core::respondToCollision(model, state, floorHit(model, c, mu), kind);
        EXPECT_TRUE(out.sliding);
        const Vec3 tangential(out.impulseOnA_W.x(), out.impulseOnA_W.y(), 0.0);
        EXPECT_NEAR(tangential.norm(), mu * out.impulseOnA_W.z(), 1e-14 * pn);
        EXPECT_LT((tangential.normalized() + s.normalized()).norm(), 1e-14); // against the slip
        EXPECT_LT((out.impulseOnA_W - P).cwiseAbs().maxCoeff(), 1e-12 * P.norm());
        EXPECT_LT((out.bodies[0].velocity_W - v1).cwiseAbs().maxCoeff(), 1e-12 * c.v.norm());
        EXPECT_LT((out.bodies[0].angularVelocity_W - w1).cwiseAbs().maxCoeff(), 1e-12 * c.w.norm());
        const Vec3 after = out.bodies[0].velocity_W + out.bodies[0].angularVelocity_W.cross(rc);
        EXPECT_NEAR(after.z(), -c.e * slip.z(), 1e-12 * c.v.norm());
    }
}

// A chain of mixed joint types (a random tree grown as a chain), moving rigidly downwards and
// sideways, hits the floor with its last body.
struct ChainHit
{
    Model model;
    core::State state;
    CollisionEvent event;
};

ChainHit chainHit(unsigned seed, int bodies, double mu, double restitution)
{
    ChainHit hit;
    RandomTreeOptions options;
    options.bodies = bodies;
    options.branching = 0.0; // a chain
    options.minMass = 0.1;
    options.maxMass = 10.0;
    hit.model = randomTree(seed, options);
    // Rigid motion V + Omega x (x - x0) satisfies every joint.
    const Vec3 x0 = hit.model.bodies[0].position_W;
    const Vec3 V(2.0, -0.5, -3.0), omega(0.02, -0.03, 0.05);
    for (core::Body& body : hit.model.bodies)
    {
        body.velocity_W = V + omega.cross(body.position_W - x0);
        body.angularVelocity_W = omega;
    }
    hit.state = core::initialState(hit.model);
    const int last = bodies - 1;
    hit.event.bodyA = last;
    hit.event.bodyB = core::cWorld;
    hit.event.point_W = hit.model.bodies[static_cast<std::size_t>(last)].position_W + Vec3(0.1, -0.05, -0.2);
    hit.event.normal_W = -Vec3::UnitZ();
    hit.event.restitution = restitution;
    hit.event.friction = mu;
    return hit;
}

double outcomeDifference(const CollisionOutcome& a, const CollisionOutcome& b, double& scale)
{
    double diff = 0.0;
    scale = 0.0;
    for (std::size_t i = 0; i < a.bodies.size(); ++i)
    {
        diff = std::max(diff, (velocityOf(a.bodies[i]) - velocityOf(b.bodies[i])).cwiseAbs().maxCoeff());
        scale = std::max(scale, velocityOf(b.bodies[i]).cwiseAbs().maxCoeff());
    }
    return diff / scale;
}

TEST(CollisionResponse, ChainStruckAtItsEndAgreesBetweenLinearAndDense)
{
    for (double mu : {5.0, 0.05})
    {
        SCOPED_TRACE("mu " + std::to_string(mu));
        const ChainHit hit = chainHit(11, 12, mu, 0.3);
        const CollisionOutcome linear =
            core::respondToCollision(hit.model, hit.state, hit.event, SolverKind::Linear);
        const CollisionOutcome dense =
            core::respondToCollision(hit.model, hit.state, hit.event, SolverKind::Dense);
        ASSERT_GT(linear.approachSpeed, 0.5);
        EXPECT_EQ(linear.sliding, mu < 1.0);
        EXPECT_EQ(dense.sliding, linear.sliding);
        double scale = 0.0;
        const double dv = outcomeDifference(linear, dense, scale);
        EXPECT_LT(dv, 1e-12); // measured 3.5e-14
        EXPECT_LT((linear.impulseOnA_W - dense.impulseOnA_W).norm(), 1e-12 * dense.impulseOnA_W.norm());
        double lambdaScale = 0.0, lambdaDiff = 0.0;
        for (std::size_t j = 0; j < linear.jointImpulses.size(); ++j)
        {
            lambdaScale = std::max(lambdaScale, dense.jointImpulses[j].cwiseAbs().maxCoeff());
            lambdaDiff = std::max(lambdaDiff,
                                  (linear.jointImpulses[j] - dense.jointImpulses[j]).cwiseAbs().maxCoeff());
        }
        EXPECT_LT(lambdaDiff, 1e-12 * lambdaScale);
        std::printf("chain hit, mu %.2f: linear vs dense velocity %.3g, impulse %.3g (relative)\n", mu, dv,
                    lambdaDiff / lambdaScale);
        RecordProperty("linear_vs_dense_velocity_mu_" + std::to_string(mu), std::to_string(dv));
    }
}

// Sticking: one dense KKT system with the joints and the three collision rows,
//   [ A     Jc^T ] [ x  ]   [ b      ]      A, b: the joint system in layout order
//   [ Jc    0    ] [ yc ] = [ target ]      Jc: the contact rows at body A's columns
// with target = (-e * normal velocity before, 0, 0) and yc = -lambda_c, solved by FullPivLU.
TEST(CollisionResponse, StickingChainMatchesOneDenseSystemWithTheCollisionRows)
{
    const ChainHit hit = chainHit(12, 10, 5.0, 0.4);
    const Model& model = hit.model;
    const CollisionOutcome linear = core::respondToCollision(model, hit.state, hit.event, SolverKind::Linear);
    ASSERT_FALSE(linear.sliding);

    const core::FrontierLayout layout = core::buildFrontierLayout(model);
    core::RowSystem system;
    core::assembleRows(model, layout, hit.state, 0.0, system);
    const Eigen::MatrixXd a = core::DenseSolver::assemble(system);
    const int n = layout.size;
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + 3, n + 3);
    k.topLeftCorner(n, n) = a;
    const core::ContactRows rows = core::contactRows(model, hit.state, hit.event.bodyA, hit.event.bodyB,
                                                     hit.event.point_W, hit.event.normal_W);
    const int col =
        layout.blocks[static_cast<std::size_t>(layout.bodyBlock[static_cast<std::size_t>(hit.event.bodyA)])]
            .offset;
    k.block(n, col, 3, 6) = rows.J_A;
    k.block(col, n, 6, 3) = rows.J_A.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 3);
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const int o = layout.blocks[static_cast<std::size_t>(layout.bodyBlock[i])].offset;
        rhs.segment<3>(o) = system.mass[i] * hit.state.bodies[i].velocity_W;
        rhs.segment<3>(o + 3) = system.inertia_W[i] * hit.state.bodies[i].angularVelocity_W;
    }
    const Eigen::Vector3d before =
        rows.J_A * velocityOf(hit.state.bodies[static_cast<std::size_t>(hit.event.bodyA)]);
    rhs(n) = -hit.event.restitution * before(0);
    const Eigen::VectorXd x = Eigen::FullPivLU<Eigen::MatrixXd>(k).solve(rhs);
    ASSERT_LT((k * x - rhs).cwiseAbs().maxCoeff(), 1e-12 * rhs.cwiseAbs().maxCoeff());

    double scale = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const int o = layout.blocks[static_cast<std::size_t>(layout.bodyBlock[i])].offset;
        const Vec6 u = x.segment<6>(o);
        scale = std::max(scale, u.cwiseAbs().maxCoeff());
        diff = std::max(diff, (velocityOf(linear.bodies[i]) - u).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(diff, 1e-12 * scale); // measured 1.2e-14
    const Eigen::Vector3d lambdaC = -x.tail<3>();
    const Vec3 impulse = rows.J_A.leftCols<3>().transpose() * lambdaC;
    EXPECT_LT((linear.impulseOnA_W - impulse).norm(), 1e-12 * impulse.norm());
    double lambdaScale = 0.0, lambdaDiff = 0.0;
    for (std::size_t j = 0; j < model.joints.size(); ++j)
    {
        const core::LayoutBlock& edge = layout.blocks[static_cast<std::size_t>(layout.jointBlock[j])];
        for (int r = 0; r < edge.dim; ++r)
        {
            const double expected = -x(edge.offset + r);
            lambdaScale = std::max(lambdaScale, std::abs(expected));
            lambdaDiff = std::max(lambdaDiff, std::abs(linear.jointImpulses[j](r) - expected));
        }
    }
    EXPECT_LT(lambdaDiff, 1e-12 * lambdaScale);
    std::printf("sticking chain vs one dense system: velocity %.3g, joint impulse %.3g (relative)\n",
                diff / scale, lambdaDiff / lambdaScale);
    // The sticking conditions hold after the impact.
    const Eigen::Vector3d after =
        rows.J_A * velocityOf(linear.bodies[static_cast<std::size_t>(hit.event.bodyA)]);
    EXPECT_NEAR(after(0), -hit.event.restitution * before(0), 1e-12 * std::abs(before(0)));
    EXPECT_LT(after.tail<2>().norm(), 1e-12 * std::abs(before(0)));
    EXPECT_LE(lambdaC.tail<2>().norm(), hit.event.friction * lambdaC(0));
}

} // namespace
} // namespace frontier::test
