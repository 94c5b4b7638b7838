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

} // namespace

int runOne(const RunOptions& options, const std::string& scene, const JobOutputs& out, int renderThreads,
           const std::function<void(const std::string&)>& status, std::string& summaryText,
           std::string& error, const SceneLoader& load)
{
    core::Model model;
    long steps = 0;
    std::unique_ptr<io::TrajectoryWriter> trajectory;
    std::unique_ptr<StepOutputs> stepOutputs; // --joints, --contacts
    std::vector<std::string> inputFiles;      // read by the load
    try
    {
        run::LoadedScene loaded = load ? load() : run::loadScene(scene, options.urdf);
        inputFiles = io::inputPaths(loaded.report.inputFiles);
        checkInputsKept(outputPathsOf(out), inputFiles); // before anything is written
        if (options.strict && loaded.startPenetration)
        {
            throw io::InputError(scene, 0, 0, "--strict: " + run::startPenetrationText(loaded));
        }
        if (!options.quiet)
        {
            run::printLoadWarnings(loaded.report);
        }
        model = std::move(loaded.model);
        const double asked = options.duration.value_or(model.simulation.duration); // s
        steps = applyOverrides(options, model);
        const std::string note =
            options.steps || options.quiet ? "" : roundedDurationNote(asked, steps, model.simulation.dt);
        if (!note.empty())
        {
            std::fprintf(stderr, "frontier: %s: note: %s\n", scene.c_str(), note.c_str());
        }
        if (!out.frames.empty())
        {
            checkFrameCount(model.simulation.duration, options.fps, static_cast<double>(steps) + 1.0, scene);
        }
        io::TrajectoryMetadata metadata =
            io::makeTrajectoryMetadata(scene, model.simulation, steps, options.recordEvery);
        io::addUrdfOptions(metadata, options.urdf);
        io::addContactTolerances(metadata, options.contact);
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
            trajectory = std::make_unique<io::TrajectoryWriter>(out.trajectory, metadata);
        }
        if (!out.joints.empty() || !out.contacts.empty())
        {
            stepOutputs = std::make_unique<StepOutputs>(out.joints, out.contacts, metadata);
        }
        if (!out.frames.empty())
        {
            prepareFrameFolder(out.frames, out.video);
        }
    }
    catch (const io::InputError& e)
    {
        error = e.what();
        return cExitBadInput;
    }
    catch (const io::OutputError& e)
    {
        error = e.what();
        return cExitBadInput;
    }
    catch (const std::filesystem::filesystem_error& e)
    {
        error = e.what();
        return cExitBadInput;
    }
    catch (const core::Interrupted& e) // a signal while loading: no output was begun
    {
        error = std::string(e.what()) + " while loading " + scene + "; nothing written";
        return run::interruptedExitCode(e.signal());
    }

    std::vector<core::State> frames;
    FrameSampler sampler(options.fps);
    const run::Recorder record = [&](const core::State& state, const core::Simulator* lastStep)
    {
        const bool due = state.step % options.recordEvery == 0;
        if (trajectory && due)
        {
            trajectory->writeState(model, state);
        }
        if (stepOutputs && due)
        {
            stepOutputs->record(model, state, lastStep);
        }
        if (!out.frames.empty() && sampler.due(state.time))
        {
            frames.push_back(state);
        }
    };
    run::RunSettings settings;
    settings.steps = steps;
    const double dt = model.simulation.dt;
    long lastShown = -1;
    settings.progress = [&](long step)
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

    run::RunSummary summary;
    try
    {
        summary = run::runSimulation(model, settings, record);
    }
    catch (const core::UnsupportedModelError& e)
    {
        error = scene + ": " + e.what();
        return cExitBadInput;
    }
    catch (const core::SingularJointError& e) // singular at the start (the simulator's construction)
    {
        summary.completed = false;
        summary.failure = e.what();
    }
    catch (const core::Interrupted& e) // a signal while setting up, before the first step
    {
        summary.completed = false;
        summary.interruptedBy = e.signal();
        summary.failure = std::string(e.what()) + " before the first step";
    }
    catch (const io::OutputError& e) // an output file could not be written on (a full disk)
    {
        error = e.what();
        return cExitBadInput;
    }

    // A passive scene cannot gain energy; when it does, the step was too large for it (or worse).
    const double rise = run::passiveEnergyRise(model, summary);
    std::vector<std::string> warnings =
        loadsAfterTheEnd(model, static_cast<double>(steps) * model.simulation.dt);
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
    std::string failure = summary.failure;
    if (summary.completed && options.strict && !warnings.empty())
    {
        failure = "--strict: " + warnings.front();
    }
    const bool ok = failure.empty();
    // A run that failed keeps its rows up to the failure under names that say so (failedPath).
    std::vector<std::string> written;
    try
    {
        if (trajectory)
        {
            written.push_back(ok ? out.trajectory : failedPath(out.trajectory));
            trajectory->commitAs(written.back());
        }
        if (stepOutputs)
        {
            if (ok)
            {
                stepOutputs->commit();
            }
            else
            {
                for (const std::string& file : stepOutputs->commitFailed())
                {
                    written.push_back(file);
                }
            }
        }
        if (!out.stats.empty())
        {
            io::RunStats stats = run::runStats(scene, model, summary);
            stats.completed = ok;
            stats.failure = failure;
            stats.warnings = warnings;
            if (!options.inputsDigest.empty())
            {
                stats.inputsDigest = options.inputsDigest;
                stats.inputFiles = inputFiles;
            }
            io::writeStats(out.stats, stats);
            written.push_back(out.stats);
        }
        if (!out.frames.empty() && ok)
        {
            if (const int code =
                    writeFrames(model, frames, {out.frames, options.width, options.height, renderThreads},
                                options.fps, out.video, status, error);
                code != cExitOk)
            {
                return code;
            }
        }
    }
    catch (const io::OutputError& e)
    {
        error = e.what();
        return cExitBadInput;
    }
    summaryText = formatSummary(model, summary);
    for (const std::string& warning : warnings)
    {
        summaryText += " Warning: " + warning + ".";
    }
    if (!out.frames.empty() && ok)
    {
        summaryText += " Wrote " + std::to_string(frames.size()) + " frames to " + out.frames + ".";
    }
    if (!ok)
    {
        // Every file of a failed run says so: rows under .failed names, stats with "completed": false.
        error = (summary.interruptedBy != 0 ? "" : scene + ": ") + failure;
        for (std::size_t k = 0; k < written.size(); ++k)
        {
            error += (k == 0 ? "; partial outputs kept in " : ", ") + written[k];
        }
        if (written.empty())
        {
            error += "; nothing written";
        }
        return summary.interruptedBy != 0 ? run::interruptedExitCode(summary.interruptedBy) : cExitFailed;
    }
    return cExitOk;
}

} // namespace frontier::app
