// bench/peers/main.cpp: frontier_peers, the same scene stepped by Frontier and its peers (Bullet,
// ODE, MuJoCo), with the same dt; one CSV row and one table row per engine.
//
//   frontier_peers --chain 100 --duration 1 --csv peers.csv --markdown peers.md
//   frontier_peers --scene scenes/chain30.yaml --engines frontier-euler,mujoco
//   frontier_peers --scene scenes/chain30.yaml --dt 0.002,0.001,0.0005 --reference-dt 5e-6 --chart out/peers
//
// Per engine: wall time of its steps alone (us per step and per body-step), the largest joint gap
// after any step (m), the energy by central differences of its poses (engine-independent: the
// change from the first to the last measurable step, in J and in % of the largest kinetic energy),
// and the largest centre-of-mass distance at the end from a reference run (Frontier rattle at
// dt / --reference-divisions), and the deepest overlap between two bodies that may collide over
// the run (m), found by Frontier's contact detection on the engine's poses after every step. An
// engine that exceeds --max-seconds stops early and says so. With several time steps every engine
// runs at each, and --chart DIR draws error against cost as `frontier sweep` draws its chart
// (app/sweep_chart.h), one line per engine; --chart-accuracy joint-gap or penetration puts that
// on the y axis instead (for scenes whose trajectories are chaotic, like the pileup).
#include "app/scene_loading.h"
#include "app/sweep_chart.h"
#include "bench/peers/chain.h"
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/measures.h"
#include "io/scene.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace
{

using namespace frontier;
using namespace frontier::peers;

constexpr double cNan = std::numeric_limits<double>::quiet_NaN();

struct Row
{
    std::string engine;
    double dt = 0.0; // s
    long steps = 0;
    double secondsStepping = 0.0;
    double maxGapM = 0.0;
    double maxPenetrationM = 0.0;
    double energyChangeJ = cNan;
    double energyChangePercent = cNan;
    double errorM = cNan;
    std::string note;
};

struct Settings
{
    double duration = 1.0;
    int referenceDivisions = 16;
    double maxSeconds = 60.0;
};

// Checks that an engine starts where the model does: a translation error shows here, before any
// step.
void checkStartPose(const core::Model& model, const std::vector<Pose>& poses, const std::string& engine)
{
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
    {
        const double dx = (poses[b].position_W - model.bodies[b].position_W).norm();
        const double dq = poses[b].orientation_WB.angularDistance(model.bodies[b].orientation_WB);
        if (dx > 1e-9 || dq > 1e-9)
            throw std::logic_error(engine + " starts body '" + model.bodies[b].name + "' " +
                                   std::to_string(dx) + " m and " + std::to_string(dq) +
                                   " rad from the model's pose");
    }
}

// The poses at the end of a Frontier rattle run at the time step referenceDt (s).
std::vector<Pose> referenceEnd(const core::Model& model, double referenceDt, const Settings& s)
{
    core::Model fine = model;
    fine.simulation.dt = referenceDt;
    const auto engine = makeFrontier(fine, core::IntegratorKind::Rattle);
    const long steps = std::lround(s.duration / fine.simulation.dt);
    for (long k = 0; k < steps; ++k)
        engine->step();
    std::vector<Pose> end;
    engine->poses(end);
    return end;
}

// A message as one line of a table cell: line breaks become spaces, '|' becomes '/'.
std::string oneLine(std::string s)
{
    for (char& c : s)
        c = c == '\n' || c == '\r' ? ' ' : c == '|' ? '/' : c;
    return s;
}

Row run(const std::string& name, const core::Model& model, const std::vector<Pose>& reference,
        const Settings& s)
{
    Row row;
    row.engine = name;
    row.dt = model.simulation.dt;
    std::unique_ptr<Engine> engine;
    try
    {
        engine = makeEngine(name, model);
    }
    catch (const Unsupported& e)
    {
        row.note = oneLine(e.what());
        return row;
    }
    const double h = model.simulation.dt;
    const long steps = std::lround(s.duration / h);
    std::vector<Pose> before, middle, after;
    engine->poses(after);
    checkStartPose(model, after, name);
    PenetrationMeter penetration(model);
    double firstEnergy = cNan, lastEnergy = cNan, maxKinetic = 0.0;
    using Clock = std::chrono::steady_clock;
    for (long k = 0; k < steps; ++k)
    {
        const auto t0 = Clock::now();
        engine->step();
        row.secondsStepping += std::chrono::duration<double>(Clock::now() - t0).count();
        ++row.steps;
        std::swap(before, middle);
        std::swap(middle, after);
        engine->poses(after);
        row.maxGapM = std::max(row.maxGapM, jointGap(model, after));
        row.maxPenetrationM = std::max(row.maxPenetrationM, penetration.deepest(after));
        if (!std::isfinite(row.maxGapM))
        {
            row.note = "blew up at step " + std::to_string(k + 1);
            return row;
        }
        if (k >= 1)
        {
            const Energy e = energyByDifferences(model, before, middle, after, h);
            if (std::isnan(firstEnergy))
                firstEnergy = e.total;
            lastEnergy = e.total;
            maxKinetic = std::max(maxKinetic, e.kinetic);
        }
        if (row.secondsStepping > s.maxSeconds)
        {
            row.note = "stopped after " + std::to_string(row.steps) + " steps (--max-seconds)";
            return row;
        }
    }
    row.energyChangeJ = lastEnergy - firstEnergy;
    row.energyChangePercent = maxKinetic > 0.0 ? 100.0 * row.energyChangeJ / maxKinetic : cNan;
    row.errorM = positionError(after, reference);
    return row;
}

std::string number(double v, const char* format = "%.3g")
{
    if (std::isnan(v))
        return "";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, format, v);
    return buffer;
}

std::string csvField(const std::string& s)
{
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

// Error against cost, every engine a series: the cells of a sweep (study/sweep.h) whose reference
// is Frontier rattle at referenceDt and whose one sample time is the end of the run.
void drawChart(const std::string& folder, const core::Model& model, const std::vector<Row>& rows,
               double referenceDt, const Settings& s, app::Accuracy accuracy)
{
    app::SweepResult result;
    result.bodies = static_cast<int>(model.bodies.size());
    result.schedule.unitS = s.duration;
    result.schedule.units = 1;
    result.schedule.sampleUnits = {1};
    result.reference.method.integrator = core::IntegratorKind::Rattle;
    result.reference.dt = referenceDt;
    for (const Row& r : rows)
    {
        app::SweepCell cell;
        cell.engine = r.engine;
        cell.dt = r.dt;
        cell.steps = std::lround(s.duration / r.dt);
        cell.stepsRun = r.steps;
        cell.bodies = result.bodies;
        cell.survived = r.note.empty() && std::isfinite(r.errorM);
        cell.wallSeconds = r.secondsStepping;
        cell.secondsPerSimSecond = r.steps ? r.secondsStepping / (static_cast<double>(r.steps) * r.dt) : cNan;
        cell.trajectoryErrorM = r.errorM;
        cell.finalErrorM = r.errorM;
        cell.maxJointErrorM = r.steps ? r.maxGapM : cNan;
        cell.maxPenetrationM = r.steps ? r.maxPenetrationM : cNan;
        cell.failure = r.note;
        result.cells.push_back(cell);
    }
    std::filesystem::create_directories(folder);
    if (!app::drawSweepChart(folder, model.name, result, accuracy))
        std::cerr << "frontier_peers: gnuplot is not installed: " << folder << "/sweep.png not drawn\n";
}

} // namespace

int runHarness(int argc, char** argv)
{
    CLI::App app{"frontier_peers: one scene in Frontier, Bullet, ODE and MuJoCo at the same dt"};
    std::string scene;
    int chain = 0;
    double tipRatio = 1.0;
    std::vector<double> dts;
    double referenceDt = 0.0;
    std::string chartDir;
    app::Accuracy chartAccuracy = app::Accuracy::TrajectoryError;
    std::string engines;
    std::string csvPath, markdownPath;
    Settings s;
    app.add_option("--scene", scene, "a scene file (YAML or URDF)");
    app.add_option("--chain", chain, "a generated chain of N boxes on ball joints instead")
        ->check(CLI::Range(1, 10000000));
    app.add_option("--tip-mass-ratio", tipRatio, "the chain's last link's mass over the others'")
        ->check(CLI::PositiveNumber);
    app.add_option("--dt", dts,
                   "time steps (s), comma-separated, each run by every engine; default: the scene's")
        ->delimiter(',')
        ->check(CLI::PositiveNumber);
    app.add_option("--duration", s.duration, "simulated time (s)")->check(CLI::PositiveNumber);
    app.add_option("--engines", engines, "comma-separated engine names; default: all");
    app.add_option("--reference-divisions", s.referenceDivisions, "the reference's dt is dt / this")
        ->check(CLI::Range(1, 1000));
    app.add_option("--reference-dt", referenceDt,
                   "the reference's dt (s), one reference for every dt (instead of --reference-divisions)")
        ->check(CLI::PositiveNumber);
    app.add_option("--chart", chartDir,
                   "draw error against cost, one line per engine (DIR/sweep.png by gnuplot, DIR/sweep.gp, "
                   "DIR/sweep.dat)");
    app.add_option_function<std::string>(
           "--chart-accuracy",
           [&chartAccuracy](const std::string& name) { chartAccuracy = app::accuracyNames().at(name); },
           "the chart's y axis: error (against the reference, the default), joint-gap or penetration "
           "(largest over the run)")
        ->check(CLI::IsMember(app::accuracyNames()));
    app.add_option("--max-seconds", s.maxSeconds, "stop an engine after this much stepping time (s)")
        ->check(CLI::PositiveNumber);
    app.add_option("--csv", csvPath, "write the rows as CSV");
    app.add_option("--markdown", markdownPath, "write the rows as a markdown table");
    CLI11_PARSE(app, argc, argv);
    if (scene.empty() == (chain == 0))
    {
        std::cerr << "frontier_peers: give --scene FILE or --chain N (one of them)\n";
        return 2;
    }
    const std::vector<std::string> all = engineNames();
    std::vector<std::string> names = all;
    if (!engines.empty())
    {
        names.clear();
        std::stringstream list(engines);
        for (std::string name; std::getline(list, name, ',');)
        {
            if (std::find(all.begin(), all.end(), name) == all.end())
            {
                std::cerr << "frontier_peers: unknown engine '" << name << "' (expected one of";
                for (const auto& a : all)
                    std::cerr << " " << a;
                std::cerr << ")\n";
                return 2;
            }
            names.push_back(name);
        }
    }
    core::Model model;
    try
    {
        if (chain > 0)
            model = chainOfBoxes(chain, tipRatio);
        else
        {
            // As `frontier run` loads it: a robot's links that overlap at the start never collide.
            app::LoadedScene loaded = app::loadSceneWithRobots(scene, {});
            app::printLoadWarnings(loaded.report);
            model = std::move(loaded.model);
        }
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier_peers: " << e.what() << "\n";
        return 2;
    }
    if (dts.empty())
        dts.push_back(model.simulation.dt);
    if (!chartDir.empty() && chartAccuracy == app::Accuracy::TrajectoryError && dts.size() > 1 &&
        referenceDt <= 0.0)
    {
        std::cerr
            << "frontier_peers: --chart with several --dt needs --reference-dt (one reference for all)\n";
        return 2;
    }

    std::vector<Row> rows;
    std::vector<Pose> reference;
    if (referenceDt > 0.0)
        reference = referenceEnd(model, referenceDt, s);
    for (const double dt : dts)
    {
        model.simulation.dt = dt;
        if (referenceDt <= 0.0)
            reference = referenceEnd(model, dt / s.referenceDivisions, s);
        for (const std::string& name : names)
        {
            rows.push_back(run(name, model, reference, s));
            const Row& r = rows.back();
            std::cerr << name << " dt " << dt
                      << " s: " << (r.steps ? number(1e6 * r.secondsStepping / r.steps) + " us/step" : r.note)
                      << "\n";
        }
    }

    const int n = static_cast<int>(model.bodies.size());
    std::ostringstream csv, md;
    csv << "scene,bodies,engine,dt_s,steps,us_per_step,us_per_body_step,max_joint_gap_m,max_penetration_m,"
           "energy_change_j,"
           "energy_change_percent_of_max_kinetic,error_m,note\n";
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        const Row& r = rows[i];
        if (i == 0 || r.dt != rows[i - 1].dt)
            md << (i > 0 ? "\n" : "") << "# " << model.name << " (" << n << " bodies), dt = " << r.dt
               << " s\n\n"
               << "| engine | us/step | us/body-step | joint gap (m) | penetration (m) | energy change (% of "
                  "max "
                  "kinetic) | error at "
               << number(s.duration, "%g") << " s (m) | note |\n|---|---|---|---|---|---|---|---|\n";
        const double perStep = r.steps ? 1e6 * r.secondsStepping / r.steps : cNan;
        csv << csvField(model.name) << "," << n << "," << r.engine << "," << number(r.dt, "%g") << ","
            << r.steps << "," << number(perStep) << "," << number(perStep / n) << ","
            << number(r.steps ? r.maxGapM : cNan) << "," << number(r.steps ? r.maxPenetrationM : cNan) << ","
            << number(r.energyChangeJ) << "," << number(r.energyChangePercent) << "," << number(r.errorM)
            << "," << csvField(r.note) << "\n";
        md << "| " << r.engine << " | " << number(perStep) << " | " << number(perStep / n) << " | "
           << number(r.steps ? r.maxGapM : cNan) << " | " << number(r.steps ? r.maxPenetrationM : cNan)
           << " | " << number(r.energyChangePercent) << " | " << number(r.errorM) << " | " << r.note
           << " |\n";
    }
    std::cout << md.str();
    if (!csvPath.empty())
        std::ofstream(csvPath) << csv.str();
    if (!markdownPath.empty())
        std::ofstream(markdownPath) << md.str();
    if (!chartDir.empty())
        drawChart(chartDir, model, rows, referenceDt > 0.0 ? referenceDt : dts.back() / s.referenceDivisions,
                  s, chartAccuracy);
    return 0;
}

int main(int argc, char** argv)
{
    try
    {
        return runHarness(argc, argv);
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier_peers: " << e.what() << "\n";
        return 1;
    }
}
