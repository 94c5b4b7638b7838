// tests/contact/penetration_test.cpp: bodies that start inside the floor, inside each other or
// beyond a joint limit are recovered boundedly (core::PenetrationProjection, core/penetration.h)
// and never explode; a run that does fail names the likely cause (core/failure_hint.h).
//
// The bounds, from what the projection is: a displacement H^-1 J^T mu that leaves velocities
// alone, moves no body faster than v_max = StepOptions::penetrationMaxSpeed and turns none faster
// than w_max = penetrationMaxAngularSpeed, and leaves rows the joints hold alone. So
// * recovery of an overlap d takes about d / (v_max dt) steps (rotations: angle / (w_max dt));
// * a step adds at most the potential energy of lifting every body by v_max dt;
// * kinetic energy comes only from the physics: a body resting on what it was pushed out of
//   gains at most one step's fall, 1/2 m (|g| dt)^2, before its contact stops it.
#include "contact_harness.h"
#include "core/extra_rows.h"
#include "core/failure_hint.h"
#include "core/joints/coordinates.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>

namespace frontier::test
{
namespace
{

const core::StepOptions cDefaults;

// What a run did, measured here from the states after every step.
struct Recovery
{
    std::string failure;         // the SimulationError's message, if any
    bool finite = true;          // every state finite
    long steps = 0;              // steps taken
    double energyStart = 0.0;    // J
    double energyMax = 0.0;      // J, over the run
    double energyStepRise = 0.0; // largest rise of the total energy in one step (J)
    double kineticMax = 0.0;     // J, over the run
    double jointErrorM = 0.0;    // largest joint gap after a step (m)
    double depthStart = 0.0;     // deepest contact the first step found (m)
    long outStep = -1;           // first step that starts with no contact deeper than cOut
};

constexpr double cOut = 1e-3; // m: "out": overlaps left to the slop (0.5 mm) and the contacts

Recovery runFor(SceneRun& run, double seconds)
{
    Recovery r;
    r.energyStart = core::totalEnergy(run.model, run.state);
    r.energyMax = r.energyStart;
    double energy = r.energyStart;
    const long steps = run.stepsFor(seconds);
    try
    {
        for (long k = 0; k < steps; ++k)
        {
            run.step();
            r.steps = k + 1;
            r.finite = allFinite(run.state);
            if (!r.finite)
            {
                break;
            }
            const core::StepStats& stats = run.simulator.lastStep();
            if (k == 0)
            {
                r.depthStart = stats.maxPenetrationM;
            }
            if (r.outStep < 0 && stats.maxPenetrationM <= cOut)
            {
                r.outStep = k; // this step started out of the overlap
            }
            const double next = core::totalEnergy(run.model, run.state);
            r.energyStepRise = std::max(r.energyStepRise, next - energy);
            energy = next;
            r.energyMax = std::max(r.energyMax, energy);
            r.kineticMax = std::max(r.kineticMax, core::kineticEnergy(run.model, run.state));
            r.jointErrorM = std::max(r.jointErrorM, stats.maxJointErrorM);
        }
    }
    catch (const core::SimulationError& e)
    {
        r.finite = false;
        r.failure = e.what();
    }
    std::printf("%ld steps: energy %.6g J -> max %.6g J (largest rise in a step %.3g J), kinetic max %.3g J, "
                "joint gap %.3g m, depth %.3g m, out at step %ld %s\n",
                r.steps, r.energyStart, r.energyMax, r.energyStepRise, r.kineticMax, r.jointErrorM,
                r.depthStart, r.outStep, r.failure.c_str());
    return r;
}

double movingMass(const core::Model& model)
{
    double m = 0.0;
    for (const core::Body& body : model.bodies)
    {
        m += body.isStatic ? 0.0 : body.mass;
    }
    return m;
}

// One step's fall of all moving bodies: 1/2 m (|g| dt)^2 (J).
double oneStepFall(const core::Model& model)
{
    const double v = model.simulation.gravity.norm() * model.simulation.dt;
    return 0.5 * movingMass(model) * v * v;
}

// The most energy one recovery step adds (J): lifting every moving body by v_max dt, plus what
// the step's own contact solve and integration may move between kinetic and potential energy
// (m |g|^2 dt^2, a step's worth of gravity acting through a step's motion).
double oneStepLift(const core::Model& model)
{
    const double g = model.simulation.gravity.norm();
    const double dt = model.simulation.dt;
    return movingMass(model) * g * (cDefaults.penetrationMaxSpeed * dt + g * dt * dt);
}

// Steps to remove an overlap d (m) at v_max, and cSpare more for the contacts to settle.
long recoverySteps(double depth, double dt)
{
    constexpr long cSpare = 20;
    return static_cast<long>(std::ceil(depth / (cDefaults.penetrationMaxSpeed * dt))) + cSpare;
}

// A cylinder (radius 0.3 m, 0.2 m long, 56.5 kg) on a revolute joint to the world at the origin.
std::string wheelScene(const std::string& position, const std::string& orientation, const std::string& axis,
                       const std::string& spin)
{
    return R"(
simulation: {dt: 0.001}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}
  - name: wheel
    shape: {type: cylinder, radius: 0.3, length: 0.2}
    position: )" +
           position + "\n    orientation: " + orientation + "\n    angular_velocity: " + spin + R"(
joints:
  - {name: hinge, type: revolute, parent: world, child: wheel, anchor: [0, 0, 0], axis: )" +
           axis + "}\n";
}

// The issue's case: a cylinder on a vertical hinge sunk 0.1 m into the floor went from 0 J to
// 1e22 J in a few steps. No motion the hinge allows lifts it, so the projection must leave its
// contacts alone (their G_ii is round-off, even negative). Four cases: standing off the axis
// (0.1 m deep) and lying across it (0.3 m deep), at rest and spinning at 3 rad/s about the hinge
// (the floor cannot push it, so there is no friction either). 2 s each: no failure, finite, the
// energy never above its start by more than 1e-6 J (measured at most 3.5e-10 J), joints within
// 1e-6 m (measured 6e-14 m). Before: every one of them blew up within 3 steps.
TEST(PenetrationRecovery, CylinderSunkOnAVerticalHingeNeverExplodes)
{
    for (const char* spin : {"[0, 0, 0]", "[0, 0, 3]"})
    {
        for (const auto& [position, orientation] :
             {std::pair<const char*, const char*>{"[0.3, 0, 0]", "[1, 0, 0, 0]"},
              std::pair<const char*, const char*>{"[0, 0, 0]", "[0.7071068, 0.7071068, 0, 0]"}})
        {
            SCOPED_TRACE(std::string("wheel at ") + position + " spinning " + spin);
            SceneRun run(
                io::loadSceneFromString(wheelScene(position, orientation, "[0, 0, 1]", spin), "hinge.yaml"));
            const Recovery r = runFor(run, 2.0);
            EXPECT_TRUE(r.finite) << r.failure;
            EXPECT_EQ(r.steps, 2000);
            EXPECT_LE(r.energyMax, r.energyStart + 1e-6);
            EXPECT_LE(r.jointErrorM, 1e-6);
            EXPECT_GT(r.depthStart, 0.09); // it really started sunk
        }
    }
}

// A wheel on a horizontal axle through its rim, sunk 0.1 m: only turning it up by a quarter
// turn (until it stands on the axle) brings its near edge out. Bounds: out within
// (pi / 2) / (w_max dt) + 30 steps (measured 94 of 109), joints within 1e-6 m, no step adds
// more than lifting the wheel by v_max dt (its centre of mass rises at that cap: 2.77 J of
// 2.78 J), kinetic energy under one step's fall (measured 9e-7 J of 2.7e-3 J). Before: 6e9 J.
TEST(PenetrationRecovery, WheelSunkOnAHorizontalAxleTurnsOutBoundedly)
{
    SceneRun run(io::loadSceneFromString(wheelScene("[0.3, 0, 0]", "[1, 0, 0, 0]", "[0, 1, 0]", "[0, 0, 0]"),
                                         "axle.yaml"));
    const Recovery r = runFor(run, 2.0);
    ASSERT_TRUE(r.finite) << r.failure;
    const double dt = run.model.simulation.dt;
    const long quarterTurn =
        static_cast<long>(std::ceil(0.5 * M_PI / (cDefaults.penetrationMaxAngularSpeed * dt)));
    EXPECT_GE(r.outStep, 0);
    EXPECT_LE(r.outStep, quarterTurn + 30);
    EXPECT_LE(r.jointErrorM, 1e-6);
    EXPECT_LE(r.energyStepRise, oneStepLift(run.model));
    EXPECT_LE(r.kineticMax, oneStepFall(run.model));
}

std::string boxScene(const std::string& size, double z, const std::string& orientation)
{
    return R"(
simulation: {dt: 0.001}
contact: {restitution: 1}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}
  - {name: box, shape: {type: box, size: )" +
           size + "}, position: [0.3, -0.2, " + std::to_string(z) + "], orientation: " + orientation + "}\n";
}

// A free box started in the floor: upright 5 cm deep, a 0.2 m cube buried 0.3 m deep (its top
// 0.1 m under the floor), and a 0.4 m cube tilted 0.36 rad with its lowest corner 0.34 m deep.
// Restitution 1: deep overlap must not turn into bounce velocity either. Bounds: out within
// depth / (v_max dt) + 20 steps (measured 10 of 30, 77 of 80, 60 of 98), no step adds more than
// lifting the box by v_max dt (the boxes rise at that cap), kinetic energy under one step's fall
// (measured at most 2.3e-4 J, the buried cube; bound 3.8e-4 J for it, 3.1e-3 J for the larger
// boxes). Before: the buried cube was turned 57 degrees in one step (1.4 J), the tilted box
// tumbled out (5.4 J); the upright box came out well already.
TEST(PenetrationRecovery, FreeBoxInTheFloorComesOutBoundedly)
{
    struct Case
    {
        const char* size;
        double z; // m
        const char* orientation;
    };
    for (const Case& c :
         {Case{"[0.4, 0.4, 0.4]", 0.15, "[1, 0, 0, 0]"}, Case{"[0.2, 0.2, 0.2]", -0.2, "[1, 0, 0, 0]"},
          Case{"[0.4, 0.4, 0.4]", -0.1, "[0.98, 0.1, 0.15, 0]"}})
    {
        SCOPED_TRACE(std::string("box ") + c.size + " at z = " + std::to_string(c.z) + ", " + c.orientation);
        SceneRun run(io::loadSceneFromString(boxScene(c.size, c.z, c.orientation), "box.yaml"));
        const double depth = planePenetration(run.model, run.state);
        const Recovery r = runFor(run, 1.0);
        ASSERT_TRUE(r.finite) << r.failure;
        EXPECT_GE(r.outStep, 0);
        EXPECT_LE(r.outStep, recoverySteps(depth, run.model.simulation.dt));
        EXPECT_LE(planePenetration(run.model, run.state), cOut);
        EXPECT_LE(r.energyStepRise, oneStepLift(run.model));
        EXPECT_LE(r.kineticMax, oneStepFall(run.model));
    }
}

std::string twoBoxScene(const std::string& gravity, const std::string& positionB)
{
    return R"(
simulation: {dt: 0.001, gravity: )" +
           gravity + R"(}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}
  - {name: a, shape: {type: box, size: [0.4, 0.4, 0.4]}, position: [0, 0, 0.2]}
  - {name: b, shape: {type: box, size: [0.4, 0.4, 0.4]}, position: )" +
           positionB + R"(, orientation: [0.96, 0.1, 0.2, 0.15]}
)";
}

// Two 64 kg boxes, b turned and started deep inside a (which stands on the floor): 0.45 m up
// (0.15 m overlap on the centre line, more at b's corners) and 0.22 m up (nearly on top of each
// other, b also in the floor). They separate without flying apart. Without gravity the projection
// never gives them velocity: kinetic energy stays exactly 0. With gravity, b ends on a: kinetic
// energy under one step's fall of both (measured 1.8e-7 J and 1.5e-7 J of 6.3e-3 J), no step
// adds more than lifting both by v_max dt. Both out within depth / (v_max dt) + 20 steps
// (measured 30 of 71 and 79 of 113). Before: 8.3 J and 196 J (b tumbled off a).
TEST(PenetrationRecovery, BoxesStartedInsideEachOtherSeparateWithoutFlyingApart)
{
    for (const char* gravity : {"[0, 0, 0]", "[0, 0, -9.81]"})
    {
        for (const char* positionB : {"[0, 0, 0.45]", "[0.02, 0.01, 0.22]"})
        {
            SCOPED_TRACE(std::string("gravity ") + gravity + ", b at " + positionB);
            SceneRun run(io::loadSceneFromString(twoBoxScene(gravity, positionB), "boxes.yaml"));
            const Recovery r = runFor(run, 1.0);
            ASSERT_TRUE(r.finite) << r.failure;
            EXPECT_GT(r.depthStart, 0.1);
            EXPECT_GE(r.outStep, 0);
            EXPECT_LE(r.outStep, recoverySteps(r.depthStart, run.model.simulation.dt));
            EXPECT_LE(r.energyStepRise, oneStepLift(run.model));
            EXPECT_LE(r.kineticMax,
                      run.model.simulation.gravity.norm() > 0.0 ? oneStepFall(run.model) : 1e-20);
        }
    }
}

constexpr const char* cLimitScene = R"(
simulation: {dt: 0.001}
bodies:
  - {name: rod, shape: {type: box, size: [0.05, 0.05, 1.0]}, position: [0, 0, 1.5]}
joints:
  - {name: hinge, type: revolute, parent: world, child: rod, anchor: [0, 0, 2], axis: [1, 0, 0], limits: [0.5, 1.0]}
)";

// A 1 m, 2.5 kg rod hanging from a hinge whose limits [0.5, 1] rad leave out its start pose (0):
// the limit is 0.5 rad beyond reach of the first step. The rod is turned into its range at
// theta = min(w_max dt, v_max dt / r) a step (r = 0.5 m, its centre of mass from the axis: 0.01
// rad) within 0.5 / theta + 10 steps (measured 50) and stays there (to 1e-3 rad), joints within
// 1e-6 m, kinetic energy under one step's fall (measured 7e-9 J of 1.2e-4 J). Before: 5380 J in
// the first step (the joint correction turned the second-order joint gap of a 0.5 rad turn into
// velocity).
TEST(PenetrationRecovery, JointStartedBeyondItsLimitIsTurnedBackBoundedly)
{
    SceneRun run(io::loadSceneFromString(cLimitScene, "limit.yaml"));
    const double dt = run.model.simulation.dt;
    const double theta =
        std::min(cDefaults.penetrationMaxAngularSpeed * dt, cDefaults.penetrationMaxSpeed * dt / 0.5);
    const long within = static_cast<long>(std::ceil(0.5 / theta)) + 10;
    double kinetic = 0.0, jointError = 0.0, outside = 0.0;
    for (long k = 0; k < run.stepsFor(1.0); ++k)
    {
        ASSERT_NO_THROW(run.step()) << "step " << k;
        ASSERT_TRUE(allFinite(run.state)) << "step " << k;
        kinetic = std::max(kinetic, core::kineticEnergy(run.model, run.state));
        jointError = std::max(jointError, run.simulator.lastStep().maxJointErrorM);
        if (k + 1 >= within)
        {
            const double angle = core::jointCoordinate(run.model, run.state, 0);
            outside = std::max({outside, 0.5 - angle, angle - 1.0});
        }
    }
    std::printf("kinetic max %.3g J, joint gap %.3g m, outside the limits after step %ld: %.3g rad\n",
                kinetic, jointError, within, outside);
    EXPECT_LE(outside, 1e-3);
    EXPECT_LE(jointError, 1e-6);
    EXPECT_LE(kinetic, oneStepFall(run.model));
}

// The messages. A run that fails while the scene's deep start overlap is still there (the sunk
// hinge: nothing lifts it) names the overlap it started with, the bodies and the depth, and says a
// smaller time step does not help, instead of advising one. The failure is made by hand: after
// the first step (which records how the scene started) the wheel is spun about its hinge beyond
// the runaway bound (1e6 rad/s), which the next step's check stops.
TEST(PenetrationRecovery, FailureWithDeepInitialOverlapNamesBodiesAndDepth)
{
    SceneRun run(io::loadSceneFromString(wheelScene("[0.3, 0, 0]", "[1, 0, 0, 0]", "[0, 0, 1]", "[0, 0, 0]"),
                                         "hinge.yaml"));
    std::string message;
    try
    {
        run.step();
        core::BodyState& wheel = run.state.bodies[static_cast<std::size_t>(run.model.findBody("wheel"))];
        wheel.angularVelocity_W = Vec3(0.0, 0.0, 2e6);                                     // rad/s
        wheel.velocity_W = wheel.angularVelocity_W.cross(wheel.position_W - Vec3::Zero()); // on the hinge
        run.step();
    }
    catch (const core::SimulationError& e)
    {
        message = e.what();
    }
    std::printf("%s\n", message.c_str());
    ASSERT_FALSE(message.empty()) << "no failure";
    EXPECT_NE(message.find("starts with 'wheel' 0.1 m deep in 'floor'"), std::string::npos) << message;
    EXPECT_NE(message.find("does not help"), std::string::npos) << message;
    EXPECT_EQ(message.find("try a smaller --dt"), std::string::npos) << message;
}

// A limit beyond reach: the hint names the joint, where it starts and its limits (the rod above
// at its start, as the first step sees it); only fast rotation in the failing step advises a
// smaller step.
TEST(PenetrationRecovery, HintNamesTheJointStartedBeyondItsLimit)
{
    const core::Model model = io::loadSceneFromString(cLimitScene, "limit.yaml");
    const core::State state = core::initialState(model);
    std::vector<core::ExtraBlock> blocks;
    core::appendLimitBlocks(model, state, 0, cDefaults.limitMargin, blocks);
    const core::StartDefects start = core::findStartDefects({}, blocks, model, state);
    const std::string hint = core::failureHint(model, start, true, 0.0, -1);
    std::printf("%s\n", hint.c_str());
    EXPECT_NE(hint.find("joint 'hinge' starts at 0 rad, 0.5 rad beyond its limits [0.5, 1] rad"),
              std::string::npos)
        << hint;
    EXPECT_EQ(hint.find("try a smaller --dt"), std::string::npos) << hint;
    // Long after the start (no longer recovering) and turning 0.3 rad a step: the step is the cause.
    const std::string fast = core::failureHint(model, start, false, 0.3, 0);
    EXPECT_NE(fast.find("body 'rod' turned 0.3 rad in one step: try a smaller --dt"), std::string::npos)
        << fast;
    EXPECT_EQ(core::failureHint(model, start, false, 0.01, 0), "");
}

} // namespace
} // namespace frontier::test
