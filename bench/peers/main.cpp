// bench/peers/main.cpp: frontier_peers, the same scene stepped by Frontier and its peers (Bullet,
// ODE, MuJoCo), with the same dt; one CSV row and one table row per engine.
//
//   frontier_peers --chain 100 --duration 1 --csv peers.csv --markdown peers.md
//   frontier_peers --scene scenes/chain30.yaml --engines frontier-euler,mujoco --rounds 1
//   frontier_peers --scene scenes/pileup44.yaml --rounds 5 --baseline bullet-si --variants 6
//   frontier_peers --scene scenes/chain30.yaml --dt 0.002,0.001,0.0005 --reference-dt 5e-6 --chart out/peers
//
// An MJCF file (--mjcf FILE, mjcf_peers.h) runs in MuJoCo from the file itself and in Frontier from
// its import: masses and inertias of every body, --duration s of passive motion (MuJoCo RK4 and
// Frontier rattle4 at 1e-4 s, contacts off) and the time per step of each on the file as it is:
//   frontier_peers --mjcf /usr/share/doc/dart/data/mjcf/openai/inverted_pendulum.xml --duration 1
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
// on the y axis instead (for scenes whose trajectories are chaotic, like the pileup; with
// --variants, the penetration is the median over the jittered starts).
//
// Engine settings: an engine in --engines (and --baseline) may carry accuracy settings after its
// name, each as :KEY=VALUE (engine.h: parseEngine), and is then a row and a line of its own named
// by that spelling: --engines frontier-euler,frontier-euler:relative=0.01,bullet-si:iterations=50.
// An unknown engine or key, or a value out of range, exits with code 2 and names them.
//
// Rounds (--rounds N, default 5): every engine's run is repeated N times, the engines alternating
// within each round (A B C, A B C, ...), so that a shared machine's slow spells fall on all of
// them; the time per step is the median over the rounds with its range (smallest-largest).
// --baseline ENGINE gives each engine's time over the baseline's, taken round by round (engine in
// round k over baseline in round k) and reported as the median and range of those ratios. The
// accuracy columns are the first round's: every engine here is deterministic (a run starts from a
// new engine; ODE's random generator is reset for each), which the harness checks; should the rounds
// ever disagree, each column shows the worst of them and the note says so.
//
// Jittered starts (--variants N, --seed S): N more runs of every engine, each from a variant of
// the scene whose free trees (moving bodies joined by joints and by none to the world or to a
// static body; a free body alone) are each moved rigidly by a pseudo-random offset: up to +-2 cm
// in x and in y, up to 5 mm upwards, and a yaw of up to +-0.05 rad about the vertical through the
// tree's centre of mass (uniform; std::mt19937_64 seeded with S, default 1: reproducible). Joints
// stay exactly closed; a variant that would start overlapping more deeply than the scene itself is
// drawn again (jitter.h). The table gives the median and the largest penetration over the variants.
//
// Warnings: whatever an engine reports (MuJoCo's warning counters, ODE's and Bullet's messages, a
// full buffer, a bound it cuts at; engine.h) goes into the row's note with the step it first came
// at. MuJoCo's fixed buffers are sized from the scene; a run that still fills one is rerun with
// them doubled (up to 8x), and the note says so.
#include "app/sweep_chart.h"
#include "bench/peers/chain.h"
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/harness.h"
#include "bench/peers/jitter.h"
#include "bench/peers/measures.h"
#include "bench/peers/mjcf_peers.h"
#include "io/scene.h"
#include "run/scene_loading.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

namespace
{

using namespace frontier;
using namespace frontier::peers;

constexpr double cNan = std::numeric_limits<double>::quiet_NaN();

struct Settings
{
    RunSettings run;
    int referenceDivisions = 16;
    int rounds = 5;
    std::string baseline; // an engine's name, or none
    int variants = 0;
    std::uint64_t seed = 1;
};

// One engine at one time step: its runs over the rounds and over the jittered variants.
struct Row
{
    std::string engine;
    double dt = 0.0; // s
    std::vector<EngineRun> rounds;
    std::vector<EngineRun> variants;

    // us per step of every round, in round order (NaN for a round that took no step).
    std::vector<double> microsecondsPerStep() const
    {
        std::vector<double> out;
        for (const EngineRun& r : rounds)
            out.push_back(1e6 * r.secondsPerStep());
        return out;
    }
    bool ran() const { return !rounds.empty() && rounds.front().steps > 0; }
};

// The poses at the end of a Frontier rattle run at the time step referenceDt (s).
std::vector<Pose> referenceEnd(const core::Model& model, double referenceDt, const Settings& s)
{
    core::Model fine = model;
    fine.simulation.dt = referenceDt;
    const auto engine = makeFrontier(fine, core::IntegratorKind::Rattle);
    const long steps = std::lround(s.run.duration / fine.simulation.dt);
    for (long k = 0; k < steps; ++k)
        engine->step();
    std::vector<Pose> end;
    engine->poses(end);
    return end;
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

// What the table, the CSV and the chart show of a row.
struct Summary
{
    Spread microsecondsPerStep; // over the rounds
    Spread ratio;               // to the baseline, round by round
    Accuracy accuracy;          // the first round's (the worst of the rounds if they differ)
    Spread variantPenetrationM; // over the variants
    long steps = 0;             // of the first round
    std::string failure;        // of the first round
    std::string note;
};

Summary summarize(const Row& row, const Row* baseline, const Settings& s)
{
    Summary out;
    if (row.rounds.empty())
        return out;
    const EngineRun& first = row.rounds.front();
    out.steps = first.steps;
    out.failure = first.failure;
    if (first.steps > 0)
    {
        out.microsecondsPerStep = spread(row.microsecondsPerStep());
        if (baseline && baseline->ran())
            out.ratio = spread(pairedRatios(row.microsecondsPerStep(), baseline->microsecondsPerStep()));
    }
    // A later round that --max-seconds cut shorter than the first measured less: it has a time
    // (and its note says where it stopped), not accuracy figures.
    std::vector<EngineRun> complete;
    for (const EngineRun& r : row.rounds)
        if (!(r.timedOut && r.steps < first.steps))
            complete.push_back(r);
    out.accuracy = worstAccuracy(complete);
    std::vector<std::string> parts;
    if (!out.accuracy.agree)
        parts.push_back("the rounds' accuracy figures differ: the worst of " +
                        std::to_string(complete.size()) + " shown");
    parts.push_back(note(first));
    for (std::size_t k = 1; k < row.rounds.size(); ++k)
        if (note(row.rounds[k]) != note(first))
            parts.push_back("round " + std::to_string(k + 1) + ": " + note(row.rounds[k]));
    std::vector<double> depths;
    for (std::size_t v = 0; v < row.variants.size(); ++v)
    {
        depths.push_back(row.variants[v].steps > 0 ? row.variants[v].maxPenetrationM : cNan);
        if (!note(row.variants[v]).empty())
            parts.push_back("variant " + std::to_string(v + 1) + ": " + note(row.variants[v]));
    }
    out.variantPenetrationM = spread(depths);
    if (row.rounds.size() < static_cast<std::size_t>(s.rounds) && !first.refused)
        parts.push_back("1 round");
    for (const std::string& part : parts)
        if (!part.empty())
            out.note += (out.note.empty() ? "" : "; ") + part;
    return out;
}

// Error against cost, every engine a series: the cells of a sweep (study/sweep.h) whose reference
// is Frontier rattle at referenceDt and whose one sample time is the end of the run; the cost is
// the median over the rounds.
void drawChart(const std::string& folder, const core::Model& model, const std::vector<Row>& rows,
               const std::vector<Summary>& summaries, double referenceDt, const Settings& s,
               app::Accuracy accuracy)
{
    app::SweepResult result;
    result.bodies = static_cast<int>(model.bodies.size());
    result.schedule.unitS = s.run.duration;
    result.schedule.units = 1;
    result.schedule.sampleUnits = {1};
    result.reference.method.integrator = core::IntegratorKind::Rattle;
    result.reference.dt = referenceDt;
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        const Row& r = rows[i];
        const Summary& m = summaries[i];
        const double secondsPerStep = 1e-6 * m.microsecondsPerStep.median;
        app::SweepCell cell;
        cell.engine = r.engine;
        cell.dt = r.dt;
        cell.steps = std::lround(s.run.duration / r.dt);
        cell.stepsRun = m.steps;
        cell.bodies = result.bodies;
        cell.survived = m.failure.empty() && std::isfinite(m.accuracy.errorM);
        cell.wallSeconds = m.steps ? secondsPerStep * static_cast<double>(m.steps) : 0.0;
        cell.secondsPerSimSecond = m.steps ? secondsPerStep / r.dt : cNan;
        cell.trajectoryErrorM = m.accuracy.errorM;
        cell.finalErrorM = m.accuracy.errorM;
        cell.maxJointErrorM = m.steps ? m.accuracy.maxGapM : cNan;
        // With jittered starts, the median over them: one start's landing is chance.
        cell.maxPenetrationM = !m.steps             ? cNan
                               : r.variants.empty() ? m.accuracy.maxPenetrationM
                                                    : m.variantPenetrationM.median;
        cell.failure = m.failure;
        result.cells.push_back(cell);
    }
    std::filesystem::create_directories(folder);
    if (!app::drawSweepChart(folder, model.name, result, accuracy))
        std::cerr << "frontier_peers: gnuplot is not installed: " << folder << "/sweep.png not drawn\n";
}

// A time in us: 3 significant digits, whole numbers from 1 000 on (no exponent: a range joins two).
std::string micros(double v)
{
    return v >= 999.5 ? number(v, "%.0f") : number(v);
}

// "min-max" of a spread, "" when it has none.
std::string range(
    const Spread& v, std::string (*format)(double) = [](double x) { return number(x); })
{
    return std::isnan(v.min) ? "" : format(v.min) + "-" + format(v.max);
}

// The command line: what to run, how often, and where to write it.
struct Options
{
    std::string scene;
    int chain = 0;
    double tipRatio = 1.0;
    std::string mjcfFile;
    bool noContacts = false;
    double motionDt = 1e-4; // s
    std::vector<double> dts;
    double referenceDt = 0.0; // s
    std::string chartDir;
    app::Accuracy chartAccuracy = app::Accuracy::TrajectoryError;
    std::string engines;
    std::string csvPath, markdownPath;
    Settings s;
};

void addSceneOptions(CLI::App& app, Options& o)
{
    app.add_option("--scene", o.scene, "a scene file (YAML or URDF)");
    app.add_option("--mjcf", o.mjcfFile,
                   "an MJCF file in MuJoCo (from the file) beside Frontier (from its import): masses and "
                   "inertias, --duration s of passive motion, time per step (mjcf_peers.h)");
    app.add_option("--motion-dt", o.motionDt, "--mjcf: the time step of both engines' passive runs (s)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_flag("--no-contacts", o.noContacts,
                 "--mjcf: compare the motion with contacts off even where geoms may collide");
    app.add_option("--chain", o.chain, "a generated chain of N boxes on ball joints instead")
        ->check(CLI::Range(1, 10000000));
    app.add_option("--tip-mass-ratio", o.tipRatio, "the chain's last link's mass over the others'")
        ->check(CLI::PositiveNumber);
}

void addRunOptions(CLI::App& app, Options& o)
{
    app.add_option("--dt", o.dts,
                   "time steps (s), comma-separated, each run by every engine; default: the scene's")
        ->delimiter(',')
        ->check(CLI::PositiveNumber);
    app.add_option("--duration", o.s.run.duration, "simulated time (s)")->check(CLI::PositiveNumber);
    app.add_option("--engines", o.engines,
                   "comma-separated engines, each a name with any settings as :KEY=VALUE "
                   "(frontier-euler:tolerance=1e-3:relative=0.01, bullet-si:iterations=20; engine.h); "
                   "default: every engine at its defaults");
    app.add_option("--reference-divisions", o.s.referenceDivisions, "the reference's dt is dt / this")
        ->check(CLI::Range(1, 1000));
    app.add_option("--reference-dt", o.referenceDt,
                   "the reference's dt (s), one reference for every dt (instead of --reference-divisions)")
        ->check(CLI::PositiveNumber);
    app.add_option("--chart", o.chartDir,
                   "draw error against cost, one line per engine (DIR/sweep.png by gnuplot, DIR/sweep.gp, "
                   "DIR/sweep.dat)");
    app.add_option_function<std::string>(
           "--chart-accuracy",
           [&o](const std::string& name) { o.chartAccuracy = app::accuracyNames().at(name); },
           "the chart's y axis: error (against the reference, the default), joint-gap or penetration "
           "(largest over the run)")
        ->check(CLI::IsMember(app::accuracyNames()));
    app.add_option("--max-seconds", o.s.run.maxSeconds, "stop an engine after this much stepping time (s)")
        ->check(CLI::PositiveNumber);
}

void addRepeatAndOutputOptions(CLI::App& app, Options& o)
{
    app.add_option("--rounds", o.s.rounds,
                   "runs of every engine, alternating engines within a round; the time is the median "
                   "and range over them")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--baseline", o.s.baseline,
                   "an engine of --engines (with its settings): every engine's time over its time, round by "
                   "round (median and range)");
    app.add_option("--variants", o.s.variants,
                   "more runs of every engine from jittered starts (free trees moved by up to 2 cm, "
                   "5 mm up, 0.05 rad of yaw): median and largest penetration over them")
        ->check(CLI::Range(0, 1000))
        ->capture_default_str();
    app.add_option("--seed", o.s.seed, "the jitter's seed (--variants)")->capture_default_str();
    app.add_option("--csv", o.csvPath, "write the rows as CSV");
    app.add_option("--markdown", o.markdownPath, "write the rows as a markdown table");
}

// The engines to run (every engine by default), each checked by parseEngine; none (after a
// message) when one is unknown or the baseline is not among them.
std::optional<std::vector<std::string>> engineList(const Options& o)
{
    std::vector<std::string> names = engineNames();
    if (!o.engines.empty())
    {
        names.clear();
        std::stringstream list(o.engines);
        for (std::string name; std::getline(list, name, ',');)
        {
            try
            {
                parseEngine(name);
            }
            catch (const std::invalid_argument& e)
            {
                std::cerr << "frontier_peers: --engines: " << e.what() << "\n";
                return std::nullopt;
            }
            names.push_back(name);
        }
    }
    if (!o.s.baseline.empty() && std::find(names.begin(), names.end(), o.s.baseline) == names.end())
    {
        std::cerr << "frontier_peers: --baseline " << o.s.baseline << " is not among the engines run\n";
        return std::nullopt;
    }
    return names;
}

// The generated chain or the scene file, as `frontier run` loads it; none after a message.
std::optional<core::Model> loadModel(const Options& o)
{
    try
    {
        if (o.chain > 0)
            return chainOfBoxes(o.chain, o.tipRatio);
        // As `frontier run` loads it: a robot's links that overlap at the start never collide.
        run::LoadedScene loaded = run::loadScene(o.scene, {});
        run::printLoadWarnings(loaded.report);
        return std::move(loaded.model);
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier_peers: " << e.what() << "\n";
        return std::nullopt;
    }
}

// Every engine's runs at one time step: the rounds, then the jittered variants.
struct TimeStepRuns
{
    const core::Model& model;
    const std::vector<Pose>& reference;
    const Settings& s;
    std::vector<Row>::iterator begin, end; // the rows of this time step

    // A refused engine, or one stopped by --max-seconds, runs once.
    static bool again(const Row& row) { return !row.rounds.front().refused && !row.rounds.front().timedOut; }
    static EngineOptions grown(const Row& row)
    {
        EngineOptions options;
        options.bufferGrowth = row.rounds.front().bufferGrowth;
        return options;
    }
    static void progress(const Row& row, const EngineRun& run, const std::string& what)
    {
        std::cerr << row.engine << " dt " << row.dt << " s " << what << ": "
                  << (run.steps ? number(1e6 * run.secondsPerStep()) + " us/step" : run.failure) << "\n";
    }

    void rounds() const
    {
        for (int round = 0; round < s.rounds; ++round)
            for (auto row = begin; row != end; ++row)
            {
                if (round > 0 && !again(*row))
                    continue;
                // The first round finds the buffers the scene needs; the others use them.
                EngineRun run = round == 0 ? runGrowingBuffers(row->engine, model, reference, s.run)
                                           : runEngine(row->engine, model, reference, s.run, grown(*row));
                if (round > 0)
                    run.grownAfter = row->rounds.front().grownAfter;
                progress(*row, run, "round " + std::to_string(round + 1));
                row->rounds.push_back(std::move(run));
            }
    }

    void variants(std::vector<core::Model>& variants, double dt) const
    {
        for (std::size_t v = 0; v < variants.size(); ++v)
        {
            variants[v].simulation.dt = dt;
            for (auto row = begin; row != end; ++row)
            {
                if (!again(*row))
                    continue;
                EngineRun run = runGrowingBuffers(row->engine, variants[v], {}, s.run, grown(*row));
                progress(*row, run, "variant " + std::to_string(v + 1));
                row->variants.push_back(std::move(run));
            }
        }
    }
};

// Every engine at every time step, against the reference's end (one for all with --reference-dt).
std::vector<Row> runAll(core::Model& model, std::vector<core::Model>& variants,
                        const std::vector<std::string>& names, const Options& o)
{
    std::vector<Row> rows;
    std::vector<Pose> reference;
    if (o.referenceDt > 0.0)
        reference = referenceEnd(model, o.referenceDt, o.s);
    for (const double dt : o.dts)
    {
        model.simulation.dt = dt;
        if (o.referenceDt <= 0.0)
            reference = referenceEnd(model, dt / o.s.referenceDivisions, o.s);
        const std::size_t first = rows.size();
        for (const std::string& name : names)
            rows.push_back({name, dt, {}, {}});
        const TimeStepRuns runs{model, reference, o.s, rows.begin() + static_cast<std::ptrdiff_t>(first),
                                rows.end()};
        runs.rounds();
        runs.variants(variants, dt);
    }
    return rows;
}

std::vector<Summary> summarizeAll(const std::vector<Row>& rows, const Settings& s)
{
    std::vector<Summary> summaries;
    for (const Row& row : rows)
    {
        const auto baseline = std::find_if(
            rows.begin(), rows.end(), [&](const Row& r) { return r.engine == s.baseline && r.dt == row.dt; });
        summaries.push_back(summarize(row, baseline == rows.end() ? nullptr : &*baseline, s));
    }
    return summaries;
}

// The CSV and the markdown table of every row, a markdown section per time step.
struct Tables
{
    const core::Model& model;
    const Settings& s;
    int n = static_cast<int>(model.bodies.size());
    bool ratios = !s.baseline.empty();
    bool jittered = s.variants > 0;
    std::ostringstream csv{}, md{};

    void csvHeader()
    {
        csv << "scene,bodies,engine,dt_s,steps,us_per_step,us_per_body_step,max_joint_gap_m,"
               "max_penetration_m,energy_change_j,energy_change_percent_of_max_kinetic,error_m,rounds,"
               "us_per_step_min,us_per_step_max,baseline,ratio_to_baseline,ratio_min,ratio_max,variants,"
               "variant_penetration_median_m,variant_penetration_max_m,note\n";
    }

    void markdownHeading(double dt, bool firstSection)
    {
        md << (firstSection ? "" : "\n") << "# " << model.name << " (" << n << " bodies), dt = " << dt
           << " s";
        if (s.rounds > 1)
            md << ", time: the median and range of " << s.rounds << " rounds";
        md << "\n\n| engine | us/step | range";
        if (ratios)
            md << " | over " << s.baseline << " | range";
        md << " | us/body-step | joint gap (m) | penetration (m)";
        if (jittered)
            md << " | penetration over " << s.variants << (s.variants == 1 ? " variant" : " variants")
               << ": median (max) (m)";
        md << " | energy change (% of max kinetic) | error at " << number(s.run.duration, "%g")
           << " s (m) | note |\n|---|---|---";
        md << (ratios ? "|---|---" : "") << "|---|---|---" << (jittered ? "|---" : "") << "|---|---|---|\n";
    }

    void row(const Row& r, const Summary& m)
    {
        const Accuracy& a = m.accuracy;
        const double perStep = m.microsecondsPerStep.median;
        const double gap = m.steps ? a.maxGapM : cNan;
        const double depth = m.steps ? a.maxPenetrationM : cNan;
        csv << csvField(model.name) << "," << n << "," << r.engine << "," << number(r.dt, "%g") << ","
            << m.steps << "," << number(perStep) << "," << number(perStep / n) << "," << number(gap) << ","
            << number(depth) << "," << number(a.energyChangeJ) << "," << number(a.energyChangePercent) << ","
            << number(a.errorM) << "," << r.rounds.size() << "," << number(m.microsecondsPerStep.min) << ","
            << number(m.microsecondsPerStep.max) << "," << s.baseline << "," << number(m.ratio.median) << ","
            << number(m.ratio.min) << "," << number(m.ratio.max) << "," << r.variants.size() << ","
            << number(m.variantPenetrationM.median) << "," << number(m.variantPenetrationM.max) << ","
            << csvField(m.note) << "\n";
        md << "| " << r.engine << " | " << micros(perStep) << " | " << range(m.microsecondsPerStep, micros);
        if (ratios)
            md << " | " << number(m.ratio.median) << " | " << range(m.ratio);
        md << " | " << number(perStep / n) << " | " << number(gap) << " | " << number(depth);
        if (jittered)
            md << " | " << number(m.variantPenetrationM.median)
               << (std::isnan(m.variantPenetrationM.max) ? ""
                                                         : " (" + number(m.variantPenetrationM.max) + ")");
        md << " | " << number(a.energyChangePercent) << " | " << number(a.errorM) << " | " << m.note
           << " |\n";
    }

    void write(const std::vector<Row>& rows, const std::vector<Summary>& summaries)
    {
        csvHeader();
        for (std::size_t i = 0; i < rows.size(); ++i)
        {
            if (i == 0 || rows[i].dt != rows[i - 1].dt)
                markdownHeading(rows[i].dt, i == 0);
            row(rows[i], summaries[i]);
        }
    }
};

// Ends the run early (with its exit code) on a command line that does not hold together.
std::optional<int> refuseOptions(const Options& o)
{
    if (int(!o.scene.empty()) + int(o.chain != 0) + int(!o.mjcfFile.empty()) != 1)
    {
        std::cerr << "frontier_peers: give --scene FILE, --chain N or --mjcf FILE (one of them)\n";
        return 2;
    }
    return std::nullopt;
}

int runMjcf(const Options& o)
{
    MjcfMotionSettings motion;
    motion.duration = o.s.run.duration;
    motion.mujocoDt = motion.frontierDt = o.motionDt;
    return runMjcfComparison(o.mjcfFile, motion, o.noContacts, o.s.rounds, std::cout);
}

// The scene's jittered variants (--variants); none after a message when they cannot be drawn.
std::optional<std::vector<core::Model>> variantsOf(const core::Model& model, const Settings& s)
{
    if (s.variants > 0 && freeTrees(model).empty())
        std::cerr
            << "frontier_peers: --variants: the scene has no free tree to move; every variant is the scene\n";
    try
    {
        return jitteredVariants(model, s.variants, s.seed);
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier_peers: --variants: " << e.what() << "\n";
        return std::nullopt;
    }
}

void writeOutputs(const Options& o, const core::Model& model, const std::vector<Row>& rows)
{
    const std::vector<Summary> summaries = summarizeAll(rows, o.s);
    Tables tables{model, o.s};
    tables.write(rows, summaries);
    std::cout << tables.md.str();
    if (!o.csvPath.empty())
        std::ofstream(o.csvPath) << tables.csv.str();
    if (!o.markdownPath.empty())
        std::ofstream(o.markdownPath) << tables.md.str();
    if (!o.chartDir.empty())
        drawChart(o.chartDir, model, rows, summaries,
                  o.referenceDt > 0.0 ? o.referenceDt : o.dts.back() / o.s.referenceDivisions, o.s,
                  o.chartAccuracy);
}

} // namespace

int runHarness(int argc, char** argv)
{
    CLI::App app{"frontier_peers: one scene in Frontier, Bullet, ODE and MuJoCo at the same dt"};
    Options o;
    addSceneOptions(app, o);
    addRunOptions(app, o);
    addRepeatAndOutputOptions(app, o);
    CLI11_PARSE(app, argc, argv);
    if (const auto code = refuseOptions(o))
        return *code;
    if (!o.mjcfFile.empty())
        return runMjcf(o);
    const auto names = engineList(o);
    if (!names)
        return 2;
    auto model = loadModel(o);
    if (!model)
        return 2;
    if (o.dts.empty())
        o.dts.push_back(model->simulation.dt);
    if (!o.chartDir.empty() && o.chartAccuracy == app::Accuracy::TrajectoryError && o.dts.size() > 1 &&
        o.referenceDt <= 0.0)
    {
        std::cerr
            << "frontier_peers: --chart with several --dt needs --reference-dt (one reference for all)\n";
        return 2;
    }
    auto variants = variantsOf(*model, o.s);
    if (!variants)
        return 1;
    const std::vector<Row> rows = runAll(*model, *variants, *names, o);
    writeOutputs(o, *model, rows);
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
