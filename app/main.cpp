// app/main.cpp: command-line parsing (CLI11) and exit codes of `frontier`.
#include "app/commands.h"

#include <CLI/CLI.hpp>
#include <iostream>

namespace
{
using namespace frontier::app;

// --height is the frame height; a robot's start height is --drop-height (the names of both are kept
// from the command-line contract), so a height in metres gets pointed there.
const CLI::Validator cFrameHeight(
    [](std::string& value)
    {
        int pixels = 0;
        const bool whole = CLI::detail::lexical_cast(value, pixels);
        if (whole && pixels >= 16 && pixels <= 16384)
        {
            return std::string();
        }
        return "--height is the frame height in pixels (16 to 16384), got " + value +
               "; to start a robot higher above the floor, use --drop-height METRES";
    },
    "PIXELS");

// Robot flags (README "Robots"): how a .urdf is read and placed.
void addPackagePathOption(CLI::App& command, std::vector<std::string>& packagePaths)
{
    command
        .add_option("--package-path", packagePaths,
                    "where package://NAME/ meshes are: a package, a folder of packages, or NAME=DIR "
                    "(repeatable; searched before ROS_PACKAGE_PATH)")
        ->allow_extra_args(false);
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
        ->check(CLI::NonNegativeNumber);
    command
        .add_option_function<std::string>(
            "--self-collision", [&o](const std::string& value) { o.selfCollision = value == "on"; },
            "on: links collide unless joined or overlapping at the start (default); off: never")
        ->check(CLI::IsMember({"on", "off"}));
    command.add_flag("--hold", o.hold,
                     "a position servo on every joint of every URDF robot, holding it where it starts "
                     "(gains from the joint's inertia and effort limit)");
}

void addRunOptions(CLI::App& run, RunOptions& o)
{
    run.add_option("scenes", o.scenes, "scene .yaml or model .urdf; several make a batch run in parallel")
        ->required()
        ->expected(1, -1);
    auto* duration =
        run.add_option("--duration", o.duration, "simulated time (s)")->check(CLI::PositiveNumber);
    run.add_option("--steps", o.steps, "number of steps")->check(CLI::PositiveNumber)->excludes(duration);
    run.add_option("--dt", o.dt, "time step (s)")->check(CLI::PositiveNumber);
    run.add_option("--solver", o.solver, "linear | dense | pgs")
        ->check(CLI::IsMember({"linear", "dense", "pgs"}));
    run.add_option("--pgs-iterations", o.pgsIterations, "sweeps of the pgs solver")
        ->check(CLI::PositiveNumber);
    run.add_option("--integrator", o.integrator,
                   "euler | rattle | rattle4 (fourth order, 3 rattle stages a step; a step with contacts "
                   "or joint limits is one rattle step, first order across an impact; order 4 for "
                   "conservative joints only: damping, friction, servos are first order)")
        ->check(CLI::IsMember({"euler", "rattle", "rattle4"}));
    run.add_option("--trajectory", o.trajectory, "write the trajectory CSV here");
    run.add_option("--record-every", o.recordEvery, "trajectory, joints and contacts rows every K steps")
        ->check(CLI::PositiveNumber);
    run.add_option("--stats", o.stats, "write the run statistics JSON here");
    run.add_option("--joints", o.joints,
                   "write the joints CSV here: per recorded step and joint coordinate, position, velocity, "
                   "actuator effort, and the force and torque the joint passes to its child");
    run.add_option(
        "--contacts", o.contacts,
        "write the contacts CSV here: per recorded step and contact, bodies, point, normal, depth, "
        "normal and friction impulse");
    run.add_option("--frames", o.frames, "write PNG frames into this folder");
    run.add_option("--fps", o.fps, "frames per simulated second")->check(CLI::PositiveNumber);
    run.add_option("--width", o.width, "frame width (pixels)")->check(CLI::Range(16, 16384));
    run.add_option("--height", o.height, "frame height (pixels)")->check(cFrameHeight);
    run.add_option("--video", o.video, "assemble the frames into this MP4 with ffmpeg");
    run.add_option("--jobs", o.jobs, "parallel jobs (a batch) or render threads")->check(CLI::Range(1, 256));
    run.add_flag("--quiet", o.quiet, "no summary, no progress");
    addRobotOptions(run, o.urdf);
}
void addSweepOptions(CLI::App& sweep, SweepOptions& o)
{
    sweep.add_option("scene", o.scene, "scene .yaml or model .urdf")->required();
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
        ->check(CLI::PositiveNumber);
    sweep
        .add_option(
            "--out", o.out,
            "folder for sweep.csv, the chart sweep.png (drawn by gnuplot; without it, sweep.gp to draw it "
            "later) and its data sweep.dat")
        ->required();
    addRobotOptions(sweep, o.urdf);
    sweep.footer(
        "Each cell (integrator, solver, dt) is one run, timed, and compared with a reference run: "
        "rattle (rattle4 when the sweep has rattle4; euler when that fails) with the linear solver at "
        "the finest dt / 4. Trajectory "
        "error: the largest centre-of-mass distance (m) to the reference over all moving bodies at 20 "
        "sample times spread over the run, the last at its end. Exit codes: 0 done (failed cells are "
        "results), 1 the reference or every cell failed, or gnuplot failed; 2 bad input.");
}
} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Frontier: articulated rigid bodies, joint and contact impulses solved exactly in O(n)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "frontier 0.1.0");

    RunOptions runOptions;
    auto* run = app.add_subcommand("run", "simulate a scene, writing trajectory, statistics and frames");
    addRunOptions(*run, runOptions);

    InfoOptions infoOptions;
    auto* info =
        app.add_subcommand("info", "bodies, joints, degrees of freedom, frontier order, loops, pairs");
    info->add_option("scene", infoOptions.scene, "scene .yaml or model .urdf")->required();
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
    render->add_option("--frames", renderOptions.frames, "folder for the PNG frames")->required();
    render->add_option("--fps", renderOptions.fps, "frames per simulated second")->check(CLI::PositiveNumber);
    render->add_option("--width", renderOptions.width, "frame width (pixels)")->check(CLI::Range(16, 16384));
    render->add_option("--height", renderOptions.height, "frame height (pixels)")->check(cFrameHeight);
    render->add_option("--video", renderOptions.video, "assemble the frames into this MP4 with ffmpeg");
    render->add_option("--jobs", renderOptions.jobs, "parallel jobs (a batch) or render threads")
        ->check(CLI::Range(1, 256));
    render->add_flag("--quiet", renderOptions.quiet, "no summary, no progress");
    addPackagePathOption(*render, renderOptions.packagePaths);

    CheckOptions checkOptions;
    auto* check =
        app.add_subcommand("check", "re-simulate a scene and compare with a recorded reference trajectory");
    check->add_option("scene", checkOptions.scene, "scene .yaml or model .urdf")->required();
    check->add_option("--reference", checkOptions.reference, "reference trajectory CSV")->required();
    check->add_option("--tol", checkOptions.positionTolerance, "position tolerance (m)")
        ->check(CLI::PositiveNumber);
    check->add_option("--tol-orientation", checkOptions.orientationTolerance, "orientation tolerance (rad)")
        ->check(CLI::PositiveNumber);
    check->add_option("--tol-velocity", checkOptions.velocityTolerance, "velocity tolerance (m/s)")
        ->check(CLI::PositiveNumber);
    check
        ->add_option("--tol-angular-velocity", checkOptions.angularVelocityTolerance,
                     "angular velocity tolerance (rad/s)")
        ->check(CLI::PositiveNumber);
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
    stability->add_option("--out", stabilityOptions.out, "also write the markdown table here");
    stability
        ->add_option("--duration", stabilityOptions.duration, "simulated time instead of each scene's (s)")
        ->check(CLI::PositiveNumber);
    stability->add_option("--dt", stabilityOptions.dt, "time step instead of each scene's (s)")
        ->check(CLI::PositiveNumber);
    stability
        ->add_option("--max-dense-rows", stabilityOptions.maxDenseRows,
                     "skip dense runs of larger KKT matrices")
        ->check(CLI::PositiveNumber);
    stability->add_flag("--quiet", stabilityOptions.quiet, "no progress lines");

    SweepOptions sweepOptions;
    auto* sweep = app.add_subcommand(
        "sweep",
        "speed against accuracy over time steps, solvers and integrators: DIR/sweep.csv, DIR/sweep.png");
    addSweepOptions(*sweep, sweepOptions);

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
    return infoCommand(infoOptions);
}
