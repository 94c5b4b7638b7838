// app/sweep_command.cpp: `frontier sweep`: parse the lists, run the grid (study/sweep.h), write
// DIR/sweep.csv, print the table, draw DIR/sweep.png (app/sweep_chart.h).
#include "app/commands.h"
#include "app/model_overrides.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "app/sweep_chart.h"
#include "core/simulator.h"
#include "io/atomic_file.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "run/run_loop.h"
#include "run/scene_loading.h"
#include "study/study.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

int fail(const std::string& message, int code)
{
    std::cerr << "frontier: " << message << "\n";
    return code;
}

// A sweep stopped by a signal: the finished cells go to DIR/sweep.failed.csv (the name a stopped
// run's rows take, app/outputs.h), so that nothing under the final names passes for a finished
// sweep; no chart. Returns 128 + the signal.
int interrupted(const SweepOptions& options, const study::SweepResult& result, std::size_t cellCount)
{
    const std::string csv = failedPath((fs::path(options.out) / "sweep.csv").string());
    try
    {
        study::writeSweepCsv(csv, options.scene, result);
    }
    catch (const io::OutputError& e)
    {
        return fail(e.what(), cExitBadInput);
    }
    if (!result.cells.empty())
    {
        std::printf("%s\n", study::formatSweepTable(result, options.chartAccuracy).c_str());
        std::fflush(stdout);
    }
    return fail(run::signalName(result.interruptedBy) + ": the sweep stopped after " +
                    std::to_string(result.cells.size()) + " of " + std::to_string(cellCount) +
                    " cells; the finished ones are in " + csv + " (no chart: a finished sweep draws it)",
                run::interruptedExitCode(result.interruptedBy));
}
} // namespace

int sweepCommand(const SweepOptions& options)
{
    core::Model model;
    study::SweepGrid grid;
    study::SweepSchedule schedule;
    double requestedS = 0.0;
    std::optional<study::ExternalReference> external;
    const fs::path folder(options.out);
    run::installInterruptHandlers();
    try
    {
        const io::detail::InputFileLog reads; // the scene, every file it reads, the reference CSV
        run::LoadedScene loaded = run::loadScene(options.scene, options.urdf);
        run::printLoadWarnings(loaded.report);
        model = std::move(loaded.model);
        grid = study::makeSweepGrid(model, options.dts, options.solvers, options.integrators);
        grid.contact = options.contact;
        requestedS = study::sweepDuration(model, options.duration);
        if (!options.referenceCsv.empty()) // the command line's, else the scene's `reference:`
        {
            external = study::readReferenceCsv(options.referenceCsv, options.referenceBody);
        }
        else if (loaded.report.reference)
        {
            external =
                study::readReferenceCsv(loaded.report.reference->csvPath, loaded.report.reference->body);
        }
        schedule = study::planSchedule(grid.dts, requestedS);
        // The reference run takes the most steps: at the finest dt / study::cReferenceRefinement.
        checkedStepCount(schedule.durationS(),
                         *std::min_element(grid.dts.begin(), grid.dts.end()) / study::cReferenceRefinement,
                         options.scene);
        // None of our files may be one the sweep read; the folder must take them before minutes of
        // simulation are spent.
        const std::string csv = (folder / "sweep.csv").string();
        std::vector<OutputPath> written = {{"--out", csv, false, ""},
                                           {"--out", failedPath(csv), false, "a stopped sweep's cells"}};
        for (const char* name : cSweepChartFiles)
        {
            written.push_back({"--out", (folder / name).string(), false, ""});
        }
        checkInputsKept(written, io::inputPaths(reads.files()));
        for (const OutputPath& file : written)
        {
            io::removeStaleTemporariesOf(file.path); // of a sweep killed outright (SIGKILL)
        }
        fs::create_directories(folder);
        io::AtomicFile probe((folder / "sweep.csv").string()); // removed again, never committed
    }
    catch (const io::InputError& e)
    {
        return fail(e.what(), cExitBadInput);
    }
    catch (const study::SweepInputError& e)
    {
        return fail(e.what(), cExitBadInput);
    }
    catch (const io::OutputError& e)
    {
        return fail(e.what(), cExitBadInput);
    }
    catch (const fs::filesystem_error& e)
    {
        return fail(options.out + ": cannot create the output folder: " + e.code().message(), cExitBadInput);
    }
    if (schedule.durationS() < requestedS * (1.0 - 1e-9))
    {
        std::printf(
            "note: simulating %.9g s instead of %.9g s: the runs end at a multiple of %.9g s, which every "
            "time step reaches\n",
            schedule.durationS(), requestedS, schedule.unitS);
    }

    const bool terminal = stderrIsTerminal();
    int lastPercent = -1;
    int lastIndex = -1;
    const study::SweepProgress progress = [&](const std::string& run, int index, int count, double fraction)
    {
        const int percent = static_cast<int>(100.0 * fraction);
        if (!terminal || (percent == lastPercent && index == lastIndex))
        {
            return;
        }
        lastPercent = percent;
        lastIndex = index;
        std::fprintf(stderr, "\r\033[Ksweep %d/%d  %s  %3d%%", index + 1, count, run.c_str(), percent);
    };
    study::SweepResult result;
    try
    {
        result = study::runSweep(model, grid, schedule, progress, external ? &*external : nullptr);
    }
    catch (const core::UnsupportedModelError& e)
    {
        return fail(options.scene + ": " + e.what(), cExitBadInput);
    }
    catch (const study::SweepInputError& e) // the external reference's body or times
    {
        if (terminal)
        {
            std::fprintf(stderr, "\r\033[K");
        }
        return fail(e.what(), cExitBadInput);
    }
    catch (const study::SweepReferenceError& e)
    {
        if (terminal)
        {
            std::fprintf(stderr, "\r\033[K");
        }
        return fail(options.scene + ": " + e.what(), cExitFailed);
    }
    if (terminal)
    {
        std::fprintf(stderr, "\r\033[K");
    }
    if (result.interruptedBy != 0)
    {
        return interrupted(options, result, grid.integrators.size() * grid.solvers.size() * grid.dts.size());
    }

    const std::string csv = (folder / "sweep.csv").string();
    try
    {
        study::writeSweepCsv(csv, options.scene, result);
        std::error_code ignored; // the cells of an earlier sweep of this folder that was stopped
        fs::remove(failedPath(csv), ignored);
    }
    catch (const io::OutputError& e)
    {
        return fail(e.what(), cExitBadInput);
    }
    std::printf("%s: %d moving bod%s, %.9g s simulated per run\n%s\n\n%s", model.name.c_str(), result.bodies,
                result.bodies == 1 ? "y" : "ies", schedule.durationS(),
                study::describeReference(result).c_str(),
                study::formatSweepTable(result, options.chartAccuracy).c_str());
    std::fflush(stdout);

    const bool anySurvived = std::any_of(result.cells.begin(), result.cells.end(),
                                         [](const study::SweepCell& c) { return c.survived; });
    try
    {
        if (drawSweepChart(options.out, model.name, result, options.chartAccuracy))
        {
            std::printf("Wrote %s and %s (gnuplot script %s).\n", csv.c_str(), (folder / "sweep.png").c_str(),
                        (folder / "sweep.gp").c_str());
        }
        else
        {
            std::printf("Wrote %s and the chart script %s.\n", csv.c_str(), (folder / "sweep.gp").c_str());
            std::cerr
                << "frontier: note: gnuplot is not installed, so there is no chart "
                << (folder / "sweep.png").string()
                << ". Install it (apt-get install gnuplot-nox, or scripts/install-deps.sh), then draw it "
                   "with: cd "
                << folder.string() << " && gnuplot sweep.gp\n";
        }
    }
    catch (const io::OutputError& e)
    {
        return fail(e.what(), cExitBadInput);
    }
    catch (const ChartError& e)
    {
        return fail(e.what() + std::string(" (") + csv + " is written)", cExitFailed);
    }
    if (!anySurvived)
    {
        return fail("no cell of the sweep survived (see the failures above)", cExitFailed);
    }
    return cExitOk;
}

} // namespace frontier::app
