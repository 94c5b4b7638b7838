// app/run_one.h: one scene run as `frontier run` runs it (load, simulate, write the outputs through
// temporary files renamed into place, summarize); also one job of `frontier batch`.
#pragma once

#include "app/commands.h"
#include "app/outputs.h"
#include "run/scene_loading.h"

#include <functional>
#include <string>

namespace frontier::app
{

// Loads the scene of a run; empty: loadScene(scene, options.urdf).
using SceneLoader = std::function<run::LoadedScene()>;

// Runs `scene` with the flags of `options` into `out`; returns its exit code (cExitOk, cExitFailed,
// cExitBadInput, or interruptedExitCode). Progress goes to `status`, the one-line summary to
// `summaryText`, messages for the user to `error`. A failed run keeps its rows under failedPath
// names and writes stats with "completed": false.
int runOne(const RunOptions& options, const std::string& scene, const JobOutputs& out, int renderThreads,
           const std::function<void(const std::string&)>& status, std::string& summaryText,
           std::string& error, const SceneLoader& load = {});

} // namespace frontier::app
