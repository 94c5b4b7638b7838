// app/run_one.cpp: one scene of `frontier run` (and one job of `frontier batch`): load, simulate,
// record, summarize.
#include "app/run_one.h"

#include "app/frames.h"
#include "app/model_overrides.h"
#include "app/progress.h"
#include "app/step_outputs.h"
#include "core/impulse_solver.h"
#include "io/atomic_file.h"
#include "io/scene.h"
#include "io/stats.h"
#include "io/trajectory.h"
#include "run/run_loop.h"
#include "run/run_stats.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace frontier::app
{

namespace
{
int movingBodies(const core::Model& model)
{
    int n = 0;
    for (const core::Body& body : model.bodies)
    {
        n += body.isStatic ? 0 : 1;
    }
    return n;
}

int constraintRows(const core::Model& model)
{
    int rows = 0;
    for (const core::Joint& joint : model.joints)
    {
        rows += core::jointRowCount(joint.type);
    }
    return rows;
}

std::string formatSummary(const core::Model& model, const run::RunSummary& s)
{
    const double simulated = static_cast<double>(s.steps) * model.simulation.dt;
    const double perStep = s.steps > 0 ? s.wallSeconds / static_cast<double>(s.steps) : 0.0;
    const double change = s.energyFinalJ - s.energyInitialJ;
    // A relative change needs a start to be relative to: near zero (a robot at the height where its
    // potential energy is zero) the change is given in joules.
    char changeText[64];
    if (std::abs(s.energyInitialJ) > 1e-9 * std::max(1.0, std::abs(s.energyFinalJ)))
    {
        std::snprintf(changeText, sizeof changeText, "%+.3g%%", 100.0 * change / std::abs(s.energyInitialJ));
    }
    else
    {
        std::snprintf(changeText, sizeof changeText, "%+.3g J", change);
    }
    char text[1024];
    std::snprintf(
        text, sizeof text,
        "%s: %ld steps of %g s (%.3f s simulated) in %.3f s wall, %.2f us per step (%.1fx real time); "
        "%d bodies, %zu joints, %d constraint rows; largest joint error %.3g m, %.3g rad; "
        "energy %.6g J -> %.6g J (%s); max contacts %d, max penetration %.3g m%s",
        model.name.c_str(), s.steps, model.simulation.dt, simulated, s.wallSeconds, perStep * 1e6,
        s.wallSeconds > 0 ? simulated / s.wallSeconds : 0.0, movingBodies(model), model.joints.size(),
        constraintRows(model), s.maxJointErrorM, s.maxJointErrorRad, s.energyInitialJ, s.energyFinalJ,
        changeText, s.maxContacts, s.maxPenetrationM, s.completed ? "." : "; the run FAILED.");
    return text;
}

// A run loaded, its step count set, its output files opened as temporaries.
struct PreparedRun
{
    core::Model model;
    long steps = 0;
    io::TrajectoryMetadata metadata;
    std::unique_ptr<io::TrajectoryWriter> trajectory;
    std::unique_ptr<StepOutputs> stepOutputs; // --joints, --contacts
    std::vector<std::string> inputFiles;      // read by the load
};

// The scene loaded, the flags applied (a note when --duration was rounded to whole steps).
// Throws io::InputError, io::OutputError, core::Interrupted.
PreparedRun loadRun(const RunRequest& r)
{
    const RunOptions& options = r.options;
    run::LoadedScene loaded = r.load ? r.load() : run::loadScene(r.scene, options.urdf);
    PreparedRun prepared;
    prepared.inputFiles = io::inputPaths(loaded.report.inputFiles);
    checkInputsKept(outputPathsOf(r.out), prepared.inputFiles); // before anything is written
    if (options.strict && loaded.startPenetration)
    {
        throw io::InputError(r.scene, 0, 0, "--strict: " + run::startPenetrationText(loaded));
    }
    if (!options.quiet)
    {
        run::printLoadWarnings(loaded.report);
    }
    prepared.model = std::move(loaded.model);
    const double asked = options.duration.value_or(prepared.model.simulation.duration); // s
    prepared.steps = applyOverrides(options, prepared.model);
    const std::string note = options.steps || options.quiet
                                 ? ""
                                 : roundedDurationNote(asked, prepared.steps, prepared.model.simulation.dt);
    if (!note.empty())
    {
        std::fprintf(stderr, "frontier: %s: note: %s\n", r.scene.c_str(), note.c_str());
    }
    if (!r.out.frames.empty())
    {
        checkFrameCount(prepared.model.simulation.duration, r.options.fps,
                        static_cast<double>(prepared.steps) + 1.0, r.scene);
    }
    prepared.metadata =
        io::makeTrajectoryMetadata(r.scene, prepared.model.simulation, prepared.steps, options.recordEvery);
    io::addUrdfOptions(prepared.metadata, options.urdf);
    io::addContactTolerances(prepared.metadata, options.contact);
    return prepared;
}

// The output files opened as temporaries (and the frames folder prepared), before the first step.
// Throws io::OutputError, std::filesystem::filesystem_error.
void openOutputs(const JobOutputs& out, PreparedRun& prepared)
{
    for (const std::string* file : {&out.trajectory, &out.joints, &out.contacts, &out.stats})
    {
        if (!file->empty())
        {
            io::makeFolderFor(*file);
        }
    }
    removeStaleOutputTemporaries(out); // of a run killed outright (SIGKILL)
    if (!out.stats.empty())
    {
        io::AtomicFile probe(out.stats); // the stats can be written (removed again, never committed)
    }
    if (!out.trajectory.empty())
    {
        prepared.trajectory = std::make_unique<io::TrajectoryWriter>(out.trajectory, prepared.metadata);
    }
    if (!out.joints.empty() || !out.contacts.empty())
    {
        prepared.stepOutputs = std::make_unique<StepOutputs>(out.joints, out.contacts, prepared.metadata);
    }
    if (!out.frames.empty())
    {
        prepareFrameFolder(out.frames, out.video);
    }
}

// What the simulation gave: its summary and the states sampled for frames.
struct SimulatedRun
{
    run::RunSummary summary;
    std::vector<core::State> frames;
};

// "simulating  40%  t = ..." to `status` whenever the percentage changes.
std::function<void(long)> simulationProgress(const JobStatus& status, long steps, double dt)
{
    return [status, steps, dt, lastShown = -1L](long step) mutable
    {
        const long percent = 100 * step / std::max(1L, steps);
        if (percent != lastShown)
        {
            lastShown = percent;
            char text[96];
            std::snprintf(text, sizeof text, "simulating %3ld%%  t = %.3f / %.3f s", percent,
                          static_cast<double>(step) * dt, static_cast<double>(steps) * dt);
            status(text);
        }
    };
}

// Steps the run, recording rows and frames as it goes. A singular joint at the start or a signal
// before the first step ends it as failed. Throws core::UnsupportedModelError, io::OutputError.
SimulatedRun simulate(const RunRequest& r, PreparedRun& prepared)
{
    SimulatedRun result;
    FrameSampler sampler(r.options.fps);
    const run::Recorder record = [&](const core::State& state, const core::Simulator* lastStep)
    {
        const bool due = state.step % r.options.recordEvery == 0;
        if (prepared.trajectory && due)
        {
            prepared.trajectory->writeState(prepared.model, state);
        }
        if (prepared.stepOutputs && due)
        {
            prepared.stepOutputs->record(prepared.model, state, lastStep);
        }
        if (!r.out.frames.empty() && sampler.due(state.time))
        {
            result.frames.push_back(state);
        }
    };
    run::RunSettings settings;
    settings.steps = prepared.steps;
    settings.progress = simulationProgress(r.status, prepared.steps, prepared.model.simulation.dt);
    try
    {
        result.summary = run::runSimulation(prepared.model, settings, record);
    }
    catch (const core::SingularJointError& e) // singular at the start (the simulator's construction)
    {
        result.summary.completed = false;
        result.summary.failure = e.what();
    }
    catch (const core::Interrupted& e) // a signal while setting up, before the first step
    {
        result.summary.completed = false;
        result.summary.interruptedBy = e.signal();
        result.summary.failure = std::string(e.what()) + " before the first step";
    }
    return result;
}

// The warnings of a run: loads that start after its end; a passive scene that gained energy (the
// step was too large for it, or worse).
std::vector<std::string> runWarnings(const PreparedRun& prepared, const run::RunSummary& summary)
{
    const double rise = run::passiveEnergyRise(prepared.model, summary);
    std::vector<std::string> warnings =
        loadsAfterTheEnd(prepared.model, static_cast<double>(prepared.steps) * prepared.model.simulation.dt);
    if (rise > run::cEnergyGainTolerance)
    {
        char text[256];
        std::snprintf(
            text, sizeof text,
            "the energy of this passive scene (no actuators, no loads) rose by %.3g J, %.3g%% of its "
            "scale %.3g J (tolerance %g%%): a smaller dt or --integrator rattle may hold it",
            summary.energyMaxJ - summary.energyInitialJ, 100.0 * rise, summary.energyScaleJ,
            100.0 * run::cEnergyGainTolerance);
        warnings.push_back(text);
    }
    return warnings;
}

// Renames the rows and writes the stats; a run that failed (`failure` not empty) keeps its rows up
// to the failure under names that say so (failedPath). Returns the files written. Throws
// io::OutputError.
std::vector<std::string> commitOutputs(const RunRequest& r, PreparedRun& prepared,
                                       const run::RunSummary& summary,
                                       const std::vector<std::string>& warnings, const std::string& failure)
{
    const bool ok = failure.empty();
    std::vector<std::string> written;
    if (prepared.trajectory)
    {
        written.push_back(ok ? r.out.trajectory : failedPath(r.out.trajectory));
        prepared.trajectory->commitAs(written.back());
    }
    if (prepared.stepOutputs)
    {
        if (ok)
        {
            prepared.stepOutputs->commit();
        }
        else
        {
            for (const std::string& file : prepared.stepOutputs->commitFailed())
            {
                written.push_back(file);
            }
        }
    }
    if (!r.out.stats.empty())
    {
        io::RunStats stats = run::runStats(r.scene, prepared.model, summary);
        stats.completed = ok;
        stats.failure = failure;
        stats.warnings = warnings;
        if (!r.options.inputsDigest.empty())
        {
            stats.inputsDigest = r.options.inputsDigest;
            stats.inputFiles = prepared.inputFiles;
        }
        io::writeStats(r.out.stats, stats);
        written.push_back(r.out.stats);
    }
    return written;
}

// The summary line with the warnings and frames, and for a failed run the message naming what it
// kept (every file of a failed run says so: rows under .failed names, stats with "completed": false).
JobResult finishedRun(const RunRequest& r, const PreparedRun& prepared, const SimulatedRun& simulated,
                      const std::vector<std::string>& warnings, const std::string& failure,
                      const std::vector<std::string>& written)
{
    const bool ok = failure.empty();
    const run::RunSummary& summary = simulated.summary;
    JobResult result;
    result.summary = formatSummary(prepared.model, summary);
    for (const std::string& warning : warnings)
    {
        result.summary += " Warning: " + warning + ".";
    }
    if (!r.out.frames.empty() && ok)
    {
        result.summary +=
            " Wrote " + std::to_string(simulated.frames.size()) + " frames to " + r.out.frames + ".";
    }
    if (ok)
    {
        return result;
    }
    result.error = (summary.interruptedBy != 0 ? "" : r.scene + ": ") + failure;
    for (std::size_t k = 0; k < written.size(); ++k)
    {
        result.error += (k == 0 ? "; partial outputs kept in " : ", ") + written[k];
    }
    if (written.empty())
    {
        result.error += "; nothing written";
    }
    result.exitCode =
        summary.interruptedBy != 0 ? run::interruptedExitCode(summary.interruptedBy) : cExitFailed;
    return result;
}

// Loads the run and opens its outputs; nullopt with the result of a run that cannot start.
std::optional<JobResult> prepareRun(const RunRequest& r, PreparedRun& prepared)
{
    try
    {
        prepared = loadRun(r);
        openOutputs(r.out, prepared);
        return std::nullopt;
    }
    catch (const io::InputError& e)
    {
        return failedJob(cExitBadInput, e.what());
    }
    catch (const io::OutputError& e)
    {
        return failedJob(cExitBadInput, e.what());
    }
    catch (const std::filesystem::filesystem_error& e)
    {
        return failedJob(cExitBadInput, e.what());
    }
    catch (const core::Interrupted& e) // a signal while loading: no output was begun
    {
        return failedJob(run::interruptedExitCode(e.signal()),
                         std::string(e.what()) + " while loading " + r.scene + "; nothing written");
    }
}

} // namespace

JobResult runOne(const RunRequest& request)
{
    RunRequest r = request;
    if (!r.status)
    {
        r.status = [](const std::string&) {};
    }
    PreparedRun prepared;
    if (std::optional<JobResult> failed = prepareRun(r, prepared))
    {
        return *failed;
    }
    SimulatedRun simulated;
    try
    {
        simulated = simulate(r, prepared);
    }
    catch (const core::UnsupportedModelError& e)
    {
        return failedJob(cExitBadInput, r.scene + ": " + e.what());
    }
    catch (const io::OutputError& e) // an output file could not be written on (a full disk)
    {
        return failedJob(cExitBadInput, e.what());
    }
    const std::vector<std::string> warnings = runWarnings(prepared, simulated.summary);
    std::string failure = simulated.summary.failure;
    if (simulated.summary.completed && r.options.strict && !warnings.empty())
    {
        failure = "--strict: " + warnings.front();
    }
    std::vector<std::string> written;
    try
    {
        written = commitOutputs(r, prepared, simulated.summary, warnings, failure);
        if (!r.out.frames.empty() && failure.empty())
        {
            JobResult frames = writeFrames(prepared.model, simulated.frames,
                                           {r.out.frames, r.options.width, r.options.height, r.renderThreads},
                                           r.options.fps, r.out.video, r.status);
            if (frames.exitCode != cExitOk)
            {
                return frames;
            }
        }
    }
    catch (const io::OutputError& e)
    {
        return failedJob(cExitBadInput, e.what());
    }
    return finishedRun(r, prepared, simulated, warnings, failure, written);
}

} // namespace frontier::app
