// io/stats.h: the stats JSON of a run (docs/files.md; `frontier run --stats`).
#pragma once

#include "core/model.h"

#include <map>
#include <string>
#include <vector>

namespace frontier::io
{

// One actuator over a run: an entry of the stats' "actuators" array, each member under the key
// in its comment. Over the states at the end of the steps (one sample a step).
struct ActuatorStats
{
    std::string joint;      // "joint": the joint it drives
    std::string coordinate; // "coordinate": rotation | slide (core::coordinateName)
    std::string type;       // "type": position | velocity | effort (core::actuatorTypeName)
    // "tracking_rms", "tracking_max": RMS and largest |target - actual| (run/actuator_efforts.h
    // trackingError): rad or m for a position servo, rad/s or m/s for a velocity motor. NaN for
    // an effort actuator, whose entry has no such keys.
    double trackingRms = 0.0;
    double trackingMax = 0.0;
    double effortRms = 0.0; // "effort_rms" (N or N m)
    double effortMax = 0.0; // "effort_max": largest |effort| (N or N m)
    long limitSteps = 0;    // "limit_steps": steps at its effort limit
};

// One run's summary. Every member is written under the JSON key in its comment. Non-finite
// numbers are written as null and read back as NaN.
struct RunStats
{
    std::string scene;                   // "scene": the scene file
    std::string solver;                  // "solver": linear | dense | pgs
    std::string integrator;              // "integrator": euler | rattle
    int pgsIterations = 0;               // "pgs_iterations"
    double dt = 0.0;                     // "dt" (s)
    long steps = 0;                      // "steps" taken
    double simulatedSeconds = 0.0;       // "simulated_seconds" (s)
    int bodies = 0;                      // "bodies": moving bodies
    int staticBodies = 0;                // "static_bodies"
    int joints = 0;                      // "joints"
    int constraintRows = 0;              // "constraint_rows": joint rows
    int degreesOfFreedom = 0;            // "degrees_of_freedom": 6 bodies - joint rows
    double wallSeconds = 0.0;            // "wall_seconds" (s)
    double secondsPerStep = 0.0;         // "seconds_per_step" (s)
    double maxJointErrorM = 0.0;         // "max_joint_error_m" (m): worst joint anchor separation
    double maxPenetrationM = 0.0;        // "max_penetration_m" (m)
    double energyInitialJ = 0.0;         // "energy_initial_j" (J)
    double energyFinalJ = 0.0;           // "energy_final_j" (J)
    int maxContacts = 0;                 // "max_contacts": most contacts in one step
    bool finite = true;                  // "finite": every state stayed finite
    bool completed = true;               // "completed": the run ended without failing (false: a blow-up,
                                         // a singular joint, a signal, a --strict warning; true if absent)
    std::string failure;                 // "failure": why the run failed; written when not empty
    std::vector<std::string> warnings;   // "warnings": what looks wrong in a run that ended (an array)
    std::string inputsDigest;            // "inputs_digest": io::inputsDigest of the run (64 hex digits;
                                         // a batch job's), written when not empty
    std::vector<std::string> inputFiles; // "input_files": the files the load read (an array), written
                                         // with inputs_digest
    std::map<std::string, double> extra; // further numeric keys, written at the top level
    // "actuators": one entry per actuator, the model's order.
    std::vector<ActuatorStats> actuators;
};

// The JSON keys of RunStats's members, in their order; every other key is an extra.
const std::vector<std::string>& statsKeys();

// Fills the model's counts: bodies (moving), static_bodies, joints, constraint_rows (joint rows)
// and degrees_of_freedom (6 per moving body minus the joint rows).
void fillModelCounts(RunStats& stats, const core::Model& model);

// Writes pretty JSON atomically (temporary file + rename); throws OutputError (io/atomic_file.h).
void writeStats(const std::string& path, const RunStats& stats);

// Reads a stats file; throws InputError for unreadable JSON (with line and column), JSON nested
// deeper than cMaxStatsDepth (at the bracket that goes deeper), missing keys or values of the wrong
// type (the value shown shortened). Unknown numeric keys go to `extra`.
inline constexpr int cMaxStatsDepth = 64; // a stats file written by writeStats is 3 deep
RunStats readStats(const std::string& path);

} // namespace frontier::io
