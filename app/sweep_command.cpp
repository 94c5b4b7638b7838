// app/sweep_command.cpp: `frontier sweep`: parse the lists, run the grid (study/sweep.h), write
// DIR/sweep.csv, print the table, draw DIR/sweep.png (app/sweep_chart.h).
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/model_overrides.h"
#include "app/outputs.h"
#include "app/progress.h"
#include "app/sweep_chart.h"
#include "core/simulator.h"
#include "io/atomic_file.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/suggest.h"
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

namespace
{
// What a sweep runs: the scene, its grid of methods and time steps, the sample times.
struct SweepSetup
{
    core::Model model;
    study::SweepGrid grid;
    study::SweepSchedule schedule;
    double requestedS = 0.0; // the duration asked for (s)
    std::optional<study::ExternalReference> external;
};

// None of the sweep's files may be one it read; the folder must take them before minutes of
// simulation are spent. Throws io::InputError, io::OutputError, std::filesystem::filesystem_error.
void prepareSweepFolder(const fs::path& folder, const std::vector<std::string>& inputFiles)
{
    const std::string csv = (folder / "sweep.csv").string();
    std::vector<OutputPath> written = {{"--out", csv, false, ""},
                                       {"--out", failedPath(csv), false, "a stopped sweep's cells"}};
    for (const char* name : cSweepChartFiles)
    {
        written.push_back({"--out", (folder / name).string(), false, ""});
    }
    checkInputsKept(written, inputFiles);
    for (const OutputPath& file : written)
    {
        io::removeStaleTemporariesOf(file.path); // of a sweep killed outright (SIGKILL)
    }
    fs::create_directories(folder);
    io::AtomicFile probe(csv); // removed again, never committed
}

// Loads the scene and the reference, plans the runs, prepares the folder. Throws io::InputError,
// study::SweepInputError, io::OutputError, std::filesystem::filesystem_error.
SweepSetup setUpSweep(const SweepOptions& options)
{
    SweepSetup setup;
    const io::detail::InputFileLog reads; // the scene, every file it reads, the reference CSV
    run::LoadedScene loaded = run::loadScene(options.scene, options.urdf);
    run::printLoadWarnings(loaded.report);
    setup.model = std::move(loaded.model);
    setup.grid = study::makeSweepGrid(setup.model, options.dts, options.solvers, options.integrators);
    setup.grid.contact = options.contact;
    setup.requestedS = study::sweepDuration(setup.model, options.duration);
    if (!options.referenceCsv.empty()) // the command line's, else the scene's `reference:`
    {
        setup.external = study::readReferenceCsv(options.referenceCsv, options.referenceBody);
    }
    else if (loaded.report.reference)
    {
        setup.external =
            study::readReferenceCsv(loaded.report.reference->csvPath, loaded.report.reference->body);
    }
    setup.schedule = study::planSchedule(setup.grid.dts, setup.requestedS);
    // The reference run takes the most steps: at the finest dt / study::cReferenceRefinement.
    checkedStepCount(setup.schedule.durationS(),
                     *std::min_element(setup.grid.dts.begin(), setup.grid.dts.end()) /
                         study::cReferenceRefinement,
                     options.scene);
    prepareSweepFolder(options.out, io::inputPaths(reads.files()));
    return setup;
}

// "sweep 3/12  pgs/euler dt 0.004   40%" on a terminal, redrawn when it changes.
study::SweepProgress sweepProgress(bool terminal)
{
    return [terminal, lastPercent = -1, lastIndex = -1](const std::string& run, int index, int count,
                                                        double fraction) mutable
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
}

void clearProgress(bool terminal)
{
    if (terminal)
    {
        std::fprintf(stderr, "\r\033[K");
    }
}

// DIR/sweep.png drawn by gnuplot, or the note that gnuplot is missing; the exit code.
int drawChart(const SweepOptions& options, const std::string& sceneName, const study::SweepResult& result,
              const std::string& csv)
{
    const fs::path folder(options.out);
    try
    {
        if (drawSweepChart(options.out, sceneName, result, options.chartAccuracy))
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
    return cExitOk;
}

// A finished sweep: DIR/sweep.csv, the table on stdout, the chart; the exit code.
int writeSweep(const SweepOptions& options, const SweepSetup& setup, const study::SweepResult& result)
{
    const std::string csv = (fs::path(options.out) / "sweep.csv").string();
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
    std::printf("%s: %d moving bod%s, %.9g s simulated per run\n%s\n\n%s", setup.model.name.c_str(),
                result.bodies, result.bodies == 1 ? "y" : "ies", setup.schedule.durationS(),
                study::describeReference(result).c_str(),
                study::formatSweepTable(result, options.chartAccuracy).c_str());
    std::fflush(stdout);
    if (const int code = drawChart(options, setup.model.name, result, csv); code != cExitOk)
    {
        return code;
    }
    const bool anySurvived = std::any_of(result.cells.begin(), result.cells.end(),
                                         [](const study::SweepCell& c) { return c.survived; });
    if (!anySurvived)
    {
        return fail("no cell of the sweep survived (see the failures above)", cExitFailed);
    }
    return cExitOk;
}
} // namespace

int sweepCommand(const SweepOptions& options)
{
    SweepSetup setup;
    run::installInterruptHandlers();
    try
    {
        setup = setUpSweep(options);
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
    if (setup.schedule.durationS() < setup.requestedS * (1.0 - 1e-9))
    {
        std::printf("note: simulating %.9g s instead of %.9g s: the runs end at a multiple of %.9g s, which "
                    "every time step reaches\n",
                    setup.schedule.durationS(), setup.requestedS, setup.schedule.unitS);
    }
    const bool terminal = stderrIsTerminal();
    study::SweepResult result;
    try
    {
        result = study::runSweep(setup.model, setup.grid, setup.schedule, sweepProgress(terminal),
                                 setup.external ? &*setup.external : nullptr);
    }
    catch (const core::UnsupportedModelError& e)
    {
        return fail(options.scene + ": " + e.what(), cExitBadInput);
    }
    catch (const study::SweepInputError& e) // the external reference's body or times
    {
        clearProgress(terminal);
        return fail(e.what(), cExitBadInput);
    }
    catch (const study::SweepReferenceError& e)
    {
        clearProgress(terminal);
        return fail(options.scene + ": " + e.what(), cExitFailed);
    }
    clearProgress(terminal);
    if (result.interruptedBy != 0)
    {
        const auto& grid = setup.grid;
        return interrupted(options, result, grid.integrators.size() * grid.solvers.size() * grid.dts.size());
    }
    return writeSweep(options, setup, result);
}

namespace
{
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
                    "solvers, comma-separated: " + io::detail::joinNames(core::solverNames()) +
                        ", pgs:K (K sweeps); default: linear")
        ->delimiter(',')
        ->allow_extra_args(false);
    sweep
        .add_option("--integrator", o.integrators,
                    "integrators, comma-separated: " + io::detail::joinNames(core::integratorNames()) +
                        "; default: euler, rattle")
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
} // namespace

Command addSweepCommand(CLI::App& app)
{
    return addCommand<SweepOptions>(
        app, "sweep",
        "speed against accuracy over time steps, solvers and integrators: DIR/sweep.csv, DIR/sweep.png",
        addSweepOptions, sweepCommand);
}

} // namespace frontier::app
