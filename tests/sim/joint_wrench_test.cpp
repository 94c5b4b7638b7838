// tests/sim/joint_wrench_test.cpp: what a joint passes to its child body over a step
// (core::Simulator::jointChildImpulses; the `--joints` file's fx..tz), against statics and
// Newton's second law:
// - a chain hanging at rest passes the weight below each joint, with no torque about its anchors;
// - a welded cantilever holds its weight and its moment about the weld (closed form);
// - every body of articulated scenes (loops, limits, universal joints, welds, damping, friction;
//   euler and rattle) changes its momentum by gravity plus the impulses of its joints, the child
//   receiving what the parent gives up; a ball passes no torque, a free hinge none about its axis;
// - the torque a hinge passes about its axis is that of its damping (-d w, implicit) and friction
//   (the bound while slipping), and on a limit the gravity moment of the rod it holds.
#include "core/joints/coordinates.h"
#include "core/simulator.h"
#include "joint_models.h"
#include "momentum_balance.h"
#include "sim_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace frontier::sim::test
{
namespace
{

using core::Vec3;
using core::Vec6;

constexpr double cG = 9.81; // m/s^2

// Boxes 0.3 m tall of the given masses hanging in a vertical line from (0, 0, 2), each joined to
// the one above at its top face by the joint of the same index (the first to the world).
core::Model hangingChain(const std::vector<core::JointType>& types, const std::vector<double>& masses,
                         core::IntegratorKind integrator, core::SolverKind solver)
{
    core::Model model = emptyTestModel(Vec3(0.0, 0.0, -cG), integrator, 1e-3);
    model.simulation.solver = solver;
    const double length = 0.3;
    for (std::size_t i = 0; i < types.size(); ++i)
    {
        const double top = 2.0 - length * static_cast<double>(i);
        model.bodies.push_back(jointTestBox("link" + std::to_string(i), masses[i], Vec3(0.1, 0.08, length),
                                            Vec3(0.0, 0.0, top - 0.5 * length)));
        addTestJoint(model, types[i], i == 0 ? core::cWorld : static_cast<int>(i) - 1, static_cast<int>(i),
                     Vec3(0.0, 0.0, top), Vec3::UnitX());
    }
    return model;
}

// One step of a run as the tests see it: the states around it and what each joint passed its child
// over it, [N; N m] (the impulses over dt).
struct StepSeen
{
    long step;
    const core::State& before;
    const core::State& after;
    const std::vector<Vec6>& wrench;
    const core::Simulator& simulator;
};

// Runs `model` for `steps` steps and shows each to `see`; stops at the first fatal failure.
template <class See> void runAndSee(const core::Model& model, long steps, See&& see)
{
    core::Simulator simulator(model);
    core::State state = core::initialState(model);
    std::vector<Vec6> wrench;
    for (long step = 0; step < steps && !::testing::Test::HasFatalFailure(); ++step)
    {
        const core::State before = state;
        simulator.step(state);
        simulator.jointChildImpulses(state, wrench);
        for (Vec6& w : wrench)
        {
            w /= model.simulation.dt;
        }
        see(StepSeen{step, before, state, wrench, simulator});
    }
}

struct ChainCase
{
    core::IntegratorKind integrator;
    core::SolverKind solver;
};

class HangingChain : public ::testing::TestWithParam<ChainCase>
{
};

// Joint k holds up everything below it: it passes the weight g (m_k + ... + m_n) straight up, and
// since the chain hangs straight (every centre of mass below the anchors), no torque about its
// anchor. Every joint type that holds a point: nail, hinge, ball, universal, weld.
TEST_P(HangingChain, EachJointPassesTheWeightBelowIt)
{
    const std::vector<core::JointType> types = {core::JointType::Nail, core::JointType::Revolute,
                                                core::JointType::Ball, core::JointType::Angle,
                                                core::JointType::Fixed};
    const std::vector<double> masses = {1.3, 0.7, 2.1, 0.45, 0.9}; // kg
    const core::Model model = hangingChain(types, masses, GetParam().integrator, GetParam().solver);
    runAndSee(model, 300,
              [&](const StepSeen& seen)
              {
                  ASSERT_EQ(seen.wrench.size(), types.size());
                  double below = 0.0; // N: weight below the joint
                  for (std::size_t k = types.size(); k-- > 0;)
                  {
                      below += masses[k] * cG;
                      const Vec3 force = seen.wrench[k].head<3>();
                      const Vec3 torque = seen.wrench[k].tail<3>();
                      ASSERT_NEAR(force.z(), below, 1e-9 * below) << "joint " << k << ", step " << seen.step;
                      ASSERT_LE(force.head<2>().norm(), 1e-9 * below)
                          << "joint " << k << ", step " << seen.step;
                      ASSERT_LE(torque.norm(), 1e-9 * below * 0.3) << "joint " << k << ", step " << seen.step;
                  }
              });
}

INSTANTIATE_TEST_SUITE_P(JointWrench, HangingChain,
                         ::testing::Values(ChainCase{core::IntegratorKind::Euler, core::SolverKind::Linear},
                                           ChainCase{core::IntegratorKind::Rattle, core::SolverKind::Linear},
                                           ChainCase{core::IntegratorKind::Euler, core::SolverKind::Dense}));

// Two boxes welded end to end, horizontal along +x from a weld to the world at (0, 0, 1): the
// outer weld carries the outer box, m1 g up and the moment -m1 g (0.25 m) about y at its anchor;
// the inner weld both, -(m0 g 0.25 + m1 g 0.75) about y.
TEST(JointWrench, WeldedCantileverHoldsItsWeightAndMoment)
{
    core::Model model = emptyTestModel(Vec3(0.0, 0.0, -cG), core::IntegratorKind::Euler, 1e-3);
    const double m0 = 1.6;
    const double m1 = 0.8;
    model.bodies.push_back(jointTestBox("inner", m0, Vec3(0.5, 0.05, 0.05), Vec3(0.25, 0.0, 1.0)));
    model.bodies.push_back(jointTestBox("outer", m1, Vec3(0.5, 0.05, 0.05), Vec3(0.75, 0.0, 1.0)));
    addTestJoint(model, core::JointType::Fixed, core::cWorld, 0, Vec3(0.0, 0.0, 1.0), Vec3::UnitZ());
    addTestJoint(model, core::JointType::Fixed, 0, 1, Vec3(0.5, 0.0, 1.0), Vec3::UnitZ());
    const Vec6 expected[2] = {
        (Vec6() << 0, 0, (m0 + m1) * cG, 0, -(m0 * 0.25 + m1 * 0.75) * cG, 0).finished(),
        (Vec6() << 0, 0, m1 * cG, 0, -m1 * 0.25 * cG, 0).finished()};
    runAndSee(model, 100,
              [&](const StepSeen& seen)
              {
                  for (std::size_t k = 0; k < 2; ++k)
                  {
                      ASSERT_LE((seen.wrench[k] - expected[k]).norm(), 1e-9 * expected[k].norm())
                          << "weld " << k << ", step " << seen.step << ": " << seen.wrench[k].transpose();
                  }
              });
}

// Newton's second law for every moving body over every step (momentum_balance.h), joints only:
// residuals measured below 2e-13 of the step's largest impulse. (A rail on a turning parent is
// left out: its sliding rows turn with the parent, so their linear impulse depends on the pose.)
void expectBodiesFollowTheirJointImpulses(const core::Model& model, long steps, const std::string& what)
{
    double worst = 0.0;
    std::vector<Vec6> impulses;
    runAndSee(model, steps,
              [&](const StepSeen& seen)
              {
                  impulses = seen.wrench;
                  for (Vec6& impulse : impulses)
                  {
                      impulse *= model.simulation.dt;
                  }
                  const frontier::test::SecondLawResidual residual =
                      frontier::test::secondLawResidual(model, seen.before, seen.after, impulses, {});
                  worst = std::max(worst, residual.relative);
                  ASSERT_LE(residual.relative, 2e-12)
                      << what << ": body '" << residual.body << "', step " << seen.step;
              });
    ::testing::Test::RecordProperty(what, sci(worst));
}

class SecondLaw : public ::testing::TestWithParam<core::IntegratorKind>
{
};

TEST_P(SecondLaw, BundledScenesBodiesMoveByTheirJointImpulses)
{
    for (const char* scene :
         {"four_bar.yaml", "double_pendulum.yaml", "universal_shaft.yaml", "nail_and_weld.yaml",
          "limits.yaml", "cart_pendulum.yaml", "chain30.yaml", "cylindrical_slide.yaml"})
    {
        core::Model model = loadBundled(scene);
        model.simulation.integrator = GetParam();
        expectBodiesFollowTheirJointImpulses(model, 1500, scene);
    }
}

// While the scenes swing, a ball or nail joint passes no torque about its anchor, and a hinge
// without limit, damping or friction none about its axis (to round-off of the force times 1 m):
// the rows of the step's start, its drift correction and (rattle) its end are all taken at one pose.
TEST_P(SecondLaw, BallsPassNoTorqueAndFreeHingesNoneAboutTheirAxis)
{
    for (const char* scene :
         {"nail_and_weld.yaml", "double_pendulum.yaml", "four_bar.yaml", "chain30.yaml", "pendulum.yaml"})
    {
        core::Model model = loadBundled(scene);
        model.simulation.integrator = GetParam();
        int checked = 0;
        runAndSee(model, 1500,
                  [&](const StepSeen& seen)
                  {
                      for (std::size_t k = 0; k < model.joints.size(); ++k)
                      {
                          const core::Joint& joint = model.joints[k];
                          const Vec3 force = seen.wrench[k].head<3>();
                          const Vec3 torque = seen.wrench[k].tail<3>();
                          const double tolerance = 1e-12 * std::max(force.norm(), 1.0);
                          const std::string where =
                              std::string(scene) + ": " + joint.name + ", step " + std::to_string(seen.step);
                          if (joint.type == core::JointType::Ball || joint.type == core::JointType::Nail)
                          {
                              ASSERT_LE(torque.norm(), tolerance) << where;
                              ++checked;
                          }
                          else if (joint.type == core::JointType::Revolute)
                          {
                              const Vec3 axis = core::jointPose(seen.after, joint).q_a * joint.axisParent;
                              ASSERT_LE(std::abs(torque.dot(axis)), tolerance) << where;
                              ++checked;
                          }
                      }
                  });
        EXPECT_GT(checked, 0) << scene;
    }
}

// Damping and Coulomb friction rows (in the joint's block and extra rows), and limits, on a rail
// to the world tilted 30 degrees under gravity, and on a chain of damped hinges.
TEST_P(SecondLaw, DampedRailWithFrictionAndLimitsAndDampedChain)
{
    core::Model rail =
        slidingBox(1.2, Vec3(std::cos(0.5236), 0.0, std::sin(0.5236)), Vec3(0.0, 0.0, -cG), GetParam());
    rail.joints[0].damping = 2.0;  // N s/m
    rail.joints[0].friction = 3.0; // N
    rail.joints[0].limits = std::array<double, 2>{-0.05, 0.06};
    expectBodiesFollowTheirJointImpulses(rail, 1500, "rail");
    core::Model chain = hingedChain(4, GetParam());
    for (core::Joint& joint : chain.joints)
    {
        joint.damping = 0.3;  // N m s/rad
        joint.friction = 0.2; // N m
    }
    expectBodiesFollowTheirJointImpulses(chain, 1500, "chain");
}

INSTANTIATE_TEST_SUITE_P(JointWrench, SecondLaw,
                         ::testing::Values(core::IntegratorKind::Euler, core::IntegratorKind::Rattle,
                                           core::IntegratorKind::Rattle4));

// A box spinning on a damped hinge through its centre, no gravity: the hinge's torque about its
// axis is the damping's, -d w at the end of the step (implicit), and nothing else.
TEST(JointWrench, DampedHingeTorqueIsMinusDampingTimesSpeed)
{
    core::Model model = spinningBox(8.0);
    const double d = 0.05; // N m s/rad
    model.joints[0].damping = d;
    runAndSee(model, 500,
              [&](const StepSeen& seen)
              {
                  const Vec3 torque = seen.wrench[0].tail<3>();
                  const double w = seen.after.bodies[0].angularVelocity_W.z();
                  ASSERT_NEAR(torque.z(), -d * w, 1e-9 * d * 8.0) << "step " << seen.step;
                  ASSERT_LE(torque.head<2>().norm(), 1e-9 * d * 8.0) << "step " << seen.step;
                  ASSERT_LE(seen.wrench[0].head<3>().norm(), 1e-9) << "step " << seen.step;
              });
}

// The same box on a hinge with Coulomb friction f: while it slips, the hinge passes exactly -f
// about its axis; once it has stopped (after I w0 / f = 0.67 s), nothing (no other torque acts).
TEST(JointWrench, HingeFrictionPassesItsBoundWhileSlipping)
{
    core::Model model = spinningBox(0.5);
    const double f = 0.01; // N m
    model.joints[0].friction = f;
    int slipping = 0;
    int stuck = 0;
    runAndSee(model, 1000,
              [&](const StepSeen& seen)
              {
                  const double torque = seen.wrench[0](5);
                  const double before = seen.before.bodies[0].angularVelocity_W.z();
                  const double after = seen.after.bodies[0].angularVelocity_W.z();
                  if (after > 1e-9)
                  {
                      ++slipping;
                      ASSERT_NEAR(torque, -f, 1e-9 * f) << "step " << seen.step;
                  }
                  else if (std::abs(before) < 1e-12 && std::abs(after) < 1e-12)
                  {
                      ++stuck;
                      ASSERT_LE(std::abs(torque), 1e-9 * f) << "step " << seen.step;
                  }
              });
    EXPECT_NEAR(slipping, 667, 2);
    EXPECT_GE(stuck, 330);
}

// The rod of joint_models.h falls onto its limit at 0.4 rad and rests there: the hinge passes its
// weight and, through the limit, the gravity moment about the hinge, m g (L/2) cos(0.4) about -y.
// Resting, the contact solve leaves the rod turning by up to its tolerance (3e-5 rad/s); over a
// second those changes of angular momentum cancel but for the first and last, so the mean torque
// of the second is the moment within 2 I 3e-5 / 1 s (I = m L^2 / 3 about the hinge).
TEST(JointWrench, RodOnItsLimitPassesTheGravityMoment)
{
    const core::Model model = hingedRod(0.0, std::array<double, 2>{-1.0, 0.4}, Vec3(0.0, 0.0, -cG));
    Vec6 sum = Vec6::Zero(); // N s, N m s over the last second
    int pushing = 0;
    runAndSee(model, 3000,
              [&](const StepSeen& seen)
              {
                  if (seen.step >= 2000)
                  {
                      sum += seen.wrench[0] * model.simulation.dt;
                      pushing += seen.simulator.pushingLimitRows();
                  }
              });
    EXPECT_EQ(pushing, 1000);
    const Vec6 mean = sum / 1.0;                           // N, N m: the impulses of one second
    const double moment = 1.0 * cG * 0.25 * std::cos(0.4); // N m
    const double inertia = 1.0 * 0.25 / 3.0;               // kg m^2 about the hinge
    const double linear = 2.0 * 1.0 * 0.25 * 3e-5;         // N s: the same bound on m v = m (L/2) w
    EXPECT_NEAR(mean(2), cG, linear);
    EXPECT_NEAR(mean(4), -moment, 2.0 * inertia * 3e-5);
    EXPECT_LE(Vec3(mean(0), mean(1), 0.0).norm(), linear);
}

} // namespace
} // namespace frontier::sim::test
