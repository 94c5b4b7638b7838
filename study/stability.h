// study/stability.h: the stability suite (`frontier stability`, docs/stability.md): each
// scene run with each method (solver and integrator), and what survived: joint gaps, energy
// drift, angular momentum, penetration, tunnelling, wall time, written as a markdown table.
#pragma once

#include "core/model.h"
#include "io/scene.h"
#include "run/method.h"

#include <optional>
#include <string>
#include <vector>

namespace frontier::study
{

using run::Method; // solver, its options and integrator (run/method.h)

// linear/euler, linear/rattle, dense/euler, pgs:20/euler, pgs:100/euler.
std::vector<run::Method> defaultStabilityMethods();

struct StabilityLimits
{
    double maxJointGapM = 1e-2;     // a larger positional joint gap counts as coming apart (m)
    double maxJointGapRad = 0.1;    // a larger angular joint gap counts as coming apart (rad)
    int maxDenseRows = 2000;        // dense cells with a larger KKT matrix are skipped
    std::optional<double> duration; // simulated time (s); default: the scene's
    std::optional<double> dt;       // time step (s); default: the scene's
};

enum class StabilityOutcome
{
    Survived,    // ran to the end: finite, joints held, no tunnelling
    Failed,      // blew up, came apart, a singular joint, or a body tunnelled through a static one
    Unavailable, // the method is not built (core::UnsupportedModelError)
    Skipped,     // not run (dense beyond StabilityLimits::maxDenseRows)
};

// One scene run with one method. Energies are relative to energyScaleJ (stabilityEnergyScale).
struct StabilityCell
{
    std::string scene;  // file name without folder and extension
    std::string method; // run::Method::label()
    StabilityOutcome outcome = StabilityOutcome::Survived;
    std::string note;    // why it failed, was skipped or is unavailable (empty when it survived)
    std::string failure; // the simulator's message when the run stopped
    long steps = 0;      // steps asked for
    long stepsRun = 0;   // steps completed
    double dt = 0.0;     // s
    double maxJointGapM = 0.0;
    double maxJointGapRad = 0.0;
    double energyInitialJ = 0.0;
    double energyMaxJ = 0.0;
    double energyMinJ = 0.0;
    double energyScaleJ = 1.0;
    double maxPenetrationM = 0.0; // deepest contact overlap reported by the detector (m)
    // Largest |L(t) - L(0)| / |L(0)| of the total angular momentum; only for free systems (no
    // gravity, no static bodies, no joint to the world), where it must be conserved.
    std::optional<double> momentumDrift;
    // "'body' through 'static' at t = ... s" when a centre of mass passed right through a static
    // box within one step or ended below a static plane (empty: never).
    std::string tunnelled;
    bool passive = true;      // no actuators, no loads (run::isPassive): nothing may add energy
    double maxSpeedMps = 0.0; // largest speed of a moving body's centre of mass (m/s)
    std::string fastestBody;  // whose
    // The scene's watched joints (its `stability: joints`): the angle's extremes over the run (rad,
    // the model file's convention) and the largest distance from a position servo's target (rad).
    std::optional<double> angleLowRad;
    std::optional<double> angleHighRad;
    std::optional<double> maxTrackingErrorRad;
    double wallSeconds = 0.0;

    bool survived() const { return outcome == StabilityOutcome::Survived; }
    double energyRise() const { return (energyMaxJ - energyInitialJ) / energyScaleJ; } // relative
    double energyLoss() const { return (energyInitialJ - energyMinJ) / energyScaleJ; } // relative
};

// The energy the suite's drift is measured against (J): the initial kinetic energy plus M |g| D,
// M the moving mass and D the diagonal of the box holding the initial centres of mass (lifting
// everything across the scene); at least 1e-9 J.
double stabilityEnergyScale(const core::Model& model);

// Rows of the dense KKT matrix: 6 per moving body plus every joint row.
int denseRows(const core::Model& model);

// Runs `model` (its settings but the method's solver and integrator, and limits.dt and
// limits.duration when given). Never throws for a failed run: the cell says what happened. A run
// that survived still fails when it broke one of the scene's own `criteria`
// (study/stability_criteria.h).
StabilityCell runStabilityCell(const core::Model& model, const std::string& sceneName,
                               const run::Method& method, const StabilityLimits& limits,
                               const io::SceneStabilityCriteria& criteria = {});

// Where a method ends on a scene: the largest time step, halving from `start`, at which a run of
// the scene (for the shorter of its duration and `duration`) holds, i.e. survives and meets the
// scene's criteria. The search stops at the first step that holds, or after the first step below
// the scene's own (limits.dt, else its dt) that does not.
struct LargestDtOptions
{
    double start = 1.0 / 30.0; // s
    double duration = 1.0;     // s: the longest run of the search
};
struct LargestDtCell
{
    std::string scene;
    std::string method;
    StabilityOutcome outcome = StabilityOutcome::Survived; // Failed: no step tried held
    std::string note;             // skipped or unavailable: why; failed: the last failure
    std::optional<double> dt;     // s: the largest step that held
    double smallestTriedDt = 0.0; // s
    double duration = 0.0;        // s simulated per run
    int runs = 0;
    double wallSeconds = 0.0; // all its runs
};
LargestDtCell largestHoldingDt(const core::Model& model, const std::string& sceneName,
                               const run::Method& method, const StabilityLimits& limits,
                               const io::SceneStabilityCriteria& criteria,
                               const LargestDtOptions& options = {});

// What the report says beyond the cells: each scene's own criteria (one per scene, or empty) and
// the largest-dt search's cells (empty: not searched).
struct StabilityReportExtras
{
    std::vector<io::SceneStabilityCriteria> criteria;
    std::vector<LargestDtCell> largest;
    LargestDtOptions search;
};

// The markdown report: an overview (scene by method, survived or why not), the scenes, the
// largest time steps that hold (when searched) and the details, one row per cell; `machine`
// names the computer the wall times were measured on.
std::string stabilityMarkdown(const std::vector<core::Model>& scenes,
                              const std::vector<std::string>& sceneNames,
                              const std::vector<run::Method>& methods,
                              const std::vector<StabilityCell>& cells, const StabilityLimits& limits,
                              const std::string& machine, const StabilityReportExtras& extras = {});

// "N cores, <model name>" from std::thread and /proc/cpuinfo.
std::string machineDescription();

} // namespace frontier::study
