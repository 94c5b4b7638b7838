// app/run_one.h: one scene run as `frontier run` runs it (load, simulate, write the outputs through
// temporary files renamed into place, summarize); also one job of `frontier batch`.
#pragma once

#include "app/commands.h"
#include "app/job_result.h"
#include "app/outputs.h"
#include "run/scene_loading.h"

#include <functional>
#include <string>

namespace frontier::app
{

// Loads the scene of a run; empty: loadScene(scene, options.urdf).
using SceneLoader = std::function<run::LoadedScene()>;

// One run: a scene, the flags it runs with, where its outputs go.
struct RunRequest
{
    RunOptions options; // the flags of `frontier run` (its scene list is not read)
    std::string scene;
    JobOutputs out;
    int renderThreads = 1;
    JobStatus status; // progress lines; empty: none
    SceneLoader load; // empty: run::loadScene(scene, options.urdf)
};

// Runs the request; its exit code (cExitOk, cExitFailed, cExitBadInput, or interruptedExitCode),
// the one-line summary, and the message for the user. A failed run keeps its rows under failedPath
// names and writes stats with "completed": false.
JobResult runOne(const RunRequest& request);

} // namespace frontier::app
