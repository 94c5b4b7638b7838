// app/render_command.cpp: `frontier render`: frames from recorded trajectories, no simulation.
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

int renderOne(const RenderCommandOptions& options, const std::string& path, const JobOutputs& out,
              int threads, const std::function<void(const std::string&)>& status, std::string& summary,
              std::string& error)
{
    try
    {
        const io::detail::InputFileLog reads; // the trajectory, the scene and every file it reads
        const io::Trajectory trajectory = io::readTrajectory(path);
        std::string scenePath = options.scene;
        if (scenePath.empty())
        {
            const auto found = trajectory.metadata.find("scene");
            if (found == trajectory.metadata.end())
            {
                throw io::InputError(path, 1, 0, "the trajectory names no scene: give --scene");
            }
            scenePath = found->second;
            std::error_code missing;
            if (!std::filesystem::exists(scenePath, missing))
            {
                throw io::InputError(path, 1, 0,
                                     "the trajectory was recorded from scene '" + scenePath +
                                         "', which is not there from this folder (a relative path is "
                                         "read from where frontier runs): give --scene PATH");
            }
        }
        io::UrdfOptions urdf = io::urdfOptionsFrom(trajectory.metadata, path);
        urdf.packagePaths.insert(urdf.packagePaths.begin(), options.packagePaths.begin(),
                                 options.packagePaths.end());
        const core::Model model = run::loadScene(scenePath, urdf).model;
        const std::vector<core::State> states = statesOf(model, trajectory, path);
        std::vector<core::State> frames;
        FrameSampler sampler(options.fps);
        for (const core::State& state : states)
        {
            if (sampler.due(state.time))
            {
                frames.push_back(state);
            }
        }
        checkFrameCount(states.back().time, options.fps, static_cast<double>(frames.size()), path);
        checkInputsKept(outputPathsOf(out), io::inputPaths(reads.files())); // before anything is written
        removeStaleOutputTemporaries(out);
        prepareFrameFolder(out.frames, out.video);
        if (const int code = writeFrames(model, frames, {out.frames, options.width, options.height, threads},
                                         options.fps, out.video, status, error);
            code != cExitOk)
        {
            return code;
        }
        summary = path + ": wrote " + std::to_string(frames.size()) + " frames to " + out.frames +
                  (out.video.empty() ? "" : " and " + out.video);
        return cExitOk;
    }
    catch (const io::InputError& e)
    {
        error = e.what();
    }
    catch (const io::OutputError& e)
    {
        error = e.what();
    }
    return cExitBadInput;
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
                    [&](std::size_t job, const std::function<void(const std::string&)>& status,
                        std::string& summary, std::string& error)
                    {
                        return renderOne(options, options.trajectories[job], outputs[job],
                                         batch ? 1 : options.jobs, status, summary, error);
                    });
}

} // namespace frontier::app
