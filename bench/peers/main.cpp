// bench/peers/main.cpp: frontier_peers, the same scene stepped by Frontier and its peers (Bullet,
// ODE, MuJoCo), with the same dt; one CSV row and one table row per engine.
//
//   frontier_peers --chain 100 --duration 1 --csv peers.csv --markdown peers.md
//   frontier_peers --scene scenes/chain30.yaml --engines frontier-euler,mujoco
//
// Per engine: wall time of its steps alone (us per step and per body-step), the largest joint gap
// after any step (m), the energy by central differences of its poses (engine-independent: the
// change from the first to the last measurable step, in J and in % of the largest kinetic energy),
// and the largest centre-of-mass distance at the end from a reference run (Frontier rattle at
// dt / --reference-divisions), and the deepest overlap between two bodies that may collide over
// the run (m), found by Frontier's contact detection on the engine's poses after every step. An
// engine that exceeds --max-seconds stops early and says so.
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

std::vector<Pose> referenceEnd(const core::Model& model, const Settings& s)
{
    core::Model fine = model;
    fine.simulation.dt = model.simulation.dt / s.referenceDivisions;
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

} // namespace

int runHarness(int argc, char** argv)
{
    CLI::App app{"frontier_peers: one scene in Frontier, Bullet, ODE and MuJoCo at the same dt"};
    std::string scene;
    int chain = 0;
    double tipRatio = 1.0;
    double dt = 0.0;
    std::string engines;
    std::string csvPath, markdownPath;
    Settings s;
    app.add_option("--scene", scene, "a scene file (YAML or URDF)");
    app.add_option("--chain", chain, "a generated chain of N boxes on ball joints instead")
        ->check(CLI::Range(1, 10000000));
    app.add_option("--tip-mass-ratio", tipRatio, "the chain's last link's mass over the others'")
        ->check(CLI::PositiveNumber);
    app.add_option("--dt", dt, "time step (s); default: the scene's")->check(CLI::PositiveNumber);
    app.add_option("--duration", s.duration, "simulated time (s)")->check(CLI::PositiveNumber);
    app.add_option("--engines", engines, "comma-separated engine names; default: all");
    app.add_option("--reference-divisions", s.referenceDivisions, "the reference's dt is dt / this")
        ->check(CLI::Range(1, 1000));
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
        model = chain > 0 ? chainOfBoxes(chain, tipRatio) : io::loadScene(scene);
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier_peers: " << e.what() << "\n";
        return 2;
    }
    if (dt > 0.0)
        model.simulation.dt = dt;

    const std::vector<Pose> reference = referenceEnd(model, s);
    std::vector<Row> rows;
    for (const std::string& name : names)
    {
        rows.push_back(run(name, model, reference, s));
        const Row& r = rows.back();
        std::cerr << name << ": "
                  << (r.steps ? number(1e6 * r.secondsStepping / r.steps) + " us/step" : r.note) << "\n";
    }

    const int n = static_cast<int>(model.bodies.size());
    std::ostringstream csv, md;
    csv << "scene,bodies,engine,dt_s,steps,us_per_step,us_per_body_step,max_joint_gap_m,max_penetration_m,"
           "energy_change_j,"
           "energy_change_percent_of_max_kinetic,error_m,note\n";
    md << "| engine | us/step | us/body-step | joint gap (m) | penetration (m) | energy change (% of max "
          "kinetic) "
          "| error at "
       << number(s.duration, "%g") << " s (m) | note |\n|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows)
    {
        const double perStep = r.steps ? 1e6 * r.secondsStepping / r.steps : cNan;
        csv << csvField(model.name) << "," << n << "," << r.engine << "," << number(model.simulation.dt, "%g")
            << "," << r.steps << "," << number(perStep) << "," << number(perStep / n) << ","
            << number(r.steps ? r.maxGapM : cNan) << "," << number(r.steps ? r.maxPenetrationM : cNan) << ","
            << number(r.energyChangeJ) << "," << number(r.energyChangePercent) << "," << number(r.errorM)
            << "," << csvField(r.note) << "\n";
        md << "| " << r.engine << " | " << number(perStep) << " | " << number(perStep / n) << " | "
           << number(r.steps ? r.maxGapM : cNan) << " | " << number(r.steps ? r.maxPenetrationM : cNan)
           << " | " << number(r.energyChangePercent) << " | " << number(r.errorM) << " | " << r.note
           << " |\n";
    }
    std::cout << "# " << model.name << " (" << n << " bodies), dt = " << model.simulation.dt << " s\n\n"
              << md.str();
    if (!csvPath.empty())
        std::ofstream(csvPath) << csv.str();
    if (!markdownPath.empty())
        std::ofstream(markdownPath) << "# " << model.name << ", dt = " << model.simulation.dt << " s\n\n"
                                    << md.str();
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
