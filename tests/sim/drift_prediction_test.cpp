// tests/sim/drift_prediction_test.cpp: the predicted drift (docs/method.md §7, eq. (11a)) moves the
// drift correction's starting point, not the point it converges to: the swinging chain30 with and
// without it stays together to the projection's tolerance, agrees to far below a link's size, and
// needs half the projection iterations with it.
#include "sim_test_util.h"

#include <cstddef>
#include <cstdio>

namespace frontier::sim::test
{
namespace
{

struct ChainRun
{
    core::State state;
    double maxGapM = 0.0; // m, largest joint position error after any step
    long iterations = 0;  // projection iterations over the run
};

ChainRun runChain(bool predict, int steps)
{
    const core::Model model = loadBundled("chain30.yaml");
    core::StepOptions options;
    options.predictDrift = predict;
    core::Simulator simulator(model, options, nullptr);
    ChainRun run;
    run.state = core::initialState(model);
    for (int i = 0; i < steps; ++i)
    {
        simulator.step(run.state);
        run.maxGapM = std::max(run.maxGapM, simulator.lastStep().maxJointErrorM);
        run.iterations += simulator.lastStep().stabilizationIterations;
    }
    return run;
}

TEST(DriftPrediction, SameStepResultWithFewerProjectionIterations)
{
    constexpr int cSteps = 500; // 0.5 s at the scene's 1 ms: the chain swings down through its lowest point
    const ChainRun plain = runChain(false, cSteps);
    const ChainRun predicted = runChain(true, cSteps);
    const core::StepOptions options;
    EXPECT_LE(plain.maxGapM, options.stabilizationTolerance);
    EXPECT_LE(predicted.maxGapM, options.stabilizationTolerance);
    double largestDifferenceM = 0.0;
    double largestSpeedDifference = 0.0; // m/s
    for (std::size_t i = 0; i < plain.state.bodies.size(); ++i)
    {
        largestDifferenceM =
            std::max(largestDifferenceM,
                     (plain.state.bodies[i].position_W - predicted.state.bodies[i].position_W).norm());
        largestSpeedDifference =
            std::max(largestSpeedDifference,
                     (plain.state.bodies[i].velocity_W - predicted.state.bodies[i].velocity_W).norm());
    }
    // The two runs differ step by step by at most the tolerance (positions) and the tolerance over
    // h (velocities). Measured after 500 steps: 1.8e-10 m and 3.9e-8 m/s.
    EXPECT_LT(largestDifferenceM, 1e-8) << "speeds differ by " << largestSpeedDifference << " m/s";
    EXPECT_LT(largestSpeedDifference, 1e-6);
    // Measured: 1 041 projection iterations without (2.1 a step), 533 with (1.07 a step); 654 when
    // the prediction was the last drift alone, not extrapolated from the last two (eq. (11a)).
    // Joints under no large tension keep their prediction through misses of 4-15% a step
    // (core/step/drift_correction.cpp); starting them over every other step took 814.
    EXPECT_LT(static_cast<double>(predicted.iterations), 0.6 * static_cast<double>(plain.iterations))
        << predicted.iterations << " vs " << plain.iterations;
    std::printf(
        "chain30: %ld projection iterations without the prediction, %ld with; apart by %.3g m, %.3g m/s\n",
        plain.iterations, predicted.iterations, largestDifferenceM, largestSpeedDifference);
}

} // namespace
} // namespace frontier::sim::test
