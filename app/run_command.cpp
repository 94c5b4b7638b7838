// app/run_command.cpp: `frontier run`: load, simulate, record, summarize.
#include "app/commands.h"
#include "app/model_overrides.h"
#include "app/progress.h"
#include "app/run_loop.h"
#include "core/impulse_solver.h"
#include "io/atomic_file.h"
#include "io/scene.h"
#include "io/stats.h"
#include "io/trajectory.h"

#include <cmath>
#include <cstdio>
#include <iostream>
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

void printSummary(const core::Model& model, const RunSummary& s)
{
    const double simulated = static_cast<double>(s.steps) * model.simulation.dt;
    const double perStep = s.steps > 0 ? s.wallSeconds / static_cast<double>(s.steps) : 0.0;
    const double change = s.energyFinalJ - s.energyInitialJ;
    const double scale = std::max(std::abs(s.energyInitialJ), 1e-300);
    std::printf(
        "%s: %ld steps of %g s (%.3f s simulated) in %.3f s wall, %.2f us per step (%.1fx real time); "
        "%d bodies, %zu joints, %d constraint rows; largest joint error %.3g m, %.3g rad; "
        "energy %.6g J -> %.6g J (%+.3g%%); max contacts %d, max penetration %.3g m%s\n",
        model.name.c_str(), s.steps, model.simulation.dt, simulated, s.wallSeconds, perStep * 1e6,
        s.wallSeconds > 0 ? simulated / s.wallSeconds : 0.0, movingBodies(model), model.joints.size(),
        constraintRows(model), s.maxJointErrorM, s.maxJointErrorRad, s.energyInitialJ, s.energyFinalJ,
        100.0 * change / scale, s.maxContacts, s.maxPenetrationM, s.finite ? "." : "; the run FAILED.");
}

io::RunStats makeStats(const RunOptions& options, const core::Model& model, const RunSummary& s)
{
    io::RunStats stats;
    io::fillModelCounts(stats, model);
    stats.scene = options.scene;
    stats.solver = core::solverName(model.simulation.solver);
    stats.integrator = core::integratorName(model.simulation.integrator);
    stats.dt = model.simulation.dt;
    stats.steps = s.steps;
    stats.wallSeconds = s.wallSeconds;
    stats.secondsPerStep = s.steps > 0 ? s.wallSeconds / static_cast<double>(s.steps) : 0.0;
    stats.maxJointErrorM = s.maxJointErrorM;
    stats.pgsIterations = model.simulation.pgsIterations;
    stats.simulatedSeconds = static_cast<double>(s.steps) * model.simulation.dt;
    stats.extra["max_joint_error_rad"] = s.maxJointErrorRad;
    stats.extra["energy_max_j"] = s.energyMaxJ;
    stats.maxPenetrationM = s.maxPenetrationM;
    stats.energyInitialJ = s.energyInitialJ;
    stats.energyFinalJ = s.energyFinalJ;
    stats.maxContacts = s.maxContacts;
    stats.finite = s.finite;
    return stats;
}
} // namespace

int runCommand(const RunOptions& options)
{
    core::Model model;
    long steps = 0;
    std::unique_ptr<io::TrajectoryWriter> trajectory;
    try
    {
        model = io::loadScene(options.scene);
        steps = applyOverrides(options, model);
        if (!options.trajectory.empty())
        {
            trajectory = std::make_unique<io::TrajectoryWriter>(
                options.trajectory,
                io::makeTrajectoryMetadata(options.scene, model.simulation, steps, options.recordEvery));
        }
    }
    catch (const io::InputError& error)
    {
        std::cerr << "frontier: " << error.what() << "\n";
        return cExitBadInput;
    }
    catch (const io::OutputError& error)
    {
        std::cerr << "frontier: " << error.what() << "\n";
        return cExitBadInput;
    }

    RunSettings settings;
    settings.steps = steps;
    settings.recordEvery = options.recordEvery;
    settings.progress = !options.quiet && stderrIsTerminal();
    Recorder record;
    if (trajectory)
    {
        record = [&](const core::State& state) { trajectory->writeState(model, state); };
    }
    RunSummary summary;
    try
    {
        summary = runSimulation(model, settings, record);
    }
    catch (const core::UnsupportedModelError& error)
    {
        std::cerr << "frontier: " << options.scene << ": " << error.what() << "\n";
        return cExitBadInput;
    }
    catch (const core::SingularJointError& error)
    {
        std::cerr << "frontier: " << options.scene << ": " << error.what() << "\n";
        return cExitFailed;
    }

    try
    {
        if (trajectory && summary.finite)
        {
            trajectory->commit();
        }
        if (!options.stats.empty())
        {
            io::writeStats(options.stats, makeStats(options, model, summary));
        }
    }
    catch (const io::OutputError& error)
    {
        std::cerr << "frontier: " << error.what() << "\n";
        return cExitBadInput;
    }
    if (!options.quiet)
    {
        printSummary(model, summary);
    }
    if (!summary.finite)
    {
        std::cerr << "frontier: " << summary.failure << "\n";
        return cExitFailed;
    }
    return cExitOk;
}

} // namespace frontier::app
