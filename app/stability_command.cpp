// app/stability_command.cpp: `frontier stability`: the stability suite's table (study/stability.h).
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/model_overrides.h"
#include "app/outputs.h"
#include "io/atomic_file.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "run/scene_loading.h"
#include "study/study.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace frontier::app
{

namespace
{
// --methods parsed; the defaults when none is given. Throws std::invalid_argument naming a bad one.
std::vector<run::Method> stabilityMethods(const std::vector<std::string>& texts)
{
    std::vector<run::Method> methods;
    for (const std::string& text : texts)
    {
        const auto method = run::parseMethod(text);
        if (!method)
        {
            throw std::invalid_argument("bad method '" + text +
                                        "': expected solver[:iterations]/integrator, e.g. linear/euler or "
                                        "pgs:100/euler");
        }
        methods.push_back(*method);
    }
    return methods.empty() ? study::defaultStabilityMethods() : methods;
}

// The scenes of the table, loaded as `frontier run` loads them.
struct StabilityScenes
{
    std::vector<core::Model> models;
    std::vector<std::string> names;
    study::StabilityReportExtras extras; // each scene's criteria
};

// Loads the scenes and checks --out is none of the files they read. Throws io::InputError.
StabilityScenes loadStabilityScenes(const StabilityOptions& options)
{
    StabilityScenes scenes;
    if (!options.out.empty())
    {
        checkOutputPath("--out", options.out, options.scenes);
    }
    const io::detail::InputFileLog reads; // the scenes and every file they read
    for (const std::string& path : options.scenes)
    {
        // As `frontier run` loads it: the links of a robot that overlap at the start never collide.
        run::LoadedScene loaded = run::loadScene(path, {});
        run::printLoadWarnings(loaded.report);
        scenes.models.push_back(std::move(loaded.model));
        scenes.extras.criteria.push_back(loaded.report.stability.value_or(io::SceneStabilityCriteria{}));
        scenes.names.push_back(std::filesystem::path(path).stem().string());
        const core::SimulationSettings& sim = scenes.models.back().simulation;
        checkedStepCount(options.duration.value_or(sim.duration), options.dt.value_or(sim.dt), path);
    }
    if (!options.out.empty())
    {
        checkInputsKept({{"--out", options.out, false, ""}}, io::inputPaths(reads.files()));
        io::removeStaleTemporariesOf(options.out); // of a run killed outright (SIGKILL)
    }
    return scenes;
}

// Each scene with each method, a line per cell on stderr unless quiet.
std::vector<study::StabilityCell> runCells(const StabilityScenes& scenes,
                                           const std::vector<run::Method>& methods,
                                           const study::StabilityLimits& limits, bool quiet)
{
    std::vector<study::StabilityCell> cells;
    for (std::size_t s = 0; s < scenes.models.size(); ++s)
    {
        for (const run::Method& method : methods)
        {
            if (!quiet)
            {
                std::fprintf(stderr, "%s %s ...", scenes.names[s].c_str(), method.label().c_str());
                std::fflush(stderr);
            }
            cells.push_back(study::runStabilityCell(scenes.models[s], scenes.names[s], method, limits,
                                                    scenes.extras.criteria[s]));
            const study::StabilityCell& c = cells.back();
            if (!quiet)
            {
                std::fprintf(stderr, " %s; gap %.2g m, %.2g rad; energy %+.3g%% / %+.3g%%; %.2f s\n",
                             c.survived() ? "ok" : c.note.c_str(), c.maxJointGapM, c.maxJointGapRad,
                             100.0 * c.energyRise(), -100.0 * c.energyLoss(), c.wallSeconds);
            }
        }
    }
    return cells;
}

// --largest-dt: each cell's largest time step that holds, into scenes.extras.largest.
void searchLargestDts(StabilityScenes& scenes, const std::vector<run::Method>& methods,
                      const study::StabilityLimits& limits, bool quiet)
{
    study::StabilityReportExtras& extras = scenes.extras;
    for (std::size_t s = 0; s < scenes.models.size(); ++s)
    {
        for (const run::Method& method : methods)
        {
            if (!quiet)
            {
                std::fprintf(stderr, "largest dt: %s %s ...", scenes.names[s].c_str(),
                             method.label().c_str());
                std::fflush(stderr);
            }
            extras.largest.push_back(study::largestHoldingDt(scenes.models[s], scenes.names[s], method,
                                                             limits, extras.criteria[s], extras.search));
            const study::LargestDtCell& c = extras.largest.back();
            if (!quiet)
            {
                std::fprintf(stderr, " %s after %d runs, %.2f s\n",
                             c.dt ? ("holds at " + std::to_string(*c.dt) + " s").c_str()
                                  : (c.note.empty() ? "-" : c.note.c_str()),
                             c.runs, c.wallSeconds);
            }
        }
    }
}
} // namespace

int stabilityCommand(const StabilityOptions& options)
{
    std::vector<run::Method> methods;
    try
    {
        methods = stabilityMethods(options.methods);
    }
    catch (const std::invalid_argument& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    StabilityScenes scenes;
    try
    {
        scenes = loadStabilityScenes(options);
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    study::StabilityLimits limits;
    limits.duration = options.duration;
    limits.dt = options.dt;
    limits.maxDenseRows = options.maxDenseRows;
    const std::vector<study::StabilityCell> cells = runCells(scenes, methods, limits, options.quiet);
    if (options.largestDt)
    {
        searchLargestDts(scenes, methods, limits, options.quiet);
    }
    const std::string table = study::stabilityMarkdown(scenes.models, scenes.names, methods, cells, limits,
                                                       study::machineDescription(), scenes.extras);
    std::cout << table;
    if (options.out.empty())
    {
        return cExitOk;
    }
    try
    {
        io::AtomicFile file(options.out);
        file.write(table);
        file.commit();
    }
    catch (const io::OutputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    return cExitOk;
}

namespace
{
void addStabilityOptions(CLI::App& command, StabilityOptions& o)
{

    command.add_option("scenes", o.scenes, "scene .yaml files (scenes/stability/*.yaml)")
        ->required()
        ->expected(1, -1);
    command
        .add_option("--methods", o.methods,
                    "solver[:iterations]/integrator, comma-separated (default: linear/euler,"
                    "linear/rattle,dense/euler,pgs:20/euler,pgs:100/euler)")
        ->delimiter(',');
    command.add_option("--out", o.out, "also write the markdown table here")->check(cPath);
    command.add_option("--duration", o.duration, "simulated time instead of each scene's (s)")
        ->check(cDuration);
    command.add_option("--dt", o.dt, "time step instead of each scene's (s)")->check(cTimeStep);
    command.add_option("--max-dense-rows", o.maxDenseRows, "skip dense runs of larger KKT matrices")
        ->transform(cRows);
    command.add_flag("--largest-dt", o.largestDt,
                     "also find, per scene and method, the largest time step (halving from 1/30 s, runs "
                     "of at most 1 s) at which the scene still holds");
    command.add_flag("--quiet", o.quiet, "no progress lines");
}
} // namespace

Command addStabilityCommand(CLI::App& app)
{
    return addCommand<StabilityOptions>(
        app, "stability",
        "run scenes with several solvers and integrators: a markdown table of what survives",
        addStabilityOptions, stabilityCommand);
}

} // namespace frontier::app
