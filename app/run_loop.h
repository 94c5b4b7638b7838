// app/run_loop.h: drives a Simulator over a run, recording trajectory rows and statistics.
#pragma once

#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"

#include <array>
#include <functional>
#include <optional>
#include <string>

namespace frontier::app
{

struct RunSettings
{
    long steps = 0;                          // number of steps (from --steps or duration / dt)
    std::function<void(long step)> progress; // called after every step (may be empty)
};

struct RunSummary
{
    long steps = 0;
    double wallSeconds = 0.0;
    double maxJointErrorM = 0.0;   // largest positional joint violation over the run (m)
    double maxJointErrorRad = 0.0; // largest angular joint violation over the run (rad)
    double energyInitialJ = 0.0;
    double energyFinalJ = 0.0;
    double energyMaxJ = 0.0; // largest total energy over the run (J)
    double energyMinJ = 0.0; // smallest total energy over the run (J)
    double maxPenetrationM = 0.0;
    std::array<double, core::cStepStages> stageSeconds{}; // wall time per stage over the run (s)
    int maxContacts = 0;
    long firstOrderSteps = 0; // rattle steps that stalled and were taken by euler instead
    std::array<long, core::cContactRoutes> contactRoutes{}; // steps by core::ContactRoute
    long contactSweeps = 0;         // Gauss-Seidel sweeps of the contact problem, all steps
    long limitSteps = 0;            // steps in which some joint-limit row pushed
    double maxActuatorEffort = 0.0; // largest |effort| of any actuator in any step (N or N m)
    long actuatorLimitSteps = 0;    // steps in which some actuator sat at its effort limit
    bool finite = true;
    std::string failure;                                   // the SimulationError message when the run blew up
    std::optional<core::SimulationFailure> failureDetails; // and what it named
};

// Called with the initial state (`lastStep` null: no step yet) and with the state after every
// step, with the simulator that took it (its impulses and contacts are then that step's).
using Recorder = std::function<void(const core::State&, const core::Simulator* lastStep)>;

RunSummary runSimulation(const core::Model& model, const RunSettings& settings, const Recorder& record);

long stepsFor(double duration, double dt);

} // namespace frontier::app
