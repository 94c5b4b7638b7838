// tests/contact/impact_test.cpp: one impact of a chain on the floor, stepped by core::Simulator
// (contact rows with restitution and a friction cone on top of the tree factorization), against
// the paper's direct collision response core::respondToCollision (Moore and Wilhelms' sticking /
// sliding impulse, docs/method.md §1). Both must give the same impulses.
//
// What makes one step comparable with one collision response:
// * zero gravity, so the free velocities are the pre-impact velocities;
// * the lowest end sphere of the chain exactly touches the floor (depth 0) and approaches
//   faster than the restitution threshold (0.1 m/s), so the Simulator targets -e v_n like the
//   response does; no other shape is within the detector margin: exactly one contact;
// * depth 0 and joints exactly satisfied: the penetration projection has nothing to remove,
//   and a time step of 1e-6 s keeps the joint drift of the position update (O(h^2 w^2 r),
//   about 1e-12 m) below the stabilization tolerance (1e-10 m): no stabilization iteration
//   (asserted);
// * the Simulator then carries each body's angular momentum through the rotation
//   (w' = I_W(R_new)^-1 I_W(R_old) w); the test undoes that exactly to get the solve's w;
// * the contact problem is solved to round-off (tolerance 1e-15, up to 10000 sweeps);
// * friction: mu large, both stick (the 3x3 system, exact); mu small in a planar motion, both
//   slide with friction mu P_N along the one tangent the motion has (the cone's friction
//   opposes the post-impact slip, Moore's the pre-impact slip: the same direction when the slip
//   keeps its direction, which the test checks).
// The contact impulse of the step is the change of the chain's total linear momentum (joint
// impulses are internal).
#include "contact_harness.h"
#include "tests/support/collision_response.h"

#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::test
{
namespace
{

constexpr int cLinks = 4;
constexpr double cRadius = 0.03;
constexpr double cLength = 0.2; // joint spacing (capsule tip to tip)

struct ChainCase
{
    Vec3 direction;          // of the chain, from the floor end up
    Vec3 v0;                 // velocity of link 0's centre (m/s)
    std::vector<Vec3> omega; // angular velocity per link (rad/s)
    double mu = 0.0, e = 0.0;
};

// YAML of a chain of capsules on ball joints whose link 0 end sphere touches the floor z = 0,
// with velocities that satisfy the ball joints.
std::string chainYaml(const ChainCase& c, double dt)
{
    const Vec3 d = c.direction.normalized();
    // Link 0's lower end-sphere centre sits at height cRadius.
    const Vec3 base = Vec3(0, 0, cRadius) - d * cRadius;
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), d);
    std::ostringstream y;
    y.precision(17);
    y << "name: impact chain\nsimulation: {dt: " << dt << ", duration: 1.0, gravity: [0, 0, 0]}\n"
      << "contact: {friction: " << c.mu << ", restitution: " << c.e << "}\nbodies:\n"
      << "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}\n";
    Vec3 v = c.v0;
    for (int i = 0; i < cLinks; ++i)
    {
        const Vec3 x = base + d * (cLength * (i + 0.5));
        if (i > 0)
        {
            // Ball joint i-1/i at a: v_i + w_i x (a - x_i) = v_(i-1) + w_(i-1) x (a - x_(i-1)).
            const Vec3 a = base + d * (cLength * i);
            const Vec3 xp = base + d * (cLength * (i - 0.5));
            v = v + c.omega[static_cast<std::size_t>(i - 1)].cross(a - xp) -
                c.omega[static_cast<std::size_t>(i)].cross(a - x);
        }
        const Vec3& w = c.omega[static_cast<std::size_t>(i)];
        y << "  - name: link" << i << "\n    shape: {type: capsule, radius: " << cRadius
          << ", length: " << cLength - 2 * cRadius << "}\n    mass: " << 0.5 + 0.25 * i << "\n    position: ["
          << x.x() << ", " << x.y() << ", " << x.z() << "]\n    orientation: [" << q.w() << ", " << q.x()
          << ", " << q.y() << ", " << q.z() << "]\n    velocity: [" << v.x() << ", " << v.y() << ", " << v.z()
          << "]\n    angular_velocity: [" << w.x() << ", " << w.y() << ", " << w.z() << "]\n";
    }
    y << "joints:\n";
    for (int i = 1; i < cLinks; ++i)
    {
        const Vec3 a = base + d * (cLength * i);
        y << "  - {name: j" << i << ", type: ball, parent: link" << i - 1 << ", child: link" << i
          << ", anchor: [" << a.x() << ", " << a.y() << ", " << a.z() << "]}\n";
    }
    return y.str();
}

struct Comparison
{
    bool sliding = false;
    double approach = 0.0;
    double velocityError = 0.0; // largest |u_sim - u_response| over bodies (m/s, rad/s)
    double impulseError = 0.0;  // |P_sim - P_response| (N s)
    double jointError = 0.0;    // largest |lambda_sim - lambda_response| (N s)
    double impulse = 0.0;       // |P_response| (N s)
    Vec3 impulseResponse = Vec3::Zero();
    Vec3 slipBefore = Vec3::Zero(); // tangential velocity of link 0's contact point (m/s)
    Vec3 slipAfter = Vec3::Zero();  // the same after the response
    Vec3 impulseSimulator = Vec3::Zero();
    Vec3 slipAfterSimulator = Vec3::Zero(); // after the step (end-of-step velocities, start pose)
};

// Velocity of a body's point, tangential to the normal n.
Vec3 slip(const core::BodyState& s, const Vec3& point, const Vec3& n)
{
    const Vec3 v = s.velocity_W + s.angularVelocity_W.cross(point - s.position_W);
    return v - v.dot(n) * n;
}

Comparison compare(const ChainCase& c)
{
    const double dt = 1e-6;
    core::StepOptions options;
    options.contactSolve.tolerance = 1e-15;
    options.contactSolve.maxSweeps = 10000;
    options.contactSolve.stallSweeps = 0; // to round-off, however slowly: compared at 1e-9
    core::Model model = io::loadSceneFromString(chainYaml(c, dt), "impact_chain.yaml");
    model.contact.tolerance = 0.0;
    model.contact.relativeTolerance = 0.0;
    SceneRun run(std::move(model), options);
    const core::State before = run.state;
    const auto [jointM, jointRad] = run.simulator.jointErrors(before);
    EXPECT_LT(jointM, 1e-14);
    EXPECT_LT(jointRad, 1e-14);

    std::vector<core::Contact> contacts;
    run.detector.detect(before, contacts);
    EXPECT_EQ(contacts.size(), 1u);
    Comparison out;
    if (contacts.size() != 1)
    {
        return out;
    }
    const core::Contact& contact = contacts[0];
    EXPECT_EQ(contact.bodyA, run.model.findBody("link0"));
    EXPECT_NEAR(contact.depth, 0.0, 1e-15);

    core::CollisionEvent event;
    event.bodyA = contact.bodyA;
    event.bodyB = contact.bodyB;
    event.point_W = contact.point_W;
    event.normal_W = contact.normal_W;
    event.restitution = c.e;
    event.friction = c.mu;
    const core::CollisionOutcome response =
        core::respondToCollision(run.model, before, event, core::SolverKind::Linear);
    out.sliding = response.sliding;
    out.approach = response.approachSpeed;
    out.impulseResponse = response.impulseOnA_W;
    out.impulse = response.impulseOnA_W.norm();
    const auto a = static_cast<std::size_t>(contact.bodyA);
    out.slipBefore = slip(before.bodies[a], contact.point_W, contact.normal_W);
    out.slipAfter = slip(response.bodies[a], contact.point_W, contact.normal_W);

    run.step();
    EXPECT_EQ(run.simulator.lastStep().contacts, 1);
    EXPECT_EQ(run.simulator.lastStep().stabilizationIterations, 0);
    const core::Momentum p0 = core::totalMomentum(run.model, before);
    const core::Momentum p1 = core::totalMomentum(run.model, run.state);
    out.impulseSimulator = p1.linear - p0.linear;
    out.impulseError = (out.impulseSimulator - response.impulseOnA_W).norm();
    {
        core::BodyState s = before.bodies[a];
        s.velocity_W = run.state.bodies[a].velocity_W;
        s.angularVelocity_W = run.state.bodies[a].angularVelocity_W;
        out.slipAfterSimulator = slip(s, contact.point_W, contact.normal_W);
    }
    for (std::size_t i = 0; i < run.model.bodies.size(); ++i)
    {
        const core::Body& body = run.model.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        const core::BodyState& s = run.state.bodies[i];
        // Undo carryAngularMomentum: the solve's w has I_W(R_start) w = I_W(R_end) w_end.
        const Vec3 w = core::worldInertia(body, before.bodies[i])
                           .ldlt()
                           .solve(core::worldInertia(body, s) * s.angularVelocity_W);
        out.velocityError =
            std::max(out.velocityError, (s.velocity_W - response.bodies[i].velocity_W).norm());
        out.velocityError = std::max(out.velocityError, (w - response.bodies[i].angularVelocity_W).norm());
    }
    for (std::size_t j = 0; j < run.model.joints.size(); ++j)
    {
        out.jointError =
            std::max(out.jointError,
                     (run.simulator.jointImpulses()[j] - response.jointImpulses[j]).cwiseAbs().maxCoeff());
    }
    std::printf(
        "mu %.2f e %.2f: %s, approach %.4f m/s, slip x %.4f -> %.4f m/s, impulse (%.6f, %.6f, %.6f) N s; "
        "differences: velocity %.3g, impulse %.3g, joint impulses %.3g\n",
        c.mu, c.e, out.sliding ? "sliding" : "sticking", out.approach, out.slipBefore.x(), out.slipAfter.x(),
        out.impulseResponse.x(), out.impulseResponse.y(), out.impulseResponse.z(), out.velocityError,
        out.impulseError, out.jointError);
    return out;
}

ChainCase spatialCase(double mu, double e)
{
    ChainCase c;
    c.direction = Vec3(0.5, 0.3, 1.0);
    c.v0 = Vec3(0.4, -0.3, -2.0);
    c.omega = {Vec3(0.5, -1.0, 0.3), Vec3(-0.8, 0.2, 0.6), Vec3(0.3, 0.9, -0.4), Vec3(1.1, -0.2, 0.2)};
    c.mu = mu;
    c.e = e;
    return c;
}

// In the x-z plane: the chain leans along x, velocities in x-z, angular velocities along y.
ChainCase planarCase(double mu, double e)
{
    ChainCase c;
    c.direction = Vec3(-0.7, 0.0, 1.0);
    c.v0 = Vec3(1.5, 0.0, -2.0);
    c.omega = {Vec3(0, 0.8, 0), Vec3(0, -0.5, 0), Vec3(0, 1.2, 0), Vec3(0, 0.3, 0)};
    c.mu = mu;
    c.e = e;
    return c;
}

// Bound for all cases: velocities (m/s, rad/s), the contact impulse and the joint impulses
// (N s) agree to 1e-9.
constexpr double cTolerance = 1e-9;

TEST(SingleImpact, StickingChainMatchesCollisionResponse)
{
    for (const double e : {0.0, 0.5, 1.0})
    {
        const Comparison r = compare(spatialCase(5.0, e));
        ASSERT_FALSE(r.sliding) << "mu = 5 should stick";
        EXPECT_GT(r.approach, 0.1);
        EXPECT_GT(r.impulse, 0.1);
        EXPECT_LT(r.velocityError, cTolerance) << "e = " << e;
        EXPECT_LT(r.impulseError, cTolerance) << "e = " << e;
        EXPECT_LT(r.jointError, cTolerance) << "e = " << e;
    }
}

TEST(SingleImpact, PlanarStickingChainMatchesCollisionResponse)
{
    const Comparison r = compare(planarCase(5.0, 0.3));
    ASSERT_FALSE(r.sliding);
    EXPECT_LT(r.velocityError, cTolerance);
    EXPECT_LT(r.impulseError, cTolerance);
    EXPECT_LT(r.jointError, cTolerance);
}

// mu = 0.1 in the plane: the chain keeps sliding along +x through the impact (checked: the
// slip keeps its sign, the friction impulse on the chain points along -x and is mu times the
// normal impulse).
TEST(SingleImpact, PlanarSlidingChainMatchesCollisionResponse)
{
    for (const double e : {0.0, 0.5})
    {
        const Comparison r = compare(planarCase(0.1, e));
        ASSERT_TRUE(r.sliding) << "mu = 0.1 should slide";
        ASSERT_GT(r.slipBefore.x(), 0.1);
        ASSERT_GT(r.slipAfter.x(), 0.1) << "the premise: the slip keeps its direction";
        EXPECT_NEAR(r.impulseResponse.x(), -0.1 * r.impulseResponse.z(), 1e-12);
        EXPECT_LT(r.impulseResponse.x(), 0.0);
        EXPECT_LT(r.velocityError, cTolerance) << "e = " << e;
        EXPECT_LT(r.impulseError, cTolerance) << "e = " << e;
        EXPECT_LT(r.jointError, cTolerance) << "e = " << e;
    }
}

// Where the two models differ by design: the chain leaning the other way (+x) gets a normal
// impulse that drives its foot backwards, so a small friction cannot keep the slip's direction:
// before the impact it slides along +x, after it along -x. Moore's model (respondToCollision)
// applies mu P_N against the pre-impact slip; the friction cone of the step (maximal
// dissipation) applies it against the post-impact slip. Recorded: both are mu P_N in size, of
// opposite signs, and each opposes its own reference slip.
TEST(SingleImpact, SlipReversalMooreOpposesPreImpactSlipConeOpposesPostImpactSlip)
{
    ChainCase c = planarCase(0.1, 0.0);
    c.direction = Vec3(0.7, 0.0, 1.0);
    const Comparison r = compare(c);
    ASSERT_TRUE(r.sliding);
    ASSERT_GT(r.slipBefore.x(), 0.1);
    ASSERT_LT(r.slipAfter.x(), -0.1) << "the response reverses the slip";
    // Moore: friction on the chain along -x (against the +x pre-impact slip), |P_T| = mu P_N.
    EXPECT_NEAR(r.impulseResponse.x(), -0.1 * r.impulseResponse.z(), 1e-12);
    // The cone: friction along +x, against the step's post-impact slip (-x), |P_T| = mu P_N.
    EXPECT_LT(r.slipAfterSimulator.x(), -0.1);
    EXPECT_NEAR(r.impulseSimulator.x(), 0.1 * r.impulseSimulator.z(), 1e-9);
    EXPECT_NEAR(r.impulseSimulator.y(), 0.0, 1e-12);
}

} // namespace
} // namespace frontier::test
