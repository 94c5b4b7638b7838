// bench/peers/harness.h: one run of one engine on a model, measured the same way for every engine
// (main.cpp repeats it over engines, rounds and jittered variants), and the statistics of the
// rounds.
#pragma once

#include "bench/peers/engine.h"

#include <limits>
#include <string>
#include <vector>

namespace frontier::peers
{

struct RunSettings
{
    double duration = 1.0;    // s simulated
    double maxSeconds = 60.0; // s of stepping, after which the run stops
    // A run that reports a full buffer is rerun with its buffers doubled, up to this growth.
    int maxBufferGrowth = 8;
};

// What one run measured. The accuracy figures are deterministic for every engine here (each run
// starts from a new engine; ODE's random generator is reset, engine_ode.cpp): main.cpp checks that
// over its rounds.
struct EngineRun
{
    std::string engine;
    double dt = 0.0; // s
    long steps = 0;  // steps taken
    double secondsStepping = 0.0;
    double maxGapM = 0.0;
    double maxPenetrationM = 0.0;
    double energyChangeJ = std::numeric_limits<double>::quiet_NaN();
    double energyChangePercent = std::numeric_limits<double>::quiet_NaN(); // of the largest kinetic energy
    double errorM = std::numeric_limits<double>::quiet_NaN();              // at the end, from the reference
    bool refused = false;  // the engine cannot run the model (the failure says why)
    bool timedOut = false; // stopped by RunSettings::maxSeconds
    std::string failure;   // why the run ended early (refused, blew up, stopped, an engine error)
    std::vector<EngineWarning> warnings;
    // The buffers' growth the run had (EngineOptions::bufferGrowth), and when it is more than 1,
    // the full buffer that made it grow and the buffers it ran with.
    int bufferGrowth = 1;
    std::string grownAfter;
    std::string buffers; // the engine's fixed buffers (Engine::bufferSizes)

    double secondsPerStep() const;
};

// Runs the engine `name` on `model` for settings.duration (a reference of no poses: no error).
EngineRun runEngine(const std::string& name, const core::Model& model, const std::vector<Pose>& reference,
                    const RunSettings& settings, const EngineOptions& options = {});

// runEngine, rerun with the buffers doubled while a run reports a full one and the growth stays
// within settings.maxBufferGrowth (from options.bufferGrowth). The run kept says what it grew
// after (EngineRun::grownAfter).
EngineRun runGrowingBuffers(const std::string& name, const core::Model& model,
                            const std::vector<Pose>& reference, const RunSettings& settings,
                            EngineOptions options = {});

// The run's note: why it ended early, the growth of its buffers, then every warning with the step
// it first came at and in how many steps (one line, for a table cell).
std::string note(const EngineRun& run);

// Median (the mean of the two middle values of an even count), smallest and largest of values.
struct Spread
{
    double median = std::numeric_limits<double>::quiet_NaN();
    double min = std::numeric_limits<double>::quiet_NaN();
    double max = std::numeric_limits<double>::quiet_NaN();
};
Spread spread(std::vector<double> values);

// a[k] / b[k] for every k both have (pair by pair: round k of an engine over round k of the
// baseline).
std::vector<double> pairedRatios(const std::vector<double>& a, const std::vector<double>& b);

// The accuracy figures of runs of one engine: those of the first, or, when the runs do not all
// agree exactly, the worst of each figure (largest gap, penetration, error and energy change in
// magnitude); `agree` says which.
struct Accuracy
{
    double maxGapM = 0.0;
    double maxPenetrationM = 0.0;
    double energyChangeJ = std::numeric_limits<double>::quiet_NaN();
    double energyChangePercent = std::numeric_limits<double>::quiet_NaN();
    double errorM = std::numeric_limits<double>::quiet_NaN();
    bool agree = true;
};
Accuracy worstAccuracy(const std::vector<EngineRun>& runs);

} // namespace frontier::peers
