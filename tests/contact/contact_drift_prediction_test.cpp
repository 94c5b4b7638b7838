// tests/contact/contact_drift_prediction_test.cpp: on steps with contacts the predicted drift
// (docs/method.md §7, eq. (11a)) is solved on its own after the contact impulses, so that they do
// not see it. It then moves only the drift correction's starting point: the falling doll lands
// the same with and without it, and its contact steps need fewer projection iterations with it.
#include "contact_harness.h"

#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

struct LandingRun
{
    core::State state;
    double maxJointErrorM = 0.0;
    long contactSteps = 0;        // steps that had contacts
    long contactIterations = 0;   // projection iterations on those steps
    double maxPenetrationM = 0.0; // from the geometry, after every step
};

LandingRun land(bool predict, double seconds)
{
    core::StepOptions options;
    options.predictDrift = predict;
    SceneRun run(io::loadScene(scenePath("falling_doll.yaml")), options);
    LandingRun r;
    const long steps = run.stepsFor(seconds);
    for (long k = 0; k < steps; ++k)
    {
        run.step();
        const core::StepStats& st = run.simulator.lastStep();
        r.maxJointErrorM = std::max(r.maxJointErrorM, st.maxJointErrorM);
        r.maxPenetrationM = std::max(r.maxPenetrationM, planePenetration(run.model, run.state));
        if (st.contacts > 0)
        {
            ++r.contactSteps;
            r.contactIterations += st.stabilizationIterations;
        }
    }
    r.state = run.state;
    return r;
}

TEST(ContactDriftPrediction, SameLandingWithFewerProjectionIterations)
{
    // 0.45 s: the doll has been on the floor for a while, before the contact solver's tolerance
    // (3e-5 m/s) lets the two runs' tumbling drift apart.
    const LandingRun plain = land(false, 0.45);
    const LandingRun predicted = land(true, 0.45);
    ASSERT_GT(plain.contactSteps, 50);
    ASSERT_EQ(plain.contactSteps, predicted.contactSteps);
    const core::StepOptions options;
    EXPECT_LE(predicted.maxJointErrorM, 10.0 * options.stabilizationTolerance);
    EXPECT_NEAR(predicted.maxPenetrationM, plain.maxPenetrationM, 1e-6);
    double positionM = 0.0;
    double speed = 0.0; // m/s
    for (std::size_t i = 0; i < plain.state.bodies.size(); ++i)
    {
        positionM = std::max(
            positionM, (plain.state.bodies[i].position_W - predicted.state.bodies[i].position_W).norm());
        speed =
            std::max(speed, (plain.state.bodies[i].velocity_W - predicted.state.bodies[i].velocity_W).norm());
    }
    std::printf("contact steps %ld: projection iterations %ld without the prediction, %ld with; bodies apart "
                "by %.3g m, %.3g m/s\n",
                plain.contactSteps, plain.contactIterations, predicted.contactIterations, positionM, speed);
    // A contact that saw the prediction's velocity (about D / h: 0.1-0.6 m/s on this doll's joints)
    // would move the bodies by millimetres.
    EXPECT_LT(positionM, 1e-6);
    EXPECT_LT(speed, 1e-4);
    EXPECT_LT(static_cast<double>(predicted.contactIterations),
              0.9 * static_cast<double>(plain.contactIterations));
}

} // namespace
} // namespace frontier::test
