// tests/contact/bouncing_ball_test.cpp: scenes/bouncing_ball.yaml, restitution 0.8 on a plane.
#include "contact_harness.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

namespace frontier::test
{
namespace
{

// Every bounce faster than the restitution threshold (0.1 m/s) leaves with e times the impact
// speed, so an apex height is e^2 times the one before (no air drag). The measured apex is the
// highest bottom-of-ball height of each flight. Error budget per apex (dt = 1 ms): the impact is
// resolved where the contact is first seen, up to v dt (4.4 mm at 4.4 m/s) above the floor, and
// symplectic Euler shifts an apex by O(g dt^2) per step; both are under 1% of the heights of the
// first five bounces (1 m down to 0.64^5 = 0.107 m), so the ratios hold within 2%.
// Both integrators: rattle resolves the impact in its first stage (first order across it) and
// flies second order in between.
void checkApexRatios(core::IntegratorKind integrator)
{
    core::Model model = io::loadScene(scenePath("bouncing_ball.yaml"));
    model.simulation.integrator = integrator;
    SceneRun run(std::move(model));
    const double e = run.model.contact.restitution;
    ASSERT_EQ(e, 0.8);
    const double radius =
        run.model.bodies[static_cast<std::size_t>(run.model.findBody("ball"))].shapes[0].radius;
    std::vector<double> apex{run.body("ball").position_W.z() - radius}; // released from rest
    double highest = -1.0;
    bool rising = false;
    const long steps = run.stepsFor(5.0);
    for (long k = 0; k < steps && apex.size() < 8; ++k)
    {
        const double vzBefore = run.body("ball").velocity_W.z();
        run.step();
        const core::BodyState& ball = run.body("ball");
        ASSERT_TRUE(ball.position_W.allFinite());
        // The ball never goes through the floor (beyond the 0.5 mm slop plus round-off).
        ASSERT_GT(ball.position_W.z() - radius, -5e-4 - 1e-9) << "step " << k;
        if (ball.velocity_W.z() > 0.0 && vzBefore <= 0.0)
        {
            rising = true;
            highest = -1.0;
        }
        if (rising)
        {
            highest = std::max(highest, ball.position_W.z() - radius);
            if (ball.velocity_W.z() <= 0.0)
            {
                apex.push_back(highest);
                rising = false;
            }
        }
    }
    ASSERT_GE(apex.size(), 6u) << "fewer than five bounces seen";
    for (std::size_t k = 1; k < 6; ++k)
    {
        const double ratio = apex[k] / apex[k - 1];
        std::printf("apex %zu: %.5f m, ratio to the one before %.5f (e^2 = %.5f)\n", k, apex[k], ratio,
                    e * e);
        // The impact that starts this flight (speed sqrt(2 g h) from the apex before) is above
        // the restitution threshold, so restitution applies to it.
        ASSERT_GT(std::sqrt(2.0 * 9.81 * apex[k - 1]), 0.1);
        EXPECT_NEAR(ratio, e * e, 0.02 * e * e) << "bounce " << k;
    }
}

TEST(BouncingBall, ApexHeightsFallByRestitutionSquared)
{
    checkApexRatios(core::IntegratorKind::Euler);
}

TEST(BouncingBall, ApexHeightsFallByRestitutionSquaredWithRattle)
{
    checkApexRatios(core::IntegratorKind::Rattle);
}

} // namespace
} // namespace frontier::test
