// run/run_loop.h: drives a Simulator over a run, recording trajectory rows and statistics.
#pragma once

#include "core/interrupt.h"
#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace frontier::run
{

struct RunSettings
{
    long steps = 0;                          // number of steps (from --steps or duration / dt)
    std::function<void(long step)> progress; // called after every step (may be empty)
};

// What one actuator did over a run, over the states at the end of the steps taken (one sample a
// step; the initial state, before any effort, is not one).
struct ActuatorSummary
{
    // RMS and largest |.| of trackingError (run/actuator_efforts.h): rad or m for a position
    // servo, rad/s or m/s for a velocity motor; NaN for an effort actuator (no target to follow).
    double trackingRms = 0.0;
    double trackingMax = 0.0;
    double effortRms = 0.0; // RMS of its effort (N or N m)
    double effortMax = 0.0; // largest |effort| (N or N m)
    long limitSteps = 0;    // steps in which it sat at its effort limit
};

struct RunSummary
{
    long steps = 0;
    double wallSeconds = 0.0;
    double maxJointErrorM = 0.0;   // largest positional joint violation over the run (m)
    double maxJointErrorRad = 0.0; // largest angular joint violation over the run (rad)
    double energyInitialJ = 0.0;
    double energyFinalJ = 0.0;
    double energyMaxJ = 0.0;   // largest total energy over the run (J)
    double energyMinJ = 0.0;   // smallest total energy over the run (J)
    double energyScaleJ = 0.0; // energyScale of the initial state (J)
    double maxPenetrationM = 0.0;
    std::array<double, core::cStepStages> stageSeconds{}; // wall time per stage over the run (s)
    int maxContacts = 0;
    long firstOrderSteps = 0;  // rattle steps that stalled and were taken by euler instead
    long secondOrderSteps = 0; // rattle4 steps retaken as one rattle step (contact, limit or a stall)
    std::array<long, core::cContactRoutes> contactRoutes{}; // steps by core::ContactRoute
    long contactSweeps = 0;         // Gauss-Seidel sweeps of the contact problem, all steps
    long limitSteps = 0;            // steps in which some joint-limit row pushed
    long stiffenedSteps = 0;        // steps in which some body took geometric stiffness (docs/method.md §7a)
    double maxActuatorEffort = 0.0; // largest |effort| of any actuator in any step (N or N m)
    long actuatorLimitSteps = 0;    // steps in which some actuator sat at its effort limit
    bool finite = true;             // every state stayed finite (false: the run blew up)
    bool completed = true;          // every step was taken (false: blow-up, singular joint or interrupt)
    int interruptedBy = 0;          // the signal that stopped the run (interruptSignal), 0: none
    std::string failure;            // why the run did not complete (the error's message)
    std::optional<core::SimulationFailure> failureDetails; // and what it named
    // Per actuator, Model::actuators order.
    std::vector<ActuatorSummary> actuators;
};

// Called with the initial state (`lastStep` null: no step yet) and with the state after every
// step, with the simulator that took it (its impulses and contacts are then that step's).
using Recorder = std::function<void(const core::State&, const core::Simulator* lastStep)>;

// Runs settings.steps steps. A blow-up (core::SimulationError), a singular joint
// (core::SingularJointError) or a signal (interruptSignal, read between steps) ends the run early
// with completed false and `failure` saying why; the states recorded so far were the last good ones.
RunSummary runSimulation(const core::Model& model, const RunSettings& settings, const Recorder& record);

// A passive scene: no actuators and no loads, so nothing in it adds energy (gravity is in the
// potential; contacts, limits, joint damping and friction only take energy away).
bool isPassive(const core::Model& model);

// The size of a state's energy (J): the sum over moving bodies of the kinetic energy and the
// magnitude of the gravitational potential (zero at the origin, as in core::totalEnergy). A
// passive run whose energy rises above its start by more than cEnergyGainTolerance of this has
// gained energy it cannot have: the run summary warns, the stats list it, --strict fails the run.
double energyScale(const core::Model& model, const core::State& state);
inline constexpr double cEnergyGainTolerance = 0.01;
inline constexpr double cEnergyScaleFloorJ = 1e-6; // J: the scale of a scene at rest at the origin
// The rise of a passive run's energy as a fraction of its scale, or 0 for a scene that is not passive.
double passiveEnergyRise(const core::Model& model, const RunSummary& summary);

// The interrupt flag (core/interrupt.h), read between steps.
using core::installInterruptHandlers;
using core::interruptedExitCode;
using core::interruptSignal;
using core::signalName;

long stepsFor(double duration, double dt);

} // namespace frontier::run
