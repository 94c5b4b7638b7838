// tests/contact/cradle_test.cpp: scenes/newtons_cradle.yaml, five equal steel pendulums in a row,
// restitution 1, frictionless; ball 0 swings into the row at v0 = 0.887 m/s.
//
// What the contact pipeline does with it: the balls touch exactly (centres 2 r apart), and the
// detector reports touching spheres as contacts of depth 0 (sphere pairs are computed in closed
// form, collision/swept_spheres.cpp), so at the impact step the solver sees all four contacts
// 0-1, 1-2, 2-3, 3-4 and solves them simultaneously, as designed: contact 0-1 separates at e v0
// (restitution), 1-2, 2-3, 3-4 arrive with no approach speed so they only must not close (target
// 0). The unique solution of that complementarity problem for equal masses: balls 1-4 leave
// together at 2/5 v0 and ball 0 rebounds at -3/5 v0 (momentum -3/5 + 4 * 2/5 = 1, energy 9/25 +
// 4 * 4/25 = 1: both conserved; impulses 8/5, 6/5, 4/5, 2/5 m v0, all pushing). The momentum
// spreads over four balls instead of only the last one leaving (the classic cradle needs the
// sequential model: simultaneous impulse methods are known to differ here). A row preloaded by
// 10 um per pair (below the 0.5 mm slop, so nothing is pushed apart at rest) does the same.
// (Before the closed form, FCL reported touching spheres neither as overlapping nor as a gap, so
// the impulse hopped one ball per step and the last ball left with v0.)

#include "contact_harness.h"

#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::test
{
namespace
{

// The scene with balls 1..4 and their pivots moved towards ball 0 by k * preload (m).
std::string cradleText(double preload)
{
    std::ifstream file(scenePath("newtons_cradle.yaml"));
    std::stringstream buffer;
    buffer << file.rdbuf();
    std::string text = buffer.str();
    EXPECT_FALSE(text.empty());
    if (preload == 0.0)
    {
        return text;
    }
    const double x[4] = {-0.05, 0.0, 0.05, 0.1};
    const char* names[4] = {"-0.05", "0", "0.05", "0.1"};
    for (int k = 0; k < 4; ++k)
    {
        char moved[64];
        std::snprintf(moved, sizeof moved, "%.17g", x[k] - (k + 1) * preload);
        for (const char* z : {", 0, 0.2]", ", 0, 0.5]"})
        {
            const std::string from = std::string("[") + names[k] + z;
            const std::size_t at = text.find(from);
            EXPECT_NE(at, std::string::npos) << from;
            if (at != std::string::npos)
            {
                text.replace(at, from.size(), std::string("[") + moved + z);
            }
        }
    }
    return text;
}

struct Impact
{
    double v0 = 0.0;        // ball 0's x velocity at the step before the first contact (m/s)
    std::vector<double> vx; // x velocities after the impact (m/s)
    int contactsAtImpact = 0;
    double momentumBefore = 0.0, momentumAfter = 0.0; // sum m vx (kg m/s)
    double kineticBefore = 0.0, kineticAfter = 0.0;   // J
};

double kinetic(const core::Model& model, const core::State& state)
{
    double ke = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const core::BodyState& s = state.bodies[i];
        ke += 0.5 * model.bodies[i].mass * s.velocity_W.squaredNorm() +
              0.5 * s.angularVelocity_W.dot(core::worldInertia(model.bodies[i], s) * s.angularVelocity_W);
    }
    return ke;
}

double momentumX(const core::Model& model, const core::State& state)
{
    double p = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        p += model.bodies[i].mass * state.bodies[i].velocity_W.x();
    }
    return p;
}

// Steps until ball 0 first touches ball 1, then `after` more steps (the impact included).
Impact runImpact(const std::string& text, int after)
{
    SceneRun run(io::loadSceneFromString(text, scenePath("newtons_cradle.yaml")));
    Impact out;
    const long steps = run.stepsFor(0.5);
    for (long k = 0; k < steps; ++k)
    {
        const core::State before = run.state;
        run.step();
        const bool hit = std::abs(run.state.bodies[1].velocity_W.x()) > 0.1;
        if (hit)
        {
            out.v0 = before.bodies[0].velocity_W.x();
            out.contactsAtImpact = run.simulator.lastStep().contacts;
            out.momentumBefore = momentumX(run.model, before);
            out.kineticBefore = kinetic(run.model, before);
            for (int s = 1; s < after; ++s)
            {
                run.step();
            }
            out.momentumAfter = momentumX(run.model, run.state);
            out.kineticAfter = kinetic(run.model, run.state);
            for (int i = 0; i < 5; ++i)
            {
                out.vx.push_back(run.state.bodies[static_cast<std::size_t>(i)].velocity_W.x());
            }
            break;
        }
    }
    std::printf("contacts at the impact step %d, v0 %.5f m/s, after %d step(s):", out.contactsAtImpact,
                out.v0, after);
    for (double v : out.vx)
    {
        std::printf(" %.5f", v / out.v0);
    }
    std::printf(" (x v0); momentum %.6f -> %.6f, kinetic energy %.6f -> %.6f J\n", out.momentumBefore,
                out.momentumAfter, out.kineticBefore, out.kineticAfter);
    return out;
}

// The scene as written (exact touching) and the preloaded row: all four contacts in one solve.
// Bounds after the impact step: ball 0 at -3/5 v0 and balls 1-4 at 2/5 v0, each within 1e-3 v0;
// momentum and kinetic energy across the step within 1e-3 (the contact problem is solved to
// 3e-5 m/s, the normals tilt by under 1e-5 rad).
void expectSimultaneousSpread(const Impact& r)
{
    ASSERT_EQ(r.vx.size(), 5u);
    EXPECT_EQ(r.contactsAtImpact, 4);
    EXPECT_NEAR(r.v0, 0.887, 0.01);
    EXPECT_NEAR(r.vx[0], -0.6 * r.v0, 1e-3 * r.v0);
    for (int i = 1; i < 5; ++i)
    {
        EXPECT_NEAR(r.vx[static_cast<std::size_t>(i)], 0.4 * r.v0, 1e-3 * r.v0) << "ball " << i;
    }
    EXPECT_NEAR(r.momentumAfter, r.momentumBefore, 1e-3 * r.momentumBefore);
    EXPECT_NEAR(r.kineticAfter, r.kineticBefore, 1e-3 * r.kineticBefore);
}

TEST(NewtonsCradle, TouchingRowIsSolvedSimultaneously)
{
    expectSimultaneousSpread(runImpact(cradleText(0.0), 1));
}

TEST(NewtonsCradle, PreloadedRowSolvedSimultaneouslySpreadsTheMomentum)
{
    expectSimultaneousSpread(runImpact(cradleText(1e-5), 1));
}

} // namespace
} // namespace frontier::test
