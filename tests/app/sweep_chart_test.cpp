// tests/app/sweep_chart_test.cpp: the sweep chart's gnuplot script (title, ticks, legend, dt
// labels) and the rule that tells a chaotic sweep, on synthetic results.
#include "app/sweep_chart.h"

#include <cmath>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::app
{
namespace
{

run::Method method(core::IntegratorKind integrator, core::SolverKind solver)
{
    run::Method m;
    m.integrator = integrator;
    m.solver = solver;
    return m;
}

const run::Method cEulerLinear = method(core::IntegratorKind::Euler, core::SolverKind::Linear);
const run::Method cRattleLinear = method(core::IntegratorKind::Rattle, core::SolverKind::Linear);
const run::Method cEulerPgs = method(core::IntegratorKind::Euler, core::SolverKind::Pgs);
const run::Method cRattlePgs = method(core::IntegratorKind::Rattle, core::SolverKind::Pgs);

SweepCell cell(const run::Method& m, double dt, double costS, double errorM)
{
    SweepCell c;
    c.method = m;
    c.dt = dt;
    c.survived = true;
    c.secondsPerSimSecond = costS;
    c.trajectoryErrorM = errorM;
    return c;
}

// A method of order `order`: error errorAtCoarsest * (dt / 2 ms)^order, cost 1/dt times costPerStep.
void addConverging(std::vector<SweepCell>& cells, const run::Method& m, double order, double errorAtCoarsest,
                   double costPerStep)
{
    for (double dt : {0.002, 0.001, 0.0005, 0.00025})
    {
        cells.push_back(cell(m, dt, costPerStep / dt, errorAtCoarsest * std::pow(dt / 0.002, order)));
    }
}

// The pileup's measured errors (m) at dt 2, 1 and 0.5 ms: they wander, or barely fall.
void addPileupLike(std::vector<SweepCell>& cells)
{
    const double dts[] = {0.002, 0.001, 0.0005};
    const double euler[] = {0.145, 0.0695, 0.0753};
    const double rattle[] = {0.099, 0.0789, 0.0985};
    const double rattlePgs[] = {0.172, 0.0600, 0.0593}; // falls, but by 1 % at the last halving
    for (int i = 0; i < 3; ++i)
    {
        cells.push_back(cell(cEulerLinear, dts[i], 0.0003 / dts[i], euler[i]));
        cells.push_back(cell(cRattleLinear, dts[i], 0.0004 / dts[i], rattle[i]));
        cells.push_back(cell(cRattlePgs, dts[i], 0.006 / dts[i], rattlePgs[i]));
    }
}

SweepResult resultOf(std::vector<SweepCell> cells)
{
    SweepResult r;
    r.cells = std::move(cells);
    r.reference.method = cRattleLinear;
    r.reference.dt = 6.25e-5;
    r.schedule.unitS = 0.002;
    r.schedule.units = 500;
    for (long k = 25; k <= 500; k += 25)
    {
        r.schedule.sampleUnits.push_back(k);
    }
    return r;
}

TEST(SweepChart, ConvergingMethodsRankAndWanderingOnesDoNot)
{
    std::vector<SweepCell> converging;
    addConverging(converging, cEulerLinear, 1.0, 0.01, 3e-5);
    addConverging(converging, cRattleLinear, 2.0, 0.003, 5e-5);
    EXPECT_FALSE(errorRanksNothing(converging));

    std::vector<SweepCell> pileup;
    addPileupLike(pileup);
    EXPECT_TRUE(errorRanksNothing(pileup));

    // One converging method is enough for the chart to rank something.
    std::vector<SweepCell> mixed = pileup;
    addConverging(mixed, cEulerPgs, 1.0, 0.05, 6e-4);
    EXPECT_FALSE(errorRanksNothing(mixed));

    // A slow but steady fall (order 0.3 > 0.25) converges; order 0.2 does not.
    std::vector<SweepCell> slow;
    addConverging(slow, cEulerLinear, 0.3, 0.1, 3e-5);
    EXPECT_FALSE(errorRanksNothing(slow));
    std::vector<SweepCell> slower;
    addConverging(slower, cEulerLinear, 0.2, 0.1, 3e-5);
    EXPECT_TRUE(errorRanksNothing(slower));

    // One dt per method, or failed cells only: nothing to judge, no verdict.
    std::vector<SweepCell> single = {cell(cEulerLinear, 0.001, 0.03, 0.1),
                                     cell(cRattleLinear, 0.001, 0.05, 0.2)};
    EXPECT_FALSE(errorRanksNothing(single));
    std::vector<SweepCell> failed = pileup;
    for (SweepCell& c : failed)
    {
        c.survived = false;
        c.trajectoryErrorM = std::nan("");
    }
    EXPECT_FALSE(errorRanksNothing(failed));
}

TEST(SweepChart, TitleSaysWhenTheErrorRanksNothing)
{
    std::vector<SweepCell> pileup;
    addPileupLike(pileup);
    const std::string chaotic = sweepChartScript("pileup", resultOf(pileup));
    EXPECT_NE(chaotic.find("set title 'pileup: speed against accuracy"), std::string::npos) << chaotic;
    EXPECT_NE(chaotic.find("(chaotic: error does not rank the methods"), std::string::npos) << chaotic;

    std::vector<SweepCell> converging;
    addConverging(converging, cEulerLinear, 1.0, 0.01, 3e-5);
    const std::string ranked = sweepChartScript("chain", resultOf(converging));
    EXPECT_NE(ranked.find("set title 'chain: speed against accuracy"), std::string::npos);
    EXPECT_EQ(ranked.find("chaotic"), std::string::npos);
}

TEST(SweepChart, JointGapOnTheYAxisRanksByTheGap)
{
    // The pileup's errors wander, but its joint gaps rank the engines: three cells whose gaps and
    // costs make the front by gap {cheap and open, dear and closed}, while the front by error is
    // {cheapest, middle} (the middle one the most accurate).
    std::vector<SweepCell> cells = {cell(cEulerPgs, 0.001, 0.02, 0.05), cell(cEulerLinear, 0.001, 0.05, 0.04),
                                    cell(cRattleLinear, 0.001, 0.08, 0.06)};
    cells[0].maxJointErrorM = 3e-4;
    cells[1].maxJointErrorM = 5e-4; // dearer than cells[0] and more open: off the front
    cells[2].maxJointErrorM = 1e-10;
    EXPECT_EQ(paretoFront(cells, Accuracy::JointGap), (std::vector<std::size_t>{0, 2}));
    EXPECT_EQ(paretoFront(cells), (std::vector<std::size_t>{0, 1}));

    const std::string script = sweepChartScript("pileup", resultOf(cells), Accuracy::JointGap);
    EXPECT_NE(script.find("set title 'pileup: joint gap against cost"), std::string::npos) << script;
    EXPECT_NE(script.find("set ylabel 'joint gap (m)"), std::string::npos) << script;
    EXPECT_EQ(script.find("chaotic"), std::string::npos);
    // The y range holds the gaps in whole decades: 1e-10 to 1e-3, not the errors' 1e-2 to 1e-1.
    EXPECT_NE(script.find("set yrange [1e-10:0.001]"), std::string::npos) << script;
}

TEST(SweepChart, OneTickFormatPerLogAxisAndWholeDecades)
{
    std::vector<SweepCell> cells;
    addConverging(cells, cEulerLinear, 1.0, 0.016, 3.5e-5);  // cost 0.0175 .. 0.14 s/s
    addConverging(cells, cRattleLinear, 2.0, 0.003, 5.6e-5); // error down to 4.7e-5 m
    const std::string script = sweepChartScript("chain", resultOf(cells));
    EXPECT_NE(script.find("set logscale xy\n"), std::string::npos);
    EXPECT_NE(script.find("set format x '1e%T'\n"), std::string::npos);
    EXPECT_NE(script.find("set format y '1e%T'\n"), std::string::npos);
    EXPECT_EQ(script.find("'%g'"), std::string::npos) << "no mixed 0.001 / 1e-05 ticks";
    EXPECT_NE(script.find("set xtics 10\n"), std::string::npos);
    EXPECT_NE(script.find("set xrange [0.01:1]\n"), std::string::npos) << script;
    EXPECT_NE(script.find("set yrange [1e-05:0.1]\n"), std::string::npos) << script;
}

// The number right after `prefix` in the script (plain string search: std::regex trips GCC 12's
// maybe-uninitialized warning in the sanitizer build).
double numberAfter(const std::string& script, const std::string& prefix)
{
    const std::size_t at = script.find(prefix);
    if (at == std::string::npos)
    {
        ADD_FAILURE() << "no '" << prefix << "' in\n" << script;
        return 0.0;
    }
    return std::stod(script.substr(at + prefix.size()));
}

double screenValue(const std::string& script, const std::string& what)
{
    return numberAfter(script, what + " at screen ");
}

// "set xrange [a:b]" -> {a, b}
std::pair<double, double> rangeOf(const std::string& script, const std::string& axis)
{
    const std::string prefix = "set " + axis + "range [";
    const double low = numberAfter(script, prefix);
    const std::size_t colon = script.find(':', script.find(prefix));
    return {low, std::stod(script.substr(colon + 1))};
}

struct ChartLabel
{
    std::string text;
    double x = 0.0, y = 0.0;
};

// Every "set label N 'TEXT' at X, Y left" line.
std::vector<ChartLabel> labelsOf(const std::string& script)
{
    std::vector<ChartLabel> labels;
    std::istringstream lines(script);
    for (std::string line; std::getline(lines, line);)
    {
        if (line.rfind("set label ", 0) != 0 || line.find(" left") == std::string::npos)
            continue;
        const std::size_t open = line.find('\'');
        const std::size_t close = line.find('\'', open + 1);
        const std::size_t at = line.find(" at ", close);
        ChartLabel label;
        label.text = line.substr(open + 1, close - open - 1);
        label.x = std::stod(line.substr(at + 4));
        label.y = std::stod(line.substr(line.find(',', at) + 1));
        labels.push_back(label);
    }
    return labels;
}

TEST(SweepChart, LegendBelowThePlotAndLabelsApart)
{
    // Two methods with identical cells (as pgs gives under euler and rattle without contacts) and
    // a third: coinciding points must not get labels on top of each other.
    std::vector<SweepCell> cells;
    addConverging(cells, cEulerLinear, 1.0, 0.016, 3.5e-5);
    addConverging(cells, cEulerPgs, 1.0, 0.05, 9e-4);
    addConverging(cells, cRattlePgs, 1.0, 0.05, 9e-4);
    const std::string script = sweepChartScript("chain", resultOf(cells));

    // The key hangs from a point below the plot's bottom margin.
    const double bottom = screenValue(script, "set bmargin");
    ASSERT_NE(script.find("set key at screen 0.5, screen "), std::string::npos) << script;
    const double key = numberAfter(script, "set key at screen 0.5, screen ");
    EXPECT_NE(script.find(" center top", script.find("set key at screen 0.5")), std::string::npos);
    EXPECT_LT(key, bottom - 0.05);
    EXPECT_GT(key, 0.05);

    // Labels, in pixels of the 1100 x 720 image, from the script's margins and ranges.
    const double left = screenValue(script, "set lmargin");
    const double right = screenValue(script, "set rmargin");
    const double top = screenValue(script, "set tmargin");
    const auto [xLow, xHigh] = rangeOf(script, "x");
    const auto [yLow, yHigh] = rangeOf(script, "y");
    const double x0 = std::log10(xLow);
    const double x1 = std::log10(xHigh);
    const double y0 = std::log10(yLow);
    const double y1 = std::log10(yHigh);
    struct Box
    {
        double x0, y0, x1, y1;
    };
    std::vector<Box> boxes;
    for (const ChartLabel& label : labelsOf(script))
    {
        const double px = 1100.0 * (left + (std::log10(label.x) - x0) / (x1 - x0) * (right - left));
        const double py = 720.0 * (bottom + (std::log10(label.y) - y0) / (y1 - y0) * (top - bottom));
        const double width = 6.0 * static_cast<double>(label.text.length());
        boxes.push_back({px, py - 5.0, px + width, py + 5.0});
        EXPECT_GE(px, 1100.0 * left);
        EXPECT_LE(px + width, 1100.0 * right);
    }
    EXPECT_GE(boxes.size(), 8u); // at least the two distinct methods' points are labelled
    EXPECT_LT(boxes.size(), cells.size() + 1);
    for (std::size_t i = 0; i < boxes.size(); ++i)
    {
        for (std::size_t j = i + 1; j < boxes.size(); ++j)
        {
            const Box& a = boxes[i];
            const Box& b = boxes[j];
            const bool overlap = a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
            EXPECT_FALSE(overlap) << "labels " << i << " and " << j << " overlap";
        }
    }
}

} // namespace
} // namespace frontier::app
