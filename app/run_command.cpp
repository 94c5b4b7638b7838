// app/run_command.cpp: `frontier run`: one scene, or several as a batch (app/run_one.h runs each).
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/job_board.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "app/run_one.h"
#include "io/scene.h"
#include "run/run_loop.h"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>

namespace frontier::app
{

namespace
{
// Each scene's output paths; --video's folder for a batch. Throws io::InputError.
std::vector<JobOutputs> planRunOutputs(const RunOptions& options)
{
    std::vector<JobOutputs> outputs =
        planOutputs(options.scenes, {options.trajectory, options.stats, options.frames, options.video,
                                     options.joints, options.contacts});
    if (!options.video.empty() && options.frames.empty())
    {
        throw io::InputError(options.video, 0, 0, "--video needs --frames (the frames it is made from)");
    }
    if (options.scenes.size() > 1 && !options.video.empty())
    {
        std::filesystem::create_directories(options.video);
    }
    return outputs;
}

// One scene: its progress redrawn on a terminal, its summary on stdout, its error on stderr.
int runSingleScene(const RunOptions& options, const JobOutputs& out)
{
    const bool terminal = !options.quiet && stderrIsTerminal();
    bool shown = false;
    RunRequest request{options, options.scenes.front(), out, options.jobs, {}, {}};
    request.status = [&](const std::string& text)
    {
        if (terminal)
        {
            std::fprintf(stderr, "\r\033[K%s", text.c_str());
            shown = true;
        }
    };
    const JobResult result = runOne(request);
    if (shown)
    {
        std::fprintf(stderr, "\r\033[K");
    }
    if (!options.quiet && !result.summary.empty())
    {
        std::printf("%s\n", result.summary.c_str());
    }
    if (!result.error.empty())
    {
        std::cerr << "frontier: " << result.error << "\n";
    }
    return result.exitCode;
}
} // namespace

int runCommand(const RunOptions& options)
{
    std::vector<JobOutputs> outputs;
    try
    {
        outputs = planRunOutputs(options);
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    run::installInterruptHandlers();
    if (options.scenes.size() == 1)
    {
        return runSingleScene(options, outputs.front());
    }
    // A batch: scenes in parallel, one progress line each; a failing job does not stop the others.
    std::vector<std::string> names;
    for (const std::string& scene : options.scenes)
    {
        names.push_back(jobName(scene));
    }
    return runBatch(names, options.jobs, options.quiet,
                    [&](std::size_t job, const JobStatus& status) {
                        return runOne({options, options.scenes[job], outputs[job], 1, status, {}});
                    });
}

namespace
{
void addRunOptions(CLI::App& run, RunOptions& o)
{
    run.add_option("scenes", o.scenes, std::string(cSceneFiles) + "; several make a batch run in parallel")
        ->required()
        ->expected(1, -1);
    auto* duration = run.add_option("--duration", o.duration, "simulated time (s)")->check(cDuration);
    run.add_option("--steps", o.steps, "number of steps")->transform(cStepCount)->excludes(duration);
    run.add_option("--dt", o.dt, "time step (s)")->check(cTimeStep);
    run.add_option("--solver", o.solver, choiceHelp(core::solvers()))
        ->check(CLI::IsMember(core::solverNames()));
    run.add_option("--pgs-iterations", o.pgsIterations, "sweeps of the pgs solver")->transform(cIterations);
    run.add_option("--integrator", o.integrator, choiceHelp(core::integrators()))
        ->check(CLI::IsMember(core::integratorNames()));
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
} // namespace

Command addRunCommand(CLI::App& app)
{
    return addCommand<RunOptions>(app, "run", "simulate a scene, writing trajectory, statistics and frames",
                                  addRunOptions, runCommand);
}

} // namespace frontier::app
