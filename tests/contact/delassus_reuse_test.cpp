// tests/contact/delassus_reuse_test.cpp: resting contact solved with a recent step's Delassus
// matrix (core::ContactProblem, StepOptions::reuseDelassus) against the same
// scenes with this step's matrix built every time. The route must be taken (most resting steps),
// and it must not change the physics: the same rest poses to well under the contact tolerance's
// reach, bodies at rest, no energy gained.
#include "contact_harness.h"

#include <array>
#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

struct RouteRun
{
    std::array<long, core::cContactRoutes> routes{}; // steps by core::ContactRoute
    double maxEnergyRise = 0.0;                      // J above the scene's start
    double endSpeed = 0.0;                           // largest point speed at the end (m/s)
    std::vector<Vec3> positions;                     // centres at the end (m)
};

// `seconds` of the scene from its start, or from `from` (a state of the same scene).
RouteRun runWith(const std::string& scene, double seconds, bool reuse, const core::State* from = nullptr)
{
    core::StepOptions options;
    options.reuseDelassus = reuse;
    SceneRun run(io::loadScene(scenePath(scene)), options);
    RouteRun r;
    const double start = core::totalEnergy(run.model, run.state); // the scene's start
    if (from != nullptr)
    {
        run.state = *from;
    }
    for (long k = 0; k < run.stepsFor(seconds); ++k)
    {
        run.step();
        ++r.routes[core::routeIndex(run.simulator.lastStep().contactRoute)];
        r.maxEnergyRise = std::max(r.maxEnergyRise, core::totalEnergy(run.model, run.state) - start);
    }
    r.endSpeed = maxPointSpeed(run.model, run.state);
    for (const core::BodyState& b : run.state.bodies)
    {
        r.positions.push_back(b.position_W);
    }
    return r;
}

void print(const char* label, const RouteRun& r)
{
    std::printf("%s: steps without contact %ld, carried %ld, reused %ld, built %ld; end speed %.3g m/s, "
                "energy rise %.3g J\n",
                label, r.routes[0], r.routes[1], r.routes[2], r.routes[3], r.endSpeed, r.maxEnergyRise);
}

double largestDistance(const RouteRun& a, const RouteRun& b)
{
    double d = 0.0;
    for (std::size_t i = 0; i < a.positions.size(); ++i)
    {
        d = std::max(d, (a.positions[i] - b.positions[i]).norm());
    }
    return d;
}

// Five boxes standing 2 s, once they have landed on each other (1 s, the matrix built every step:
// the landing is a chain of small impacts, where two valid solves part ways): with reuse, most
// steps that cannot keep the last impulses take the reused route (none without); both runs end at
// rest with the same poses within 0.1 mm (the contact conditions hold to 3e-5 m/s, so two valid
// solves can move a body by at most about that times 2 s = 6e-5 m).
TEST(DelassusReuse, BoxStackRestsAsWithTheMatrixBuiltEveryStep)
{
    core::State landed;
    {
        SceneRun landing(io::loadScene(scenePath("box_stack.yaml")),
                         []
                         {
                             core::StepOptions options;
                             options.reuseDelassus = false;
                             return options;
                         }());
        for (long k = 0; k < landing.stepsFor(1.0); ++k)
        {
            landing.step();
        }
        landed = landing.state;
    }
    const RouteRun reused = runWith("box_stack.yaml", 2.0, true, &landed);
    const RouteRun built = runWith("box_stack.yaml", 2.0, false, &landed);
    print("box stack, reuse", reused);
    print("box stack, built every step", built);
    EXPECT_EQ(built.routes[core::routeIndex(core::ContactRoute::Reused)], 0);
    // Of the steps whose carried-over impulses miss, most are finished on the reused matrix.
    EXPECT_GT(reused.routes[core::routeIndex(core::ContactRoute::Reused)],
              3 * reused.routes[core::routeIndex(core::ContactRoute::Built)]);
    EXPECT_LT(reused.routes[core::routeIndex(core::ContactRoute::Built)],
              built.routes[core::routeIndex(core::ContactRoute::Built)] / 4);
    EXPECT_LT(largestDistance(reused, built), 1e-4);
    EXPECT_LT(reused.endSpeed, 1e-3);
    EXPECT_LT(built.endSpeed, 1e-3);
    EXPECT_LE(reused.maxEnergyRise, 0.0);
}

// The falling doll, 3 s: it lands chaotically, so poses are not compared; with reuse it comes to
// rest like the always-built run (every point under 1e-2 m/s), never gains energy, and builds the
// matrix on far fewer steps.
TEST(DelassusReuse, FallingDollComesToRestAsWithTheMatrixBuiltEveryStep)
{
    const RouteRun reused = runWith("falling_doll.yaml", 3.0, true);
    const RouteRun built = runWith("falling_doll.yaml", 3.0, false);
    print("falling doll, reuse", reused);
    print("falling doll, built every step", built);
    EXPECT_LT(reused.endSpeed, 1e-2);
    EXPECT_LT(built.endSpeed, 1e-2);
    EXPECT_LE(reused.maxEnergyRise, 0.0);
    EXPECT_LT(2 * reused.routes[core::routeIndex(core::ContactRoute::Built)],
              built.routes[core::routeIndex(core::ContactRoute::Built)]);
}

// Joint limits and loops carry their impulses to the next step (by joint, a limit on the same
// side) like contacts do, and take part in the reuse. scenes/limits.yaml (a limited pendulum and
// slider, no contacts, each its own island): with its limit rows active the carried impulses hold
// on a third of the steps or more (without the carry, none could: a pushing limit started from
// zero), and those that miss are finished on a kept matrix, almost never built. The pendulum
// resting on its limit settles into a cycle of three steps at the velocity tolerance's edge:
// carried within it (2.97e-5 rad/s), solved, solved; the slider's impulse holds on every step.
// scenes/doll_urdf_scene.yaml (two URDF dolls whose joints have limits, falling onto the floor and each
// other): both routes taken, the matrix built on under 3/4 of the steps it takes when built every time
// (measured 1 054 against 1 895 in 2 s: the dolls are still moving), no energy gained either way.
TEST(DelassusReuse, LimitImpulsesAreCarriedAndReused)
{
    const RouteRun limits = runWith("limits.yaml", 3.0, true);
    print("limits, reuse", limits);
    const long withRows = limits.routes[core::routeIndex(core::ContactRoute::Carried)] +
                          limits.routes[core::routeIndex(core::ContactRoute::Reused)] +
                          limits.routes[core::routeIndex(core::ContactRoute::Built)];
    EXPECT_GT(withRows, 0);
    EXPECT_GT(3 * limits.routes[core::routeIndex(core::ContactRoute::Carried)], withRows);
    EXPECT_LT(20 * limits.routes[core::routeIndex(core::ContactRoute::Built)], withRows);

    const RouteRun reused = runWith("doll_urdf_scene.yaml", 2.0, true);
    const RouteRun built = runWith("doll_urdf_scene.yaml", 2.0, false);
    print("URDF dolls, reuse", reused);
    print("URDF dolls, built every step", built);
    EXPECT_GT(reused.routes[core::routeIndex(core::ContactRoute::Carried)], 0);
    EXPECT_GT(reused.routes[core::routeIndex(core::ContactRoute::Reused)], 0);
    EXPECT_LT(4 * reused.routes[core::routeIndex(core::ContactRoute::Built)],
              3 * built.routes[core::routeIndex(core::ContactRoute::Built)]);
    EXPECT_LE(reused.maxEnergyRise, 0.0);
    EXPECT_LE(built.maxEnergyRise, 0.0);
}

} // namespace
} // namespace frontier::test
