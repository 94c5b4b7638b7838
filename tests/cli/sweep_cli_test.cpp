// tests/cli/sweep_cli_test.cpp: `frontier sweep` end to end: the CSV's header and rows, the
// accuracy ordering of euler over time steps, the chart, the printed front on the chart's accuracy,
// bad input, no gnuplot, and a sweep stopped by SIGTERM.
#include "app_test_util.h"
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <map>
#include <sstream>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::ScopedPath;
using frontier::app::test::shellQuote;
using frontier::app::test::spawnFrontier;
using frontier::app::test::TestDir;
using frontier::app::test::waitForExit;
using frontier::app::test::waitForHandler;
namespace fs = std::filesystem;

// The documented header (README.md, "Speed against accuracy"): a change here is a change of the
// file format.
const char* const cHeader =
    "scene,integrator,solver,pgs_iterations,dt,steps,bodies,survived,wall_seconds,seconds_per_sim_second,"
    "us_per_body_step,trajectory_error_m,final_error_m,worst_body,max_joint_error_m,max_joint_error_rad,"
    "energy_drift_j,energy_drift_rel,max_penetration_m,failure";

std::vector<std::string> lines(const std::string& text)
{
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
    {
        out.push_back(line);
    }
    return out;
}

// Fields of a CSV line without quoted fields that hold commas (enough for the columns read here,
// which come before the free-text failure column).
std::vector<std::string> fields(const std::string& line)
{
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ','))
    {
        out.push_back(field);
    }
    return out;
}

// The double pendulum over 0.5 s at 4, 2 and 1 ms, euler and rattle: one row per cell, the
// documented header, euler's trajectory error shrinking with dt (first order: about 5x from 4 ms
// to 1 ms against a reference at 0.25 ms), and a chart that reads back.
TEST(SweepCli, DoublePendulumCsvChartAndEulerConverges)
{
    TestDir dir;
    const std::string out = dir.out("sweep");
    const Result r = dir.run("sweep scenes/double_pendulum.yaml --duration 0.5 --dt 0.004,0.002,0.001 "
                             "--integrator euler,rattle --out " +
                             shellQuote(out));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("Pareto front"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("linear/euler"), std::string::npos) << r.out;

    const std::vector<std::string> csv = lines(readText(out + "/sweep.csv"));
    ASSERT_EQ(csv.size(), 2u + 6u) << "a comment line, the header, 2 integrators x 3 time steps";
    EXPECT_EQ(csv[0].rfind("# frontier sweep: scene=scenes/double_pendulum.yaml ", 0), 0u) << csv[0];
    EXPECT_EQ(csv[1], cHeader);
    const std::vector<std::string> header = fields(csv[1]);
    auto column = [&](const std::string& name)
    {
        const auto found = std::find(header.begin(), header.end(), name);
        EXPECT_NE(found, header.end()) << name;
        return static_cast<std::size_t>(found - header.begin());
    };
    std::map<double, double> eulerError; // dt (s) -> trajectory error (m)
    for (std::size_t i = 2; i < csv.size(); ++i)
    {
        const std::vector<std::string> row = fields(csv[i]);
        ASSERT_GE(row.size(), header.size() - 1) << csv[i];
        EXPECT_EQ(row[column("scene")], "scenes/double_pendulum.yaml");
        EXPECT_EQ(row[column("solver")], "linear");
        EXPECT_EQ(row[column("bodies")], "2");
        const double dt = std::stod(row[column("dt")]);
        EXPECT_EQ(std::stol(row[column("steps")]), std::lround(0.5 / dt)) << csv[i];
        if (row[column("integrator")] == "euler")
        {
            ASSERT_EQ(row[column("survived")], "true") << csv[i];
            const double error = std::stod(row[column("trajectory_error_m")]);
            EXPECT_TRUE(std::isfinite(error) && error > 0.0) << csv[i];
            EXPECT_LE(std::stod(row[column("final_error_m")]), error) << csv[i];
            EXPECT_FALSE(row[column("worst_body")].empty()) << csv[i];
            EXPECT_GT(std::stod(row[column("seconds_per_sim_second")]), 0.0) << csv[i];
            EXPECT_LT(std::stod(row[column("max_joint_error_m")]), 1e-6) << csv[i];
            eulerError[dt] = error;
        }
        else
        {
            EXPECT_EQ(row[column("integrator")], "rattle");
        }
    }
    ASSERT_EQ(eulerError.size(), 3u);
    std::printf("double pendulum, euler: trajectory error %.3g m at 4 ms, %.3g m at 2 ms, %.3g m at 1 ms\n",
                eulerError[0.004], eulerError[0.002], eulerError[0.001]);
    EXPECT_LT(eulerError[0.002], eulerError[0.004]);
    EXPECT_LT(eulerError[0.001], eulerError[0.002]);
    EXPECT_GT(eulerError[0.004] / eulerError[0.001], 2.0) << "euler is first order";

    const frontier::render::Image chart = frontier::render::readPng(out + "/sweep.png");
    EXPECT_GT(chart.width, 0);
    EXPECT_GT(chart.height, 0);
    EXPECT_TRUE(fs::exists(out + "/sweep.gp"));
    EXPECT_TRUE(fs::exists(out + "/sweep.dat"));
}

TEST(SweepCli, UnknownSolverExitsTwoNamingIt)
{
    TestDir dir;
    const Result r =
        dir.run("sweep scenes/pendulum.yaml --duration 0.1 --solver linear,pgs:20,simplex --out " +
                shellQuote(dir.out("sweep")));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("'simplex'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.out("sweep") + "/sweep.csv"));
}

TEST(SweepCli, NonPositiveTimeStepExitsTwoNamingIt)
{
    TestDir dir;
    for (const std::string bad : {"-0.002", "0"})
    {
        const Result r = dir.run("sweep scenes/pendulum.yaml --duration 0.1 --dt 0.004," + bad + " --out " +
                                 shellQuote(dir.out("sweep")));
        EXPECT_EQ(r.exitCode, 2) << r.err;
        EXPECT_NE(r.err.find("'" + bad + "'"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir.out("sweep") + "/sweep.csv"));
    }
}

// Without gnuplot the CSV and the chart script are written, the note says how to install it,
// and the exit code is 0.
TEST(SweepCli, WithoutGnuplotWritesCsvAndScript)
{
    TestDir dir;
    const std::string out = dir.out("sweep");
    Result r;
    {
        const ScopedPath noGnuplot((dir.path() / "empty-path").string());
        r = dir.run("sweep scenes/pendulum.yaml --duration 0.2 --dt 0.004,0.002 --integrator euler --out " +
                    shellQuote(out));
    }
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("apt-get install gnuplot-nox"), std::string::npos) << r.err;
    EXPECT_EQ(lines(readText(out + "/sweep.csv")).size(), 2u + 2u);
    EXPECT_TRUE(fs::exists(out + "/sweep.gp"));
    EXPECT_FALSE(fs::exists(out + "/sweep.png"));
}

// --chart-accuracy penetration: the chart's points are each cell's deepest overlap, as the CSV's
// max_penetration_m gives it, and the axis says so; an unknown accuracy exits 2 naming the choices.
TEST(SweepCli, ChartAccuracyPutsThePenetrationOnTheYAxis)
{
    TestDir dir;
    const std::string out = dir.out("sweep");
    const Result r = dir.run("sweep scenes/box_stack.yaml --duration 0.3 --dt 0.002,0.001 --integrator euler "
                             "--chart-accuracy penetration --out " +
                             shellQuote(out));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(readText(out + "/sweep.gp").find("set ylabel 'penetration (m)"), std::string::npos);
    const std::vector<std::string> csv = lines(readText(out + "/sweep.csv"));
    ASSERT_EQ(csv.size(), 2u + 2u);
    const std::vector<std::string> header = fields(csv[1]);
    const auto column = [&](const std::string& name)
    { return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin()); };
    const std::string data = readText(out + "/sweep.dat");
    for (std::size_t i = 2; i < csv.size(); ++i)
    {
        const std::vector<std::string> row = fields(csv[i]);
        const double depth = std::stod(row[column("max_penetration_m")]);
        ASSERT_GT(depth, 0.0) << csv[i]; // boxes resting on each other overlap a little
        const double dtMs = 1e3 * std::stod(row[column("dt")]);
        std::ostringstream label;
        label << "\"" << dtMs << " ms\"";
        bool found = false;
        for (const std::string& line : lines(data))
        {
            std::istringstream in(line);
            double cost = 0.0, y = 0.0;
            std::string rest;
            if (line.find(label.str()) != std::string::npos && (in >> cost >> y))
            {
                EXPECT_NEAR(y, depth, 1e-6 * depth) << line;
                found = true;
            }
        }
        EXPECT_TRUE(found) << label.str() << " not in sweep.dat:\n" << data;
    }
    const Result bad = dir.run("sweep scenes/box_stack.yaml --chart-accuracy depth --out " + shellQuote(out));
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("joint-gap"), std::string::npos) << bad.err;
}

// --chart-accuracy penetration prints the Pareto front the chart draws: the one on penetration,
// computed here from sweep.csv's columns (survived cells by seconds_per_sim_second, each kept when
// its max_penetration_m is below every cheaper one's), each entry with its penetration.
TEST(SweepCli, ChartAccuracyPenetrationPrintsThePenetrationFront)
{
    TestDir dir;
    const std::string out = dir.out("sweep");
    const Result r = dir.run("sweep scenes/box_stack.yaml --duration 0.2 --dt 0.004,0.002,0.001 "
                             "--integrator euler,rattle --chart-accuracy penetration --out " +
                             shellQuote(out));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<std::string> csv = lines(readText(out + "/sweep.csv"));
    ASSERT_EQ(csv.size(), 2u + 6u);
    const std::vector<std::string> header = fields(csv[1]);
    const auto column = [&](const std::string& name)
    { return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin()); };
    struct FrontCell
    {
        double cost = 0.0;  // s per simulated s
        double depth = 0.0; // m
        std::string name;   // "linear/euler dt 0.002 s", as the front line names a cell
    };
    std::vector<FrontCell> cells;
    for (std::size_t i = 2; i < csv.size(); ++i)
    {
        const std::vector<std::string> row = fields(csv[i]);
        if (row[column("survived")] != "true")
        {
            continue;
        }
        char dt[32];
        std::snprintf(dt, sizeof dt, "%.6g", std::stod(row[column("dt")]));
        cells.push_back({std::stod(row[column("seconds_per_sim_second")]),
                         std::stod(row[column("max_penetration_m")]),
                         row[column("solver")] + "/" + row[column("integrator")] + " dt " + dt + " s"});
    }
    std::sort(cells.begin(), cells.end(),
              [](const FrontCell& a, const FrontCell& b)
              { return a.cost != b.cost ? a.cost < b.cost : a.depth < b.depth; });
    std::vector<FrontCell> front;
    for (const FrontCell& c : cells)
    {
        if (front.empty() || c.depth < front.back().depth)
        {
            front.push_back(c);
        }
    }
    const std::string prefix = "Pareto front on penetration (";
    std::string line;
    for (const std::string& l : lines(r.out))
    {
        line = l.rfind(prefix, 0) == 0 ? l : line;
    }
    ASSERT_FALSE(line.empty()) << r.out;
    // " NAME (COST s/sim s, DEPTH m)" per cell, after the colon.
    std::string rest = line.substr(line.find("):") + 2);
    for (const FrontCell& c : front)
    {
        const std::size_t at = rest.find(" " + c.name + " (");
        ASSERT_EQ(at, rest.find_first_not_of(", ") - 1) << c.name << " is not next in: " << line;
        const std::size_t comma = rest.find(", ", at);
        const std::size_t metres = rest.find(" m)", comma);
        ASSERT_NE(metres, std::string::npos) << line;
        const double printed = std::stod(rest.substr(comma + 2, metres - comma - 2));
        EXPECT_NEAR(printed, c.depth, 5e-3 * c.depth) << c.name << " in: " << line;
        rest = rest.substr(metres + 3);
    }
    EXPECT_EQ(rest.find("dt"), std::string::npos) << "cells beyond the front in: " << line;
}

// --contact-tolerance applies to every cell but not to the reference: the same sweep of the box
// stack at 1e-2 m/s has the same reference, written in sweep.csv's first line with the cells'
// tolerance, and cells whose boxes sink deeper than at the scene's 3e-5 m/s.
TEST(SweepCli, ContactToleranceLoosensTheCellsNotTheReference)
{
    TestDir dir;
    const auto sweep = [&](const std::string& name, const std::string& flags)
    {
        const std::string out = dir.out(name);
        const Result r =
            dir.run("sweep scenes/box_stack.yaml --duration 0.5 --dt 0.002,0.001 --integrator euler "
                    "--chart-accuracy penetration --out " +
                    shellQuote(out) + flags);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return lines(readText(out + "/sweep.csv"));
    };
    const std::vector<std::string> tight = sweep("tight", "");
    const std::vector<std::string> loose = sweep("loose", " --contact-tolerance 1e-2");
    ASSERT_EQ(tight.size(), 4u);
    ASSERT_EQ(loose.size(), 4u);
    const std::vector<std::string> header = fields(tight[1]);
    const auto column = [&](const std::string& name)
    { return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin()); };
    for (std::size_t i = 2; i < 4; ++i)
    {
        const std::vector<std::string> a = fields(tight[i]);
        const std::vector<std::string> b = fields(loose[i]);
        EXPECT_GT(std::stod(b[column("max_penetration_m")]), std::stod(a[column("max_penetration_m")]))
            << tight[i] << "\n"
            << loose[i];
        EXPECT_NE(b[column("trajectory_error_m")], a[column("trajectory_error_m")]);
    }
    // The first line describes the reference, the same, and then the cells' tolerance.
    EXPECT_EQ(tight[0] + " contact_tolerance=0.01", loose[0]);
}

} // namespace

// --reference-csv: the errors are measured against rows the methods did not make. A box falling
// freely from (0, 0, 5) m at (1, 0, 2) m/s, its parabola every 0.1 s: euler's error at the end is
// |g| h T / 2 exactly, rattle's zero (it integrates a parabola exactly). A body the scene lacks, or
// the flag without --reference-body, exits 2.
TEST(SweepCli, ExternalReferenceCsvMeasuresTheMethodsOwnError)
{
    TestDir dir;
    const std::string scene = dir.write(
        "falling_box.yaml", "name: falling box\nsimulation: {dt: 0.01, duration: 1.0, gravity: [0, 0, "
                            "-9.81]}\nbodies:\n  - {name: box, shape: {type: box, size: [0.1, 0.1, "
                            "0.1]}, mass: 1.0,\n     position: [0, 0, 5], velocity: [1, 0, 2]}\n");
    std::string csv = "t,x,y,z\n";
    for (int k = 0; k <= 10; ++k)
    {
        const double t = 0.1 * k; // s
        char row[128];
        std::snprintf(row, sizeof row, "%.17g,%.17g,0,%.17g\n", t, t, 5.0 + 2.0 * t - 0.5 * 9.81 * t * t);
        csv += row;
    }
    const std::string reference = dir.write("box.csv", csv);
    const std::string out = dir.out("sweep");
    const Result r = dir.run("sweep " + shellQuote(scene) + " --dt 0.01,0.005 --integrator euler,rattle " +
                             "--reference-csv " + shellQuote(reference) + " --reference-body box --out " +
                             shellQuote(out));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("box.csv"), std::string::npos) << r.out;
    const std::vector<std::string> rows = lines(readText(out + "/sweep.csv")); // settings, header, cells
    ASSERT_EQ(rows.size(), 6u);
    for (std::size_t k = 2; k < rows.size(); ++k)
    {
        const std::vector<std::string> f = fields(rows[k]);
        const double dt = std::stod(f[4]);          // s
        const double finalError = std::stod(f[12]); // m
        const double expected = f[1] == "euler" ? 0.5 * 9.81 * dt * 1.0 : 0.0;
        EXPECT_NEAR(finalError, expected, 1e-9) << rows[k];
    }
    const Result lid = dir.run("sweep " + shellQuote(scene) + " --reference-csv " + shellQuote(reference) +
                               " --reference-body lid --out " + shellQuote(dir.out("lid")));
    EXPECT_EQ(lid.exitCode, 2) << lid.err;
    EXPECT_NE(lid.err.find("'lid'"), std::string::npos) << lid.err;
    const Result alone = dir.run("sweep " + shellQuote(scene) + " --reference-csv " + shellQuote(reference) +
                                 " --out " + shellQuote(dir.out("alone")));
    EXPECT_EQ(alone.exitCode, 2) << alone.err;

    // The same reference declared by the scene (its CSV relative to the scene's folder) gives the
    // same errors; `run` accepts the key; a body that is not in the scene is named at its line.
    const std::string declared =
        dir.write("declared.yaml", readText(scene) + "reference: {csv: box.csv, body: box}\n");
    const std::string declaredOut = dir.out("declared");
    const Result d = dir.run("sweep " + shellQuote(declared) +
                             " --dt 0.01,0.005 --integrator euler,rattle --out " + shellQuote(declaredOut));
    ASSERT_EQ(d.exitCode, 0) << d.err;
    const std::vector<std::string> declaredRows = lines(readText(declaredOut + "/sweep.csv"));
    ASSERT_EQ(declaredRows.size(), rows.size());
    for (std::size_t k = 2; k < rows.size(); ++k)
    {
        EXPECT_EQ(fields(declaredRows[k])[12], fields(rows[k])[12]) << declaredRows[k];
    }
    EXPECT_EQ(dir.run("run " + shellQuote(declared) + " --duration 0.05 --quiet").exitCode, 0);
    const std::string wrongBody =
        dir.write("wrong_body.yaml", readText(scene) + "reference: {csv: box.csv, body: lid}\n");
    const Result wrong = dir.run("run " + shellQuote(wrongBody) + " --duration 0.05 --quiet");
    EXPECT_EQ(wrong.exitCode, 2) << wrong.err;
    EXPECT_NE(wrong.err.find("wrong_body.yaml:6:"), std::string::npos) << wrong.err;
    EXPECT_NE(wrong.err.find("'lid'"), std::string::npos) << wrong.err;
}

// SIGTERM a second into a long sweep (its cells from a thousand steps to millions, against an
// external reference so that they start at once): exit 143; the cells finished before it in
// sweep.failed.csv, in grid order, its first line saying interrupted=SIGTERM; nothing under the
// names of a finished sweep (sweep.csv, the chart) and no temporary file. A finished sweep of the
// same folder then removes it.
TEST(SweepCli, SigtermKeepsTheFinishedCellsUnderAFailedName)
{
    const TestDir dir;
    std::string samples = "t,x,y,z\n"; // bob's positions: any will do for this test
    for (int t = 0; t <= 60; t += 10)
    {
        samples += std::to_string(t) + ",0.8,0,1.5\n";
    }
    const std::string reference = dir.write("bob.csv", samples);
    std::vector<double> dts; // 0.05 s halved 14 times: 1 000 to 16 million steps of 50 s
    std::string dtList;
    for (int k = 0; k < 15; ++k)
    {
        dts.push_back(0.05 / static_cast<double>(1 << k));
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", dts.back());
        dtList += (k == 0 ? "" : ",") + std::string(text);
    }
    const std::size_t cellCount = 2 * dts.size(); // euler and rattle
    const std::string out = dir.out("sweep");
    const pid_t pid = spawnFrontier(dir, {"sweep", "scenes/pendulum.yaml", "--duration", "50", "--dt", dtList,
                                          "--integrator", "euler,rattle", "--reference-csv", reference,
                                          "--reference-body", "bob", "--out", out});
    ASSERT_GT(pid, 0);
    ASSERT_TRUE(waitForHandler(pid, SIGTERM, 30.0)) << readText(dir.path() / "stderr.txt");
    std::this_thread::sleep_for(std::chrono::seconds(1));
    ::kill(pid, SIGTERM);
    ASSERT_EQ(waitForExit(pid, 60.0), 143) << readText(dir.path() / "stderr.txt");

    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(out))
    {
        names.push_back(entry.path().filename().string());
    }
    EXPECT_EQ(names, std::vector<std::string>{"sweep.failed.csv"});
    const std::vector<std::string> rows = lines(readText(out + "/sweep.failed.csv"));
    ASSERT_GE(rows.size(), 3u) << "no cell finished in a second; make the first cells shorter";
    ASSERT_LT(rows.size(), 2 + cellCount) << "the sweep finished before the signal; make it longer";
    EXPECT_EQ(rows[0].rfind("# frontier sweep: scene=scenes/pendulum.yaml ", 0), 0u) << rows[0];
    const std::string marker = " interrupted=SIGTERM";
    EXPECT_EQ(rows[0].substr(rows[0].size() - std::min(rows[0].size(), marker.size())), marker) << rows[0];
    EXPECT_EQ(rows[1], cHeader);
    for (std::size_t k = 2; k < rows.size(); ++k)
    {
        const std::vector<std::string> cell = fields(rows[k]);
        const std::size_t index = k - 2; // integrators, then solvers, then time steps coarse to fine
        EXPECT_EQ(cell[1], index < dts.size() ? "euler" : "rattle") << rows[k];
        EXPECT_EQ(std::stod(cell[4]), dts[index % dts.size()]) << rows[k];
        EXPECT_EQ(cell[7], "true") << rows[k];
    }
    const std::string err = readText(dir.path() / "stderr.txt");
    EXPECT_NE(err.find("frontier: SIGTERM: the sweep stopped after " + std::to_string(rows.size() - 2) +
                       " of " + std::to_string(cellCount) + " cells; the finished ones are in " + out +
                       "/sweep.failed.csv"),
              std::string::npos)
        << err;

    const Result finished = dir.run("sweep scenes/pendulum.yaml --duration 0.1 --dt 0.01 --integrator euler "
                                    "--reference-csv " +
                                    shellQuote(reference) + " --reference-body bob --out " + shellQuote(out));
    ASSERT_EQ(finished.exitCode, 0) << finished.err;
    EXPECT_TRUE(fs::exists(out + "/sweep.csv"));
    EXPECT_FALSE(fs::exists(out + "/sweep.failed.csv")) << "the stopped sweep's cells outlive a finished one";
}
