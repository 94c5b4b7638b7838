// study/sweep.h: `frontier sweep`, the engine: the grid of time steps x solvers x integrators, one
// run per cell, the reference run and the metrics (cost, trajectory error, joint gap, energy drift,
// penetration). No output: study/sweep_report.h writes the table and CSV, app/sweep_chart.h the chart.
//
// Accuracy is measured against a reference run: integrator rattle, or rattle4 when the grid has
// rattle4 (euler when that cannot be built or its run fails), solver linear, at the finest time step of the
// grid divided by cReferenceRefinement. Every run records the centre-of-mass positions of the moving bodies
// at the same sample times: about cSampleCount multiples of a common multiple of every time step of the grid
// (usually the largest one), spread evenly over the run, the last one at its end, so every cell and the
// reference hit them exactly.
#pragma once

#include "core/model.h"
#include "run/method.h"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace frontier::study
{

using run::Method; // solver, its options and integrator (run/method.h)

inline constexpr int cSampleCount = 20;          // sample times compared with the reference
inline constexpr int cReferenceRefinement = 4;   // reference dt = finest dt of the grid / 4
inline constexpr int cDefaultLadderSteps = 5;    // default --dt: scene dt x 16, 8, 4, 2, 1
inline constexpr double cDefaultMaxDuration = 2; // s: default --duration caps the scene's

// A list entry or combination the sweep cannot take (exit code 2). The message names the flag and
// the entry.
class SweepInputError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// The reference run failed with euler as well (exit code 1).
class SweepReferenceError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// List parsing (entries as given on the command line, split at commas). Throw SweepInputError.
// Time steps (s): positive finite numbers; duplicates removed; sorted coarse to fine.
std::vector<double> parseTimeSteps(const std::vector<std::string>& entries);
// Solvers: linear, dense, pgs (the scene's sweep count) or pgs:K (K >= 1 sweeps), no integrator
// (the methods' integrator is left euler).
std::vector<run::Method> parseSolvers(const std::vector<std::string>& entries, int scenePgsIterations);
// Integrators: euler, rattle, rattle4.
std::vector<core::IntegratorKind> parseIntegrators(const std::vector<std::string>& entries);

// The default --dt: a halving ladder of cDefaultLadderSteps steps ending at the scene's dt
// (16 h, 8 h, 4 h, 2 h, h): each divides the larger ones exactly.
std::vector<double> defaultTimeSteps(double sceneDt);

// When the runs stop and where they are compared.
struct SweepSchedule
{
    double unitS = 0.0;            // the smallest common multiple of every time step found (s)
    long units = 0;                // the run lasts units x unitS
    std::vector<long> sampleUnits; // sample times in units of unitS, increasing, the last == units
    double durationS() const { return static_cast<double>(units) * unitS; }
};

// Throws SweepInputError when the time steps have no common multiple within the duration (a time
// step that does not divide the largest one a small whole number of times) or the duration is
// shorter than that multiple. The run is the duration rounded down to a multiple of unitS.
SweepSchedule planSchedule(const std::vector<double>& dts, double durationS);

struct SweepCell
{
    run::Method method;
    double dt = 0.0;   // s
    long steps = 0;    // steps of the whole run
    long stepsRun = 0; // steps completed (less than steps when the run failed)
    int bodies = 0;    // moving bodies
    bool survived = false;
    double wallSeconds = 0.0;         // the step loop (s): the fastest of up to 10 runs when one is short
    double secondsPerSimSecond = 0.0; // wall s per simulated s (NaN when no step ran)
    double usPerBodyStep = 0.0;       // microseconds per moving body and step (NaN when none)
    double trajectoryErrorM = 0.0;    // largest centre-of-mass distance to the reference (m), NaN if failed
    double finalErrorM = 0.0;         // the same at the last sample time alone (m)
    std::string worstBody;            // the body of finalErrorM
    double maxJointErrorM = 0.0;      // largest positional joint gap over the run (m)
    double maxJointErrorRad = 0.0;    // largest angular joint gap over the run (rad)
    double energyDriftJ = 0.0;        // largest |E(t) - E(0)| over the run (J)
    double energyDriftRel = 0.0;      // energyDriftJ / |E(0)| (NaN when E(0) = 0)
    double maxPenetrationM = 0.0;     // deepest contact overlap over the run (m)
    std::string failure;              // why the run failed (empty when it survived)
    std::string engine;               // another engine's name when it ran the cell (bench/peers), else empty
};

// The name a cell's series goes by in charts: the other engine's, or the Frontier method's label.
inline std::string cellLabel(const SweepCell& cell)
{
    return cell.engine.empty() ? cell.method.label() : cell.engine;
}

// A reference the methods did not make: the world position of one moving body's centre of mass
// (m) as a function of the time (s), from a closed form or from another code's or a measurement's
// samples (readReferenceCsv). With one, runSweep runs no reference and every cell's error is that
// body's distance to it at the sample times.
struct ExternalReference
{
    std::string body;                             // the moving body's name in the model
    std::string source;                           // how the report names it: "tip.csv", "closed form"
    std::function<core::Vec3(double)> position_W; // m at t (s)
};

// A CSV of rows `t,x,y,z` (s, m; a first line that is not numbers is a header, `#` lines are
// comments), times increasing: positions between rows by the cubic through the four nearest rows
// (fourth-order accurate), a row's own position at its time. Throws SweepInputError naming the
// file and line when it cannot be read, has fewer than 4 rows or times that do not increase.
ExternalReference readReferenceCsv(const std::string& path, const std::string& body);

struct SweepReference
{
    std::string external; // the external reference's source (empty: a reference run, below)
    run::Method method;   // rattle (or rattle4) linear, or euler linear when that failed
    double dt = 0.0;      // s
    long steps = 0;
    double wallSeconds = 0.0;
    std::string fallback; // "rattle: why" (or rattle4) when euler was used, else empty
};

struct SweepResult
{
    SweepSchedule schedule;
    SweepReference reference;
    std::vector<SweepCell> cells;    // integrators x solvers x time steps (coarse to fine)
    int bodies = 0;                  // moving bodies
    core::ContactTolerances contact; // the cells' contact tolerances over the scene's (SweepGrid)
    // The signal that stopped the sweep (run::interruptSignal), 0: none. Then `cells` holds the
    // cells finished before it, in grid order (none when it came during the reference run).
    int interruptedBy = 0;
};

// Progress of the sweep: the run being done ("reference" or a cell's label), its index among
// count runs (the reference is 0), and the fraction of its steps done.
using SweepProgress = std::function<void(const std::string& run, int index, int count, double fraction)>;

struct SweepGrid
{
    std::vector<double> dts;          // s, coarse to fine
    std::vector<run::Method> solvers; // solver and options (the integrator is taken from integrators)
    std::vector<core::IntegratorKind> integrators;
    core::ContactTolerances contact; // over the scene's in every cell (the reference keeps the scene's)
};

// The grid from the lists as given (empty: the defaults, defaultTimeSteps of the scene's dt,
// linear, euler and rattle). Throws SweepInputError.
SweepGrid makeSweepGrid(const core::Model& model, const std::vector<std::string>& dts,
                        const std::vector<std::string>& solvers, const std::vector<std::string>& integrators);

// The simulated time asked for (s): the given one, else the scene's capped at cDefaultMaxDuration.
double sweepDuration(const core::Model& model, std::optional<double> duration);

// Runs the reference, then every cell of the grid one after another (never in parallel, so the
// wall times are comparable). A cell that throws (an integrator that cannot be built, a singular
// joint, a blow-up) is a failed cell, not an error. Throws SweepReferenceError when the reference
// fails with euler too, core::UnsupportedModelError when the scene cannot be simulated at all.
// With `external`, no reference run: the errors are those of its body against it; throws
// SweepInputError when its body is not a moving body of the model or a sample time is outside it.
// SIGINT, SIGTERM and SIGHUP, once run::installInterruptHandlers caught them, stop the run under way
// between steps; that run is dropped and the sweep returns with interruptedBy set.
SweepResult runSweep(const core::Model& model, const SweepGrid& grid, const SweepSchedule& schedule,
                     const SweepProgress& progress, const ExternalReference* external = nullptr);

// What a Pareto front or a chart ranks the cells by (m, lower is better).
enum class Accuracy
{
    TrajectoryError, // trajectoryErrorM: the largest centre-of-mass distance to the reference
    JointGap,        // maxJointErrorM: the largest positional joint gap over the run
    Penetration,     // maxPenetrationM: the deepest contact overlap over the run
};

// The cell's figure of that accuracy (m).
double accuracyOf(const SweepCell& cell, Accuracy accuracy);
// Its name in words: "trajectory error", "joint gap", "penetration".
const char* accuracyName(Accuracy accuracy);

// Indices of the Pareto-optimal cells: survived, with a finite cost and accuracy figure, and no
// other such cell at most as costly and at most as wrong (better in one). Sorted by cost.
std::vector<std::size_t> paretoFront(const std::vector<SweepCell>& cells,
                                     Accuracy accuracy = Accuracy::TrajectoryError);

} // namespace frontier::study
