// tests/app/sweep_test.cpp: the sweep's list parsing, sample schedule and Pareto front, in-process.
#include "app_test_util.h"
#include "io/scene.h"
#include "study/sweep.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>

namespace frontier::study
{
namespace
{

TEST(Sweep, DefaultTimeStepsHalveDownToTheScenesAndShareTwentySampleTimes)
{
    const std::vector<double> dts = defaultTimeSteps(0.001);
    ASSERT_EQ(dts, (std::vector<double>{0.016, 0.008, 0.004, 0.002, 0.001}));
    const SweepSchedule schedule = planSchedule(dts, 2.0);
    EXPECT_EQ(schedule.unitS, 0.016);
    EXPECT_EQ(schedule.units, 125);
    ASSERT_EQ(schedule.sampleUnits.size(), static_cast<std::size_t>(cSampleCount));
    EXPECT_EQ(schedule.sampleUnits.back(), 125);
    for (std::size_t i = 1; i < schedule.sampleUnits.size(); ++i)
    {
        EXPECT_LT(schedule.sampleUnits[i - 1], schedule.sampleUnits[i]);
    }
}

TEST(Sweep, ScheduleFindsACommonMultipleAndRoundsTheDurationDown)
{
    // 3 ms and 2 ms meet every 6 ms; 0.1 s holds 16 of those (0.096 s), so 16 sample times.
    const SweepSchedule schedule = planSchedule(parseTimeSteps({"0.002", "0.003"}), 0.1);
    EXPECT_NEAR(schedule.unitS, 0.006, 1e-15);
    EXPECT_EQ(schedule.units, 16);
    EXPECT_EQ(schedule.sampleUnits.size(), 16u);
    EXPECT_NEAR(schedule.durationS(), 0.096, 1e-12);
    // Shorter than the common multiple: bad input naming --duration.
    try
    {
        planSchedule({0.004}, 0.001);
        FAIL() << "expected SweepInputError";
    }
    catch (const SweepInputError& e)
    {
        EXPECT_NE(std::string(e.what()).find("--duration"), std::string::npos) << e.what();
    }
}

TEST(Sweep, ListsParseSortAndDeduplicate)
{
    EXPECT_EQ(parseTimeSteps({"0.001", " 0.004", "0.002", "0.004"}),
              (std::vector<double>{0.004, 0.002, 0.001}));
    const std::vector<run::Method> solvers = parseSolvers({"linear", "pgs:10", "pgs", "dense", "pgs:20"}, 20);
    ASSERT_EQ(solvers.size(), 4u); // pgs and pgs:20 are the same with the scene's 20 sweeps
    EXPECT_EQ(solvers[1].solver, core::SolverKind::Pgs);
    EXPECT_EQ(solvers[1].pgsIterations, 10);
    EXPECT_EQ(solvers[2].pgsIterations, 20);
    EXPECT_EQ(solvers[3].solver, core::SolverKind::Dense);
    EXPECT_EQ(parseIntegrators({"rattle", "euler"}),
              (std::vector<core::IntegratorKind>{core::IntegratorKind::Rattle, core::IntegratorKind::Euler}));
    EXPECT_EQ(parseIntegrators({"rattle4"}),
              (std::vector<core::IntegratorKind>{core::IntegratorKind::Rattle4}));
    EXPECT_THROW(parseTimeSteps({"1e-3", "nan"}), SweepInputError);
    EXPECT_THROW(parseTimeSteps({"inf"}), SweepInputError);
    EXPECT_THROW(parseSolvers({"pgs:"}, 20), SweepInputError);
    EXPECT_THROW(parseSolvers({"pgs:3x"}, 20), SweepInputError);
    EXPECT_THROW(parseSolvers({"pgs:3/euler"}, 20), SweepInputError); // --integrator names those
    EXPECT_THROW(parseIntegrators({"Euler"}), SweepInputError);
}

SweepCell cell(double cost, double error, bool survived = true)
{
    SweepCell c;
    c.secondsPerSimSecond = cost;
    c.trajectoryErrorM = error;
    c.survived = survived;
    return c;
}

TEST(Sweep, ParetoFrontKeepsOnlyCellsNoOtherBeatsInBoth)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<SweepCell> cells = {
        cell(1.0, 1.0),        // 0: front (cheapest)
        cell(2.0, 0.5),        // 1: front
        cell(3.0, 0.6),        // 2: dominated by 1
        cell(2.0, 0.7),        // 3: same cost as 1, worse
        cell(4.0, 0.1),        // 4: front
        cell(0.5, nan, false), // 5: failed
        cell(5.0, 0.1),        // 6: as accurate as 4 but dearer
    };
    EXPECT_EQ(paretoFront(cells), (std::vector<std::size_t>{0, 1, 4}));
}

// A box falling freely from (0, 0, 5) m at (1, 0, 2) m/s: the closed form x0 + v0 t + g t^2 / 2.
const char* cFallingBox = "name: falling box\nsimulation: {dt: 0.01, duration: 1.0, gravity: [0, 0, -9.81]}\n"
                          "bodies:\n  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.1]}, mass: 1.0,\n"
                          "     position: [0, 0, 5], velocity: [1, 0, 2]}\n";

core::Vec3 fallingBox(double t)
{
    return core::Vec3(0, 0, 5) + t * core::Vec3(1, 0, 2) + 0.5 * t * t * core::Vec3(0, 0, -9.81);
}

// Against a reference no method made, the errors are the methods' own: euler's
// x_n = x(t_n) + g h t_n / 2 exactly, so |g| h T / 2 at the end; rattle integrates a parabola
// exactly. From a closed form and from a CSV of it every 0.1 s (its cubic is the parabola).
TEST(Sweep, ExternalReferenceMeasuresTheMethodsOwnError)
{
    const core::Model model = io::loadSceneFromString(cFallingBox, "falling_box.yaml");
    const SweepGrid grid = makeSweepGrid(model, {"0.01", "0.005"}, {}, {"euler", "rattle", "rattle4"});
    const SweepSchedule schedule = planSchedule(grid.dts, 1.0);
    app::test::TestDir dir;
    std::string csv = "t,x,y,z\n";
    for (int k = 0; k <= 10; ++k)
    {
        const core::Vec3 p = fallingBox(0.1 * k);
        char row[128];
        std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g\n", 0.1 * k, p.x(), p.y(), p.z());
        csv += row;
    }
    const ExternalReference closed{"box", "closed form", fallingBox};
    const ExternalReference sampled = readReferenceCsv(dir.write("box.csv", csv), "box");
    for (const ExternalReference* reference : {&closed, &sampled})
    {
        const SweepResult result = runSweep(model, grid, schedule, {}, reference);
        EXPECT_EQ(result.reference.external, reference->source);
        ASSERT_EQ(result.cells.size(), 6u);
        for (const SweepCell& cell : result.cells)
        {
            ASSERT_TRUE(cell.survived) << cell.failure;
            const double expected =
                cell.method.integrator == core::IntegratorKind::Euler ? 0.5 * 9.81 * cell.dt * 1.0 : 0.0;
            EXPECT_NEAR(cell.trajectoryErrorM, expected, 1e-11) << cell.method.label() << " dt " << cell.dt;
        }
    }
    const ExternalReference unknown{"lid", "closed form", fallingBox};
    EXPECT_THROW(runSweep(model, grid, schedule, {}, &unknown), SweepInputError);
    EXPECT_THROW(readReferenceCsv(dir.write("bad.csv", "t,x,y,z\n0,1,2,3\n0.1,1,2\n"), "box"),
                 SweepInputError);
    EXPECT_THROW(readReferenceCsv(dir.write("short.csv", "0,1,2,3\n0.1,1,2,3\n"), "box"), SweepInputError);
}

} // namespace
} // namespace frontier::study
