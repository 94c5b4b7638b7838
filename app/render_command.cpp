// app/render_command.cpp: `frontier render`: frames from recorded trajectories, no simulation.
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/frames.h"
#include "app/job_board.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "io/atomic_file.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/trajectory.h"
#include "run/run_loop.h"
#include "run/scene_loading.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

namespace frontier::app
{

namespace
{
// The recorded states, one per recorded time, with static bodies at their scene pose. Throws
// io::InputError when the trajectory does not fit the scene.
std::vector<core::State> statesOf(const core::Model& model, const io::Trajectory& trajectory,
                                  const std::string& path)
{
    std::map<std::string, int> bodyIndex;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            bodyIndex[model.bodies[i].name] = static_cast<int>(i);
        }
    }
    const core::State initial = core::initialState(model);
    std::vector<core::State> states;
    std::vector<bool> seen;
    auto closeState = [&](double time)
    {
        for (const auto& [name, index] : bodyIndex)
        {
            if (!seen[static_cast<std::size_t>(index)])
            {
                throw io::InputError(path, 0, 0,
                                     "the scene's body '" + name +
                                         "' is missing at t = " + std::to_string(time) +
                                         " s: the trajectory does not fit the scene " + model.sourceFile);
            }
        }
    };
    for (const io::TrajectoryRow& row : trajectory.rows)
    {
        if (states.empty() || row.time != states.back().time)
        {
            if (!states.empty())
            {
                closeState(states.back().time);
            }
            states.push_back(initial);
            states.back().time = row.time;
            states.back().step = static_cast<long>(states.size()) - 1;
            seen.assign(model.bodies.size(), false);
        }
        const auto found = bodyIndex.find(row.body);
        if (found == bodyIndex.end())
        {
            throw io::InputError(path, 0, 0,
                                 "body '" + row.body + "' at t = " + std::to_string(row.time) +
                                     " s is not a moving body of the scene " + model.sourceFile);
        }
        states.back().bodies[static_cast<std::size_t>(found->second)] = row.state();
        seen[static_cast<std::size_t>(found->second)] = true;
    }
    if (states.empty())
    {
        throw io::InputError(path, 0, 0, "the trajectory has no rows");
    }
    closeState(states.back().time);
    return states;
}

// The scene the trajectory was recorded from, as its header names it. Throws io::InputError.
std::string recordedScene(const io::Trajectory& trajectory, const std::string& path)
{
    const auto found = trajectory.metadata.find("scene");
    if (found == trajectory.metadata.end())
    {
        throw io::InputError(path, 1, 0, "the trajectory names no scene: give --scene");
    }
    const std::string& scenePath = found->second;
    std::error_code missing;
    if (!std::filesystem::exists(scenePath, missing))
    {
        throw io::InputError(path, 1, 0,
                             "the trajectory was recorded from scene '" + scenePath +
                                 "', which is not there from this folder (a relative path is "
                                 "read from where frontier runs): give --scene PATH");
    }
    return scenePath;
}

// The states the frames show, at `fps` per simulated second (app/frames.h).
std::vector<core::State> sampleFrames(const std::vector<core::State>& states, double fps)
{
    std::vector<core::State> frames;
    FrameSampler sampler(fps);
    for (const core::State& state : states)
    {
        if (sampler.due(state.time))
        {
            frames.push_back(state);
        }
    }
    return frames;
}

JobResult renderOne(const RenderCommandOptions& options, const std::string& path, const JobOutputs& out,
                    int threads, const JobStatus& status)
{
    try
    {
        const io::detail::InputFileLog reads; // the trajectory, the scene and every file it reads
        const io::Trajectory trajectory = io::readTrajectory(path);
        const std::string scenePath = options.scene.empty() ? recordedScene(trajectory, path) : options.scene;
        io::UrdfOptions urdf = io::urdfOptionsFrom(trajectory.metadata, path);
        urdf.packagePaths.insert(urdf.packagePaths.begin(), options.packagePaths.begin(),
                                 options.packagePaths.end());
        const core::Model model = run::loadScene(scenePath, urdf).model;
        const std::vector<core::State> states = statesOf(model, trajectory, path);
        const std::vector<core::State> frames = sampleFrames(states, options.fps);
        checkFrameCount(states.back().time, options.fps, static_cast<double>(frames.size()), path);
        checkInputsKept(outputPathsOf(out), io::inputPaths(reads.files())); // before anything is written
        removeStaleOutputTemporaries(out);
        prepareFrameFolder(out.frames, out.video);
        JobResult result = writeFrames(model, frames, {out.frames, options.width, options.height, threads},
                                       options.fps, out.video, status);
        if (result.exitCode == cExitOk)
        {
            result.summary = path + ": wrote " + std::to_string(frames.size()) + " frames to " + out.frames +
                             (out.video.empty() ? "" : " and " + out.video);
        }
        return result;
    }
    catch (const io::InputError& e)
    {
        return failedJob(cExitBadInput, e.what());
    }
    catch (const io::OutputError& e)
    {
        return failedJob(cExitBadInput, e.what());
    }
}
} // namespace

int renderCommand(const RenderCommandOptions& options)
{
    std::vector<JobOutputs> outputs;
    try
    {
        JobOutputs given;
        given.frames = options.frames;
        given.video = options.video;
        outputs = planOutputs(options.trajectories, given);
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    std::vector<std::string> names;
    for (const std::string& path : options.trajectories)
    {
        names.push_back(jobName(path));
    }
    // One trajectory: its frames on all render threads; several: one job per trajectory.
    run::installInterruptHandlers();
    const bool batch = options.trajectories.size() > 1;
    return runBatch(names, batch ? options.jobs : 1, options.quiet,
                    [&](std::size_t job, const JobStatus& status) {
                        return renderOne(options, options.trajectories[job], outputs[job],
                                         batch ? 1 : options.jobs, status);
                    });
}

namespace
{
void addRenderOptions(CLI::App& command, RenderCommandOptions& o)
{

    command.add_option("trajectories", o.trajectories, "trajectory CSV files (several: a batch)")
        ->required()
        ->expected(1, -1);
    command.add_option("--scene", o.scene, "the scene (default: the one named in each trajectory)");
    command.add_option("--frames", o.frames, "folder for the PNG frames")->required()->check(cPath);
    command.add_option("--fps", o.fps, "frames per simulated second")->check(cFps);
    command.add_option("--width", o.width, "frame width (pixels)")->transform(cPixels);
    command.add_option("--height", o.height, "frame height (pixels)")->check(cFrameHeight);
    command.add_option("--video", o.video, "assemble the frames into this MP4 with ffmpeg")->check(cPath);
    command.add_option("--jobs", o.jobs, "parallel jobs (a batch) or render threads")->transform(cJobs);
    command.add_flag("--quiet", o.quiet, "no summary, no progress");
    addPackagePathOption(command, o.packagePaths);
}
} // namespace

Command addRenderCommand(CLI::App& app)
{
    return addCommand<RenderCommandOptions>(app, "render",
                                            "render recorded trajectories to PNG frames without simulating",
                                            addRenderOptions, renderCommand);
}

} // namespace frontier::app
