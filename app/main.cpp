// app/main.cpp: command-line parsing (CLI11) and exit codes of `frontier`.
#include "app/commands.h"
#include "app/model_overrides.h"
#include "app/sweep_chart.h"
#include "core/interrupt.h"
#include "io/input_digest.h"
#include "io/suggest.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace
{
using namespace frontier::app;

// The one rule of every numeric flag: a finite number (no nan, no inf) in its range; a count is a
// whole number, rewritten in digits ("1e3" -> "1000") for the option's integer type. `positive`:
// the range excludes its lower end `low`.
CLI::Validator numberIn(double low, double high, bool positive, bool count, const char* name = nullptr)
{
    return CLI::Validator(
        [=](std::string& value)
        {
            char* end = nullptr;
            const double x = std::strtod(value.c_str(), &end);
            const bool parsed = !value.empty() && end == value.c_str() + value.size();
            if (!parsed || !std::isfinite(x))
            {
                return "expected a finite number, got '" + value + "'";
            }
            char range[96];
            std::snprintf(range, sizeof range,
                          count ? "%s %s %.0f and at most %.0f" : "%s %s %.6g and at most %.6g",
                          count ? "a whole number" : "a number", positive ? "above" : "from", low, high);
            if (x < low || (positive && x == low) || x > high || (count && x != std::floor(x)))
            {
                return std::string("expected ") + range + ", got " + value;
            }
            if (count)
            {
                value = std::to_string(static_cast<long long>(x));
            }
            return std::string();
        },
        name != nullptr ? name : (count ? "INTEGER" : "NUMBER"));
}

// Ranges (README "Commands"): times in seconds, counts bounded where a larger one could only be a
// typo (a run's step count is bounded again from --duration / --dt, run/run_loop.h).
const CLI::Validator cTimeStep = numberIn(0.0, cMaxTimeStepS, true, false); // s
const CLI::Validator cDuration = numberIn(0.0, cMaxDurationS, true, false); // s
const CLI::Validator cStepCount = numberIn(1.0, 1e12, false, true);     // steps (run/run_loop.h cMaxSteps)
const CLI::Validator cIterations = numberIn(1.0, 1e6, false, true);     // solver sweeps
const CLI::Validator cEvery = numberIn(1.0, 2147483647.0, false, true); // steps between rows
const CLI::Validator cFps = numberIn(0.0, 1e6, true, false);            // frames per simulated second
const CLI::Validator cPixels = numberIn(16.0, 16384.0, false, true, "PIXELS"); // frame width
const CLI::Validator cJobs = numberIn(1.0, 256.0, false, true);
const CLI::Validator cTolerance = numberIn(0.0, 1e12, true, false);    // m, rad, m/s, rad/s
const CLI::Validator cDropHeight = numberIn(0.0, 1e6, false, false);   // m
const CLI::Validator cRows = numberIn(1.0, 2147483647.0, false, true); // KKT rows

// An output path given as '' would silently write nothing.
const CLI::Validator cPath([](std::string& value)
                           { return value.empty() ? std::string("expected a path, got ''") : std::string(); },
                           "PATH");

// --height is the frame height; a robot's start height is --drop-height (the names of both are kept
// from the command-line contract), so a height in metres gets pointed there.
const CLI::Validator cFrameHeight(
    [](std::string& value)
    {
        int pixels = 0;
        const bool whole = CLI::detail::lexical_cast(value, pixels);
        if (whole && pixels >= 16 && pixels <= 16384 && cPixels(value).empty())
        {
            return std::string();
        }
        return "--height is the frame height in pixels (16 to 16384), got " + value +
               "; to start a robot higher above the floor, use --drop-height METRES";
    },
    "PIXELS");

// What the scene arguments take (io::loadScene).
constexpr const char* cSceneFiles = "scene .yaml, model .urdf, MJCF .xml, or SDF .sdf/.world/.model";

// Robot flags (README "Robots"): how a .urdf is read and placed.
void addPackagePathOption(CLI::App& command, std::vector<std::string>& packagePaths)
{
    command
        .add_option("--package-path", packagePaths,
                    "where package://NAME/ meshes are: a package, a folder of packages, or NAME=DIR "
                    "(repeatable; searched before ROS_PACKAGE_PATH)")
        ->allow_extra_args(false);
}

// NAME=VALUE with a name and a finite number.
CLI::Validator jointPositionEntry()
{
    return CLI::Validator(
        [](std::string& entry)
        {
            const std::size_t equals = entry.rfind('=');
            if (equals == std::string::npos || equals == 0)
            {
                return "expected NAME=POSITION (a joint of the URDF and rad or m), got " + entry;
            }
            const std::string value = entry.substr(equals + 1);
            char* end = nullptr;
            const double position = std::strtod(value.c_str(), &end);
            return !value.empty() && *end == '\0' && std::isfinite(position)
                       ? std::string()
                       : "expected a finite number after '=' in " + entry;
        },
        "NAME=POSITION");
}

void addRobotOptions(CLI::App& command, frontier::io::UrdfOptions& o)
{
    addPackagePathOption(command, o.packagePaths);
    auto* fixed = command.add_flag("--fixed-base", o.fixedBase, "weld a bare URDF's root link to the world");
    command
        .add_flag("--free-base", o.freeBase, "let a bare URDF's root float even if it is welded to 'world'")
        ->excludes(fixed);
    command
        .add_option(
            "--drop-height", o.dropHeight,
            "a free-floating bare URDF starts with its lowest collision point this high above the floor (m)")
        ->check(cDropHeight);
    command
        .add_option_function<std::vector<std::string>>(
            "--joint-position",
            [&o](const std::vector<std::string>& entries)
            {
                for (const std::string& entry : entries)
                {
                    const std::size_t equals = entry.rfind('=');
                    o.jointPositions[entry.substr(0, equals)] =
                        std::strtod(entry.c_str() + equals + 1, nullptr);
                }
            },
            "a bare URDF's joint starts at this position (rad or m, the URDF's convention), within its "
            "limits; --hold holds it there (repeatable)")
        ->check(jointPositionEntry())
        ->allow_extra_args(false);
    command
        .add_option_function<std::string>(
            "--self-collision", [&o](const std::string& value) { o.selfCollision = value == "on"; },
            "on: links collide unless joined or overlapping at the start (default); off: never")
        ->check(CLI::IsMember({"on", "off"}));
    command.add_option("--keyframe", o.keyframe,
                       "a bare MJCF file starts in this <key> of it (its qpos, qvel and ctrl)");
    command.add_flag("--hold", o.hold,
                     "a position servo on every joint of every URDF robot, holding it where it starts "
                     "(gains from the joint's inertia and effort limit)");
}

// --contact-tolerance and --contact-relative-tolerance: when the contact solve stops (docs/method.md
// §5), over the scene's contact.tolerance and contact.relative_tolerance; ranges by core's rule.
void addContactToleranceOptions(CLI::App& command, frontier::core::ContactTolerances& o,
                                const std::string& which)
{
    // Core's rule on a value numberIn (checked first) found to be a finite number.
    const auto inRange = [](bool (*rule)(double), const char* expected)
    {
        return CLI::Validator(
            [rule, expected](std::string& value)
            {
                return rule(std::strtod(value.c_str(), nullptr))
                           ? std::string()
                           : std::string("expected ") + expected + ", got " + value;
            },
            "");
    };
    command
        .add_option("--contact-tolerance", o.tolerance,
                    "velocity (m/s) to which each contact, limit and loop row is solved " + which +
                        " (default: the scene's contact.tolerance, else 3e-5); larger is faster and "
                        "lets bodies sink and creep more")
        ->check(numberIn(0.0, frontier::core::cMaxContactTolerance, false, false))
        ->check(inRange(frontier::core::isContactTolerance, frontier::core::cContactToleranceRange));
    command
        .add_option("--contact-relative-tolerance", o.relativeTolerance,
                    "fraction of a contact island's starting residual to which it is solved " + which +
                        ", if larger than --contact-tolerance (default: the scene's "
                        "contact.relative_tolerance, else 0)")
        ->check(numberIn(0.0, 1.0, false, false))
        ->check(inRange(frontier::core::isRelativeContactTolerance,
                        frontier::core::cRelativeContactToleranceRange));
}

void addRunOptions(CLI::App& run, RunOptions& o)
{
    run.add_option("scenes", o.scenes, std::string(cSceneFiles) + "; several make a batch run in parallel")
        ->required()
        ->expected(1, -1);
    auto* duration = run.add_option("--duration", o.duration, "simulated time (s)")->check(cDuration);
    run.add_option("--steps", o.steps, "number of steps")->transform(cStepCount)->excludes(duration);
    run.add_option("--dt", o.dt, "time step (s)")->check(cTimeStep);
    run.add_option("--solver", o.solver, "linear | dense | pgs")
        ->check(CLI::IsMember({"linear", "dense", "pgs"}));
    run.add_option("--pgs-iterations", o.pgsIterations, "sweeps of the pgs solver")->transform(cIterations);
    run.add_option("--integrator", o.integrator,
                   "euler | rattle | rattle4 (fourth order, 3 rattle stages a step; a step with contacts "
                   "or joint limits is one rattle step, first order across an impact; order 4 for "
                   "conservative joints only: damping, friction, servos are first order)")
        ->check(CLI::IsMember({"euler", "rattle", "rattle4"}));
    addContactToleranceOptions(run, o.contact, "every step");
    run.add_option("--trajectory", o.trajectory, "write the trajectory CSV here")->check(cPath);
    run.add_option("--record-every", o.recordEvery, "trajectory, joints and contacts rows every K steps")
        ->transform(cEvery);
    run.add_option("--stats", o.stats, "write the run statistics JSON here")->check(cPath);
    run.add_option("--joints", o.joints,
                   "write the joints CSV here: per recorded step and joint coordinate, position, velocity, "
                   "actuator effort, and the force and torque the joint passes to its child")
        ->check(cPath);
    run.add_option(
           "--contacts", o.contacts,
           "write the contacts CSV here: per recorded step and contact, bodies, point, normal, depth, "
           "normal and friction impulse")
        ->check(cPath);
    run.add_option("--frames", o.frames, "write PNG frames into this folder")->check(cPath);
    run.add_option("--fps", o.fps, "frames per simulated second")->check(cFps);
    run.add_option("--width", o.width, "frame width (pixels)")->transform(cPixels);
    run.add_option("--height", o.height, "frame height (pixels)")->check(cFrameHeight);
    run.add_option("--video", o.video, "assemble the frames into this MP4 with ffmpeg")->check(cPath);
    run.add_option("--jobs", o.jobs, "parallel jobs (a batch) or render threads")->transform(cJobs);
    run.add_flag("--quiet", o.quiet, "no summary, no progress");
    run.add_flag("--strict", o.strict,
                 "a warning of the run fails it (exit 1): a passive scene (no actuators, no loads) whose "
                 "energy rose by more than 1% of its scale, or a load that starts after the run's end; "
                 "bodies that start inside each other deeper than contact.start_penetration refuse to start "
                 "(exit 2)");
    addRobotOptions(run, o.urdf);
}
void addSweepOptions(CLI::App& sweep, SweepOptions& o)
{
    sweep.add_option("scene", o.scene, cSceneFiles)->required();
    sweep
        .add_option(
            "--dt", o.dts,
            "time steps (s), comma-separated; default: the scene's dt x 16, 8, 4, 2, 1. Every run must "
            "reach the same sample times, so each must divide a small multiple of the largest")
        ->delimiter(',')
        ->allow_extra_args(false);
    sweep
        .add_option("--solver", o.solvers,
                    "solvers, comma-separated: linear, dense, pgs, pgs:K (K sweeps); default: linear")
        ->delimiter(',')
        ->allow_extra_args(false);
    sweep
        .add_option("--integrator", o.integrators,
                    "integrators, comma-separated: euler, rattle, rattle4; default: euler, rattle")
        ->delimiter(',')
        ->allow_extra_args(false);
    sweep
        .add_option("--duration", o.duration,
                    "simulated time of every run (s); default: the scene's duration, at most 2 s")
        ->check(cDuration);
    addContactToleranceOptions(sweep, o.contact, "in every run but the reference's");
    sweep
        .add_option(
            "--out", o.out,
            "folder for sweep.csv, the chart sweep.png (drawn by gnuplot; without it, sweep.gp to draw it "
            "later) and its data sweep.dat")
        ->required()
        ->check(cPath);
    CLI::Option* referenceCsv =
        sweep.add_option("--reference-csv", o.referenceCsv,
                         "an external reference instead of a reference run: rows t,x,y,z (s, m) of one "
                         "body's centre of mass (an analytic solution, another code), cubic between rows; "
                         "overrides the scene's `reference: {csv: FILE, body: NAME}`");
    sweep.add_option("--reference-body", o.referenceBody, "the body whose positions --reference-csv holds")
        ->needs(referenceCsv);
    sweep
        .add_option_function<std::string>(
            "--chart-accuracy", [&o](const std::string& name) { o.chartAccuracy = accuracyNames().at(name); },
            "the chart's y axis: error (trajectory error, the default), joint-gap or penetration "
            "(largest over the run: for chaotic scenes, where the error ranks nothing)")
        ->check(CLI::IsMember(accuracyNames()));
    referenceCsv->needs("--reference-body");
    addRobotOptions(sweep, o.urdf);
    sweep.footer(
        "Each cell (integrator, solver, dt) is one run, timed, and compared with a reference run: "
        "rattle (rattle4 when the sweep has rattle4; euler when that fails) with the linear solver at "
        "the finest dt / 4, or with the scene's reference or --reference-csv's body. Trajectory "
        "error: the largest centre-of-mass distance (m) to the reference over all moving bodies (that "
        "body alone with --reference-csv) at 20 "
        "sample times spread over the run, the last at its end. Exit codes: 0 done (failed cells are "
        "results), 1 the reference or every cell failed, or gnuplot failed; 2 bad input.");
}
void addBatchOptions(CLI::App& batch, BatchOptions& o)
{
    batch.add_option("plan", o.plan, "the batch plan .yaml (README \"Batches\", docs/batch.md)")->required();
    batch.add_option("--out", o.out, "folder of the batch: jobs/ID/ per job, batch.csv, summary.md, slurm/")
        ->required()
        ->check(cPath);
    batch.add_flag("--list", o.list, "print the jobs (of this shard): id, scene, variation; run nothing");
    auto* shard = batch.add_option("--shard", o.shard,
                                   "run only shard I of N: the jobs whose index mod N is I (0-based)");
    batch
        .add_option_function<std::string>(
            "--shard-from-env",
            [&o](const std::string& value)
            {
                o.shardFromEnv = true;
                o.shardVariable = value;
            },
            "the shard from SLURM_ARRAY_TASK_ID/_COUNT, JOB_COMPLETION_INDEX (count from --shards or the "
            "plan's shards:), or the variable VAR (give it after the plan, or as --shard-from-env=VAR)")
        ->expected(0, 1)
        ->excludes(shard);
    batch
        .add_option("--shards", o.shards, "shard count: the Slurm array's size (default: jobs, at most 100)")
        ->transform(numberIn(1.0, 100000.0, false, true));
    batch.add_option("--jobs", o.jobs, "jobs at a time on this machine")->transform(cJobs);
    auto* merge =
        batch.add_flag("--merge", o.merge, "write DIR/batch.csv and DIR/summary.md from the jobs' stats");
    batch
        .add_option("--chart", o.chart,
                    "with --merge (or --slurm): DIR/chart.png of column Y against column X")
        ->delimiter(',')
        ->expected(2)
        ->allow_extra_args(false);
    auto* slurm =
        batch.add_flag("--slurm", o.slurm, "write DIR/slurm/batch.sbatch (an array job) and merge.sbatch")
            ->excludes(merge);
    batch.add_option("--partition", o.partition, "#SBATCH --partition")->needs(slurm);
    batch.add_option("--time", o.time, "#SBATCH --time (a shard's time limit)")->needs(slurm);
    batch.add_option("--cpus", o.cpus, "#SBATCH --cpus-per-task, and each shard's --jobs")
        ->transform(cJobs)
        ->needs(slurm);
    batch.add_flag("--submit", o.submit, "sbatch both scripts, the merge after the array (afterok)")
        ->needs(slurm);
    batch.add_flag("--quiet", o.quiet, "no line per job");
    addPackagePathOption(batch, o.urdf.packagePaths);
    batch.footer(
        "Jobs go to DIR/jobs/ID/; complete jobs are skipped, each job is locked while it runs. Exit "
        "codes: 0 every job of the shard is done; 1 a job failed (--merge: a job failed or is "
        "missing); 2 a bad plan or flags (PLAN:LINE:COLUMN); 128 + the signal after SIGINT, SIGTERM, "
        "SIGHUP (run again to finish).");
}
} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Frontier: articulated rigid bodies, joint and contact impulses solved exactly in O(n)"};
    app.require_subcommand(1);
    app.option_defaults()->always_capture_default(); // --help shows each option's default
    app.set_version_flag("--version", frontier::io::frontierVersion());

    RunOptions runOptions;
    auto* run = app.add_subcommand("run", "simulate a scene, writing trajectory, statistics and frames");
    addRunOptions(*run, runOptions);

    InfoOptions infoOptions;
    auto* info =
        app.add_subcommand("info", "bodies, joints, degrees of freedom, frontier order, loops, pairs");
    info->add_option("scene", infoOptions.scene, cSceneFiles)->required();
    info->add_flag("--json", infoOptions.json, "machine-readable output");
    addRobotOptions(*info, infoOptions.urdf);

    RenderCommandOptions renderOptions;
    auto* render =
        app.add_subcommand("render", "render recorded trajectories to PNG frames without simulating");
    render->add_option("trajectories", renderOptions.trajectories, "trajectory CSV files (several: a batch)")
        ->required()
        ->expected(1, -1);
    render->add_option("--scene", renderOptions.scene,
                       "the scene (default: the one named in each trajectory)");
    render->add_option("--frames", renderOptions.frames, "folder for the PNG frames")
        ->required()
        ->check(cPath);
    render->add_option("--fps", renderOptions.fps, "frames per simulated second")->check(cFps);
    render->add_option("--width", renderOptions.width, "frame width (pixels)")->transform(cPixels);
    render->add_option("--height", renderOptions.height, "frame height (pixels)")->check(cFrameHeight);
    render->add_option("--video", renderOptions.video, "assemble the frames into this MP4 with ffmpeg")
        ->check(cPath);
    render->add_option("--jobs", renderOptions.jobs, "parallel jobs (a batch) or render threads")
        ->transform(cJobs);
    render->add_flag("--quiet", renderOptions.quiet, "no summary, no progress");
    addPackagePathOption(*render, renderOptions.packagePaths);

    CheckOptions checkOptions;
    auto* check =
        app.add_subcommand("check", "re-simulate a scene and compare with a recorded reference trajectory");
    check->add_option("scene", checkOptions.scene, cSceneFiles)->required();
    check->add_option("--reference", checkOptions.reference, "reference trajectory CSV")->required();
    check->add_option("--tol", checkOptions.positionTolerance, "position tolerance (m)")->check(cTolerance);
    check->add_option("--tol-orientation", checkOptions.orientationTolerance, "orientation tolerance (rad)")
        ->check(cTolerance);
    check->add_option("--tol-velocity", checkOptions.velocityTolerance, "velocity tolerance (m/s)")
        ->check(cTolerance);
    check
        ->add_option("--tol-angular-velocity", checkOptions.angularVelocityTolerance,
                     "angular velocity tolerance (rad/s)")
        ->check(cTolerance);
    check->add_flag("--quiet", checkOptions.quiet, "no progress line");
    addPackagePathOption(*check, checkOptions.packagePaths);

    StabilityOptions stabilityOptions;
    auto* stability = app.add_subcommand(
        "stability", "run scenes with several solvers and integrators: a markdown table of what survives");
    stability->add_option("scenes", stabilityOptions.scenes, "scene .yaml files (scenes/stability/*.yaml)")
        ->required()
        ->expected(1, -1);
    stability
        ->add_option("--methods", stabilityOptions.methods,
                     "solver[:iterations]/integrator, comma-separated (default: linear/euler,"
                     "linear/rattle,dense/euler,pgs:20/euler,pgs:100/euler)")
        ->delimiter(',');
    stability->add_option("--out", stabilityOptions.out, "also write the markdown table here")->check(cPath);
    stability
        ->add_option("--duration", stabilityOptions.duration, "simulated time instead of each scene's (s)")
        ->check(cDuration);
    stability->add_option("--dt", stabilityOptions.dt, "time step instead of each scene's (s)")
        ->check(cTimeStep);
    stability
        ->add_option("--max-dense-rows", stabilityOptions.maxDenseRows,
                     "skip dense runs of larger KKT matrices")
        ->transform(cRows);
    stability->add_flag("--largest-dt", stabilityOptions.largestDt,
                        "also find, per scene and method, the largest time step (halving from 1/30 s, runs "
                        "of at most 1 s) at which the scene still holds");
    stability->add_flag("--quiet", stabilityOptions.quiet, "no progress lines");

    SweepOptions sweepOptions;
    auto* sweep = app.add_subcommand(
        "sweep",
        "speed against accuracy over time steps, solvers and integrators: DIR/sweep.csv, DIR/sweep.png");
    addSweepOptions(*sweep, sweepOptions);

    BatchOptions batchOptions;
    auto* batch = app.add_subcommand(
        "batch",
        "many runs from a plan (scenes x variations): resumable, sharded (Slurm), merged into one CSV");
    addBatchOptions(*batch, batchOptions);

    // A first word that names no command: say so, instead of CLI11's "A subcommand is required".
    if (argc > 1 && argv[1][0] != '-')
    {
        std::vector<std::string> names;
        for (const CLI::App* command : app.get_subcommands({}))
        {
            names.push_back(command->get_name());
        }
        if (std::find(names.begin(), names.end(), argv[1]) == names.end())
        {
            std::cerr << "frontier: unknown command '" << argv[1] << "'"
                      << frontier::io::detail::suggestionSuffix(argv[1], names, true)
                      << "\nRun with --help for more information.\n";
            return cExitBadInput;
        }
    }
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::CallForHelp& e)
    {
        return app.exit(e);
    }
    catch (const CLI::CallForVersion& e)
    {
        return app.exit(e);
    }
    catch (const CLI::ParseError& e)
    {
        app.exit(e);
        return cExitBadInput;
    }
    // A signal at a checkpoint outside the step loop (while loading, core/interrupt.h), where the
    // command has nothing to clean up.
    try
    {
        if (run->parsed())
        {
            return runCommand(runOptions);
        }
        if (check->parsed())
        {
            return checkCommand(checkOptions);
        }
        if (stability->parsed())
        {
            return stabilityCommand(stabilityOptions);
        }
        if (render->parsed())
        {
            return renderCommand(renderOptions);
        }
        if (sweep->parsed())
        {
            return sweepCommand(sweepOptions);
        }
        if (batch->parsed())
        {
            return batchCommand(batchOptions);
        }
        return infoCommand(infoOptions);
    }
    catch (const frontier::core::Interrupted& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return frontier::core::interruptedExitCode(e.signal());
    }
}
