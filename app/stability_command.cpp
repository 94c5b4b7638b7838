// app/stability_command.cpp: `frontier stability`: the stability suite's table (study/stability.h).
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

namespace frontier::app
{

int stabilityCommand(const StabilityOptions& options)
{
    std::vector<run::Method> methods;
    for (const std::string& text : options.methods)
    {
        const auto method = run::parseMethod(text);
        if (!method)
        {
            std::cerr << "frontier: bad method '" << text
                      << "': expected solver[:iterations]/integrator, e.g. linear/euler or pgs:100/euler\n";
            return cExitBadInput;
        }
        methods.push_back(*method);
    }
    if (methods.empty())
    {
        methods = study::defaultStabilityMethods();
    }

    std::vector<core::Model> scenes;
    std::vector<std::string> names;
    study::StabilityReportExtras extras;
    try
    {
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
            scenes.push_back(std::move(loaded.model));
            extras.criteria.push_back(loaded.report.stability.value_or(io::SceneStabilityCriteria{}));
            names.push_back(std::filesystem::path(path).stem().string());
            const core::SimulationSettings& sim = scenes.back().simulation;
            checkedStepCount(options.duration.value_or(sim.duration), options.dt.value_or(sim.dt), path);
        }
        if (!options.out.empty())
        {
            checkInputsKept({{"--out", options.out, false, ""}}, io::inputPaths(reads.files()));
            io::removeStaleTemporariesOf(options.out); // of a run killed outright (SIGKILL)
        }
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
    std::vector<study::StabilityCell> cells;
    for (std::size_t s = 0; s < scenes.size(); ++s)
    {
        for (const run::Method& method : methods)
        {
            if (!options.quiet)
            {
                std::fprintf(stderr, "%s %s ...", names[s].c_str(), method.label().c_str());
                std::fflush(stderr);
            }
            cells.push_back(study::runStabilityCell(scenes[s], names[s], method, limits, extras.criteria[s]));
            const study::StabilityCell& c = cells.back();
            if (!options.quiet)
            {
                std::fprintf(stderr, " %s; gap %.2g m, %.2g rad; energy %+.3g%% / %+.3g%%; %.2f s\n",
                             c.survived() ? "ok" : c.note.c_str(), c.maxJointGapM, c.maxJointGapRad,
                             100.0 * c.energyRise(), -100.0 * c.energyLoss(), c.wallSeconds);
            }
        }
    }

    if (options.largestDt)
    {
        for (std::size_t s = 0; s < scenes.size(); ++s)
        {
            for (const run::Method& method : methods)
            {
                if (!options.quiet)
                {
                    std::fprintf(stderr, "largest dt: %s %s ...", names[s].c_str(), method.label().c_str());
                    std::fflush(stderr);
                }
                extras.largest.push_back(study::largestHoldingDt(scenes[s], names[s], method, limits,
                                                                 extras.criteria[s], extras.search));
                const study::LargestDtCell& c = extras.largest.back();
                if (!options.quiet)
                {
                    std::fprintf(stderr, " %s after %d runs, %.2f s\n",
                                 c.dt ? ("holds at " + std::to_string(*c.dt) + " s").c_str()
                                      : (c.note.empty() ? "-" : c.note.c_str()),
                                 c.runs, c.wallSeconds);
                }
            }
        }
    }

    const std::string table =
        study::stabilityMarkdown(scenes, names, methods, cells, limits, study::machineDescription(), extras);
    std::cout << table;
    if (!options.out.empty())
    {
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
    }
    return cExitOk;
}

} // namespace frontier::app
