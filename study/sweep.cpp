// study/sweep.cpp: the sweep grid, its schedule, the reference run, one run per cell and the metrics.
#include "study/sweep.h"

#include "core/simulator.h"
#include "core/state.h"
#include "io/file_util.h"
#include "run/run_loop.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

namespace frontier::study
{

// The run loop of `frontier run` (run/run_loop.h).
using run::Recorder;
using run::RunSettings;
using run::runSimulation;
using run::RunSummary;

namespace
{
constexpr double cNaN = std::numeric_limits<double>::quiet_NaN();
// A common multiple of the time steps is searched among the first this many multiples of the
// largest one.
constexpr long cMaxUnitMultiple = 1000;
// How far from a whole number (relative) a ratio of time steps may be and still count as one.
constexpr double cRatioTolerance = 1e-6;
// A cell's run shorter than this (wall s) is repeated, up to cMaxTimingRuns runs in all, and the
// fastest counts: one short run is mostly timer and cache noise.
constexpr double cTimingSeconds = 0.05;
constexpr int cMaxTimingRuns = 10;

std::string trim(const std::string& text)
{
    const auto begin = text.find_first_not_of(" \t");
    if (begin == std::string::npos)
    {
        return {};
    }
    const auto end = text.find_last_not_of(" \t");
    return text.substr(begin, end - begin + 1);
}

std::string formatSeconds(double seconds)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", seconds);
    return text;
}

// True when ratio is a whole number >= 1, within round-off.
bool isWholeRatio(double ratio)
{
    const double whole = std::round(ratio);
    return whole >= 1.0 && std::abs(ratio - whole) <= cRatioTolerance * whole;
}

long stepsPerUnit(double unitS, double dt)
{
    return static_cast<long>(std::llround(unitS / dt));
}

std::vector<int> movingBodies(const core::Model& model)
{
    std::vector<int> bodies;
    for (int i = 0; i < static_cast<int>(model.bodies.size()); ++i)
    {
        if (core::isMovingBody(model, i))
        {
            bodies.push_back(i);
        }
    }
    return bodies;
}

// Centre-of-mass positions of the moving bodies at each sample time (m).
using Samples = std::vector<std::vector<core::Vec3>>;

struct SampledRun
{
    run::RunSummary summary;
    Samples samples;
};

// One run of `model` as set up, recording the moving bodies at the sample steps. Exceptions of the
// Simulator's constructor (and SingularJointError) propagate; a blow-up is summary.finite = false.
SampledRun runSampled(const core::Model& model, const SweepSchedule& schedule, const std::vector<int>& bodies,
                      const std::function<void(double)>& fraction,
                      const std::function<void(std::size_t, const core::State&)>& atSample)
{
    const long perUnit = stepsPerUnit(schedule.unitS, model.simulation.dt);
    SampledRun run;
    run::RunSettings settings;
    settings.steps = schedule.units * perUnit;
    if (fraction)
    {
        settings.progress = [&](long step)
        { fraction(static_cast<double>(step) / static_cast<double>(settings.steps)); };
    }
    std::size_t next = 0;
    const run::Recorder record = [&](const core::State& state, const core::Simulator*)
    {
        if (next < schedule.sampleUnits.size() && state.step == schedule.sampleUnits[next] * perUnit)
        {
            if (atSample)
            {
                atSample(next, state);
            }
            else
            {
                std::vector<core::Vec3> positions;
                positions.reserve(bodies.size());
                for (int body : bodies)
                {
                    positions.push_back(state.bodies[static_cast<std::size_t>(body)].position_W);
                }
                run.samples.push_back(std::move(positions));
            }
            ++next;
        }
    };
    run.summary = run::runSimulation(model, settings, record);
    return run;
}

bool allFinite(const Samples& samples)
{
    for (const auto& sample : samples)
    {
        for (const core::Vec3& p : sample)
        {
            if (!p.allFinite())
            {
                return false;
            }
        }
    }
    return true;
}
} // namespace

std::vector<double> parseTimeSteps(const std::vector<std::string>& entries)
{
    std::vector<double> dts;
    for (const std::string& raw : entries)
    {
        const std::string entry = trim(raw);
        double dt = 0.0;
        const auto [end, error] = std::from_chars(entry.data(), entry.data() + entry.size(), dt);
        if (entry.empty() || error != std::errc() || end != entry.data() + entry.size() ||
            !std::isfinite(dt) || dt <= 0.0)
        {
            throw SweepInputError("--dt: '" + raw + "' is not a positive time step in seconds");
        }
        if (std::find(dts.begin(), dts.end(), dt) == dts.end())
        {
            dts.push_back(dt);
        }
    }
    if (dts.empty())
    {
        throw SweepInputError("--dt: no time steps given");
    }
    std::sort(dts.begin(), dts.end(), std::greater<>());
    return dts;
}

std::vector<run::Method> parseSolvers(const std::vector<std::string>& entries, int scenePgsIterations)
{
    std::vector<run::Method> solvers;
    for (const std::string& raw : entries)
    {
        const std::string entry = trim(raw);
        bool hasIntegrator = false;
        const std::optional<run::Method> parsed = run::parseMethod(entry, scenePgsIterations, &hasIntegrator);
        if (!parsed && entry.rfind("pgs:", 0) == 0)
        {
            throw SweepInputError("--solver: '" + raw +
                                  "': the pgs sweep count K of pgs:K must be a whole number from 1 to " +
                                  std::to_string(run::cMaxPgsIterations));
        }
        if (!parsed || hasIntegrator)
        {
            std::vector<std::string> known = core::solverNames();
            known.emplace_back("pgs:K with K sweeps");
            throw SweepInputError("--solver: unknown solver '" + raw + "' (expected " +
                                  core::nameList(known, "or") + ")");
        }
        const bool seen = std::any_of(solvers.begin(), solvers.end(),
                                      [&](const run::Method& s) { return s.sameSolver(*parsed); });
        if (!seen)
        {
            solvers.push_back(*parsed);
        }
    }
    if (solvers.empty())
    {
        throw SweepInputError("--solver: no solvers given");
    }
    return solvers;
}

std::vector<core::IntegratorKind> parseIntegrators(const std::vector<std::string>& entries)
{
    std::vector<core::IntegratorKind> integrators;
    for (const std::string& raw : entries)
    {
        const auto kind = core::integratorFromName(trim(raw));
        if (!kind)
        {
            throw SweepInputError("--integrator: unknown integrator '" + raw + "' (expected " +
                                  core::nameList(core::integratorNames(), "or") + ")");
        }
        if (std::find(integrators.begin(), integrators.end(), *kind) == integrators.end())
        {
            integrators.push_back(*kind);
        }
    }
    if (integrators.empty())
    {
        throw SweepInputError("--integrator: no integrators given");
    }
    return integrators;
}

std::vector<double> defaultTimeSteps(double sceneDt)
{
    std::vector<double> dts;
    for (int k = cDefaultLadderSteps - 1; k >= 0; --k)
    {
        dts.push_back(std::ldexp(sceneDt, k)); // exact: a power of two times the scene's dt
    }
    return dts;
}

SweepSchedule planSchedule(const std::vector<double>& dts, double durationS)
{
    const double largest = *std::max_element(dts.begin(), dts.end());
    SweepSchedule schedule;
    for (long m = 1; m <= cMaxUnitMultiple && schedule.unitS == 0.0; ++m)
    {
        const double candidate = static_cast<double>(m) * largest;
        if (std::all_of(dts.begin(), dts.end(), [&](double dt) { return isWholeRatio(candidate / dt); }))
        {
            schedule.unitS = candidate;
        }
    }
    if (schedule.unitS == 0.0)
    {
        double offender = largest;
        for (double dt : dts)
        {
            if (!isWholeRatio(largest / dt))
            {
                offender = dt;
                break;
            }
        }
        throw SweepInputError(
            "--dt: " + formatSeconds(offender) + " s does not divide " + formatSeconds(largest) +
            " s (the largest time step) a whole number of times, and the time steps have no "
            "common multiple below " +
            std::to_string(cMaxUnitMultiple) +
            " x the largest: every run must reach the same sample times (use halvings of "
            "the largest time step)");
    }
    schedule.units = static_cast<long>(std::floor(durationS / schedule.unitS * (1.0 + 1e-9)));
    if (schedule.units < 1)
    {
        throw SweepInputError("--duration: " + formatSeconds(durationS) + " s is shorter than " +
                              formatSeconds(schedule.unitS) +
                              " s, the smallest common multiple of the time steps (every run must reach it)");
    }
    const long count = std::min<long>(cSampleCount, schedule.units);
    for (long i = 1; i <= count; ++i)
    {
        schedule.sampleUnits.push_back((i * schedule.units + count / 2) / count);
    }
    return schedule;
}

SweepGrid makeSweepGrid(const core::Model& model, const std::vector<std::string>& dts,
                        const std::vector<std::string>& solvers, const std::vector<std::string>& integrators)
{
    SweepGrid grid;
    grid.dts = dts.empty() ? defaultTimeSteps(model.simulation.dt) : parseTimeSteps(dts);
    grid.solvers = solvers.empty() ? parseSolvers({core::solverName(core::SolverKind::Linear)},
                                                  model.simulation.pgsIterations)
                                   : parseSolvers(solvers, model.simulation.pgsIterations);
    grid.integrators = integrators.empty()
                           ? std::vector{core::IntegratorKind::Euler, core::IntegratorKind::Rattle}
                           : parseIntegrators(integrators);
    return grid;
}

double sweepDuration(const core::Model& model, std::optional<double> duration)
{
    return duration ? *duration : std::min(model.simulation.duration, cDefaultMaxDuration);
}

namespace
{
using RunFraction = std::function<void(double)>;

// The reference: rattle linear (rattle4 when the grid has rattle4) at the finest dt /
// cReferenceRefinement, euler when that fails
// (reference.fallback says why). work leaves with the reference's settings. Throws
// SweepReferenceError when euler fails too. Returns no samples when a signal stopped it
// (run::interruptSignal).
Samples runReference(core::Model& work, const SweepGrid& grid, const SweepSchedule& schedule,
                     const std::vector<int>& bodies,
                     const std::function<RunFraction(const std::string&)>& report, SweepReference& reference)
{
    reference.dt = *std::min_element(grid.dts.begin(), grid.dts.end()) / cReferenceRefinement;
    reference.steps = schedule.units * stepsPerUnit(schedule.unitS, reference.dt);
    work.simulation.dt = reference.dt;
    work.simulation.duration = schedule.durationS();
    work.simulation.solver = core::SolverKind::Linear;
    const bool fourthOrder = std::find(grid.integrators.begin(), grid.integrators.end(),
                                       core::IntegratorKind::Rattle4) != grid.integrators.end();
    const core::IntegratorKind first =
        fourthOrder ? core::IntegratorKind::Rattle4 : core::IntegratorKind::Rattle;
    for (core::IntegratorKind integrator : {first, core::IntegratorKind::Euler})
    {
        reference.method = {core::SolverKind::Linear, work.simulation.pgsIterations, integrator};
        work.simulation.integrator = integrator;
        const bool last = integrator == core::IntegratorKind::Euler;
        std::string failure;
        try
        {
            SampledRun run = runSampled(
                work, schedule, bodies,
                report("reference " + reference.method.label() + " dt " + formatSeconds(reference.dt) + " s"),
                {});
            reference.wallSeconds = run.summary.wallSeconds;
            if (run.summary.interruptedBy != 0)
            {
                return {};
            }
            if (run.summary.finite && run.samples.size() == schedule.sampleUnits.size() &&
                allFinite(run.samples))
            {
                return std::move(run.samples);
            }
            failure = run.summary.failure.empty() ? "it did not stay finite" : run.summary.failure;
        }
        catch (const core::UnsupportedModelError& e)
        {
            if (last)
            {
                throw;
            }
            failure = e.what();
        }
        catch (const core::SingularJointError& e)
        {
            failure = e.what();
        }
        if (last)
        {
            throw SweepReferenceError("the reference run (" + reference.method.label() + ", dt " +
                                      formatSeconds(reference.dt) + " s) failed: " + failure);
        }
        reference.fallback = std::string(core::integratorName(first)) + ": " + failure;
    }
    return {};
}

// The external reference at every sample time, for its body alone (compared leaves holding it).
Samples externalSamples(const core::Model& model, const std::vector<int>& bodies,
                        const SweepSchedule& schedule, const ExternalReference& external,
                        std::vector<int>& compared)
{
    const auto found =
        std::find_if(bodies.begin(), bodies.end(),
                     [&](int b) { return model.bodies[static_cast<std::size_t>(b)].name == external.body; });
    if (found == bodies.end())
    {
        throw SweepInputError("reference " + external.source + ": '" + external.body +
                              "' is not a moving body of the scene");
    }
    compared = {*found};
    Samples samples;
    for (const long unit : schedule.sampleUnits)
    {
        samples.push_back({external.position_W(static_cast<double>(unit) * schedule.unitS)});
    }
    return samples;
}

// A run's summary into its cell; survived when it stayed finite through every sample.
void takeSummary(const run::RunSummary& s, std::size_t compared, std::size_t samples, double trajectoryError,
                 SweepCell& cell)
{
    cell.stepsRun = s.steps;
    cell.wallSeconds = s.wallSeconds;
    cell.maxJointErrorM = s.maxJointErrorM;
    cell.maxJointErrorRad = s.maxJointErrorRad;
    cell.maxPenetrationM = s.maxPenetrationM;
    cell.energyDriftJ = std::max(s.energyMaxJ - s.energyInitialJ, s.energyInitialJ - s.energyMinJ);
    cell.energyDriftRel = s.energyInitialJ != 0.0 ? cell.energyDriftJ / std::abs(s.energyInitialJ) : cNaN;
    cell.survived = s.finite && compared == samples && std::isfinite(trajectoryError);
    cell.failure = s.failure;
    if (cell.failure.empty() && !cell.survived)
    {
        cell.failure = "the run did not stay finite";
    }
}

// Cost per simulated second and per body step; NaN for what a failed or empty run did not measure.
void finishCell(double trajectoryError, SweepCell& cell)
{
    const double simulated = static_cast<double>(cell.stepsRun) * cell.dt;
    cell.secondsPerSimSecond = cell.stepsRun > 0 ? cell.wallSeconds / simulated : cNaN;
    cell.usPerBodyStep = cell.stepsRun > 0 && cell.bodies > 0
                             ? 1e6 * cell.wallSeconds / (static_cast<double>(cell.stepsRun) * cell.bodies)
                             : cNaN;
    cell.trajectoryErrorM = cell.survived ? trajectoryError : cNaN;
    if (!cell.survived)
    {
        cell.finalErrorM = cNaN;
        cell.worstBody.clear();
    }
    if (cell.stepsRun == 0)
    {
        cell.maxJointErrorM = cell.maxJointErrorRad = cell.energyDriftJ = cell.energyDriftRel =
            cell.maxPenetrationM = cNaN;
    }
}

// One cell: work run with the cell's method and dt, compared with the reference at every sample,
// then timed again (up to cMaxTimingRuns runs in cTimingSeconds) when it was short. False when a
// signal stopped its run (run::interruptSignal): the cell has no result; one that stops a repeat
// leaves the fastest of the repeats before it.
bool runCell(core::Model& work, const core::Model& model, const SweepSchedule& schedule,
             const std::vector<int>& bodies, const Samples& referenceSamples, const RunFraction& fraction,
             SweepCell& cell)
{
    work.simulation.dt = cell.dt;
    cell.method.applyTo(work.simulation);
    double trajectoryError = 0.0;
    std::size_t compared = 0;
    const auto compare = [&](std::size_t sample, const core::State& state)
    {
        double finalError = 0.0;
        for (std::size_t b = 0; b < bodies.size(); ++b)
        {
            const double error =
                (state.bodies[static_cast<std::size_t>(bodies[b])].position_W - referenceSamples[sample][b])
                    .norm();
            // NaN-aware: a non-finite position makes the error NaN.
            trajectoryError = (error > trajectoryError || std::isnan(error)) ? error : trajectoryError;
            if (sample + 1 == schedule.sampleUnits.size() && (error > finalError || b == 0))
            {
                finalError = error;
                cell.worstBody = model.bodies[static_cast<std::size_t>(bodies[b])].name;
            }
        }
        cell.finalErrorM = finalError;
        ++compared;
    };
    try
    {
        const SampledRun run = runSampled(work, schedule, bodies, fraction, compare);
        if (run.summary.interruptedBy != 0)
        {
            return false;
        }
        takeSummary(run.summary, compared, schedule.sampleUnits.size(), trajectoryError, cell);
        // Repeats give the same trajectory (the runs are deterministic); only the time differs.
        double spent = run.summary.wallSeconds;
        run::RunSettings again;
        again.steps = cell.steps;
        for (int repeat = 1; cell.survived && repeat < cMaxTimingRuns && spent < cTimingSeconds; ++repeat)
        {
            const RunSummary repeated = run::runSimulation(work, again, {});
            if (repeated.interruptedBy != 0)
            {
                break;
            }
            const double wall = repeated.wallSeconds;
            cell.wallSeconds = std::min(cell.wallSeconds, wall);
            spent += wall;
        }
    }
    catch (const std::exception& e) // an integrator that cannot be built, a singular joint
    {
        cell.failure = e.what();
        cell.survived = false;
    }
    finishCell(trajectoryError, cell);
    return true;
}

// The cells, one after another, into result.cells; index counts the runs (the reference is 0).
// Stops at an interrupt, which it records in result.interruptedBy.
void runCells(core::Model& work, const core::Model& model, const SweepGrid& grid,
              const SweepSchedule& schedule, const std::vector<int>& compared,
              const Samples& referenceSamples, const std::function<RunFraction(const std::string&)>& report,
              int& index, SweepResult& result)
{
    grid.contact.applyTo(work.contact);
    result.contact = grid.contact;
    for (core::IntegratorKind integrator : grid.integrators)
    {
        for (const run::Method& solver : grid.solvers)
        {
            for (double dt : grid.dts)
            {
                ++index;
                SweepCell cell;
                cell.method = {solver.solver, solver.pgsIterations, integrator};
                cell.dt = dt;
                cell.steps = schedule.units * stepsPerUnit(schedule.unitS, dt);
                cell.bodies = result.bodies;
                if (!runCell(work, model, schedule, compared, referenceSamples,
                             report(cell.method.label() + " dt " + formatSeconds(dt) + " s"), cell))
                {
                    result.interruptedBy = run::interruptSignal();
                    return;
                }
                result.cells.push_back(std::move(cell));
            }
        }
    }
}
} // namespace

SweepResult runSweep(const core::Model& model, const SweepGrid& grid, const SweepSchedule& schedule,
                     const SweepProgress& progress, const ExternalReference* external)
{
    SweepResult result;
    result.schedule = schedule;
    const std::vector<int> bodies = movingBodies(model);
    result.bodies = static_cast<int>(bodies.size());
    const int runCount =
        1 + static_cast<int>(grid.integrators.size() * grid.solvers.size() * grid.dts.size());
    int index = 0; // of the run: the reference is 0
    const auto report = [&](const std::string& run) -> RunFraction
    {
        return [&progress, run, index, runCount](double fraction)
        {
            if (progress)
            {
                progress(run, index, runCount, fraction);
            }
        };
    };

    core::Model work = model;
    std::vector<int> compared = bodies; // the bodies whose distance to the reference is measured
    Samples referenceSamples;
    if (external != nullptr)
    {
        referenceSamples = externalSamples(model, bodies, schedule, *external, compared);
        result.reference.external = external->source;
    }
    else
    {
        referenceSamples = runReference(work, grid, schedule, bodies, report, result.reference);
        if (const int signal = run::interruptSignal(); signal != 0)
        {
            result.interruptedBy = signal;
            return result;
        }
    }

    runCells(work, model, grid, schedule, compared, referenceSamples, report, index, result);
    return result;
}

namespace
{

// One row t,x,y,z (s, m); none when the line is not four numbers.
std::optional<std::array<double, 4>> referenceRow(const std::string& line)
{
    std::array<double, 4> v{};
    std::size_t at = 0;
    bool ok = true;
    for (std::size_t k = 0; k < 4 && ok; ++k)
    {
        const std::size_t end = std::min(line.find(',', at), line.size());
        const std::optional<double> value = io::detail::parseFiniteNumber(trim(line.substr(at, end - at)));
        ok = value.has_value() && (k == 3 ? end == line.size() : end < line.size());
        v[k] = value.value_or(0.0);
        at = end + 1;
    }
    return ok ? std::optional(v) : std::nullopt;
}

// A reference CSV's rows, and the position between them at any time they cover.
struct ReferenceTable
{
    std::string path;
    std::vector<double> times;         // s, increasing
    std::vector<core::Vec3> positions; // m

    core::Vec3 at(double t) const
    {
        constexpr double cTimeTolerance = 1e-9; // s: a sample time this close to a row is the row's
        if (t < times.front() - cTimeTolerance || t > times.back() + cTimeTolerance)
        {
            throw SweepInputError("reference " + path + ": no rows around t = " + std::to_string(t) + " s");
        }
        const std::size_t upper =
            static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), t) - times.begin());
        for (const std::size_t k : {upper, upper - 1})
        {
            if (k < times.size() && std::abs(times[k] - t) <= cTimeTolerance)
            {
                return positions[k];
            }
        }
        // The cubic through the four rows around t (Lagrange form).
        const std::size_t first = std::clamp<std::size_t>(upper, 2, times.size() - 2) - 2;
        core::Vec3 p = core::Vec3::Zero();
        for (std::size_t i = first; i < first + 4; ++i)
        {
            double weight = 1.0;
            for (std::size_t j = first; j < first + 4; ++j)
            {
                if (j != i)
                {
                    weight *= (t - times[j]) / (times[i] - times[j]);
                }
            }
            p += weight * positions[i];
        }
        return p;
    }
};

ReferenceTable readReferenceTable(const std::string& path)
{
    std::istringstream in(io::detail::readTextFile(path, "reference CSV")); // regular files only, bounded
    ReferenceTable table{path, {}, {}};
    std::string line;
    int number = 0;
    while (std::getline(in, line))
    {
        ++number;
        if (line.empty() || line[0] == '#')
        {
            continue;
        }
        const std::optional<std::array<double, 4>> v = referenceRow(line);
        if (!v && table.times.empty() && number == 1)
        {
            continue; // a header
        }
        if (!v || (!table.times.empty() && !((*v)[0] > table.times.back())))
        {
            throw SweepInputError("reference " + path + ":" + std::to_string(number) +
                                  ": expected t,x,y,z (s, m) with t increasing");
        }
        table.times.push_back((*v)[0]);
        table.positions.emplace_back((*v)[1], (*v)[2], (*v)[3]);
    }
    if (table.times.size() < 4)
    {
        throw SweepInputError("reference " + path + ": fewer than 4 rows t,x,y,z");
    }
    return table;
}

} // namespace

ExternalReference readReferenceCsv(const std::string& path, const std::string& body)
{
    ExternalReference reference;
    reference.body = body;
    reference.source = path;
    reference.position_W = [table = readReferenceTable(path)](double t) { return table.at(t); };
    return reference;
}

double accuracyOf(const SweepCell& cell, Accuracy accuracy)
{
    switch (accuracy)
    {
    case Accuracy::JointGap:
        return cell.maxJointErrorM;
    case Accuracy::Penetration:
        return cell.maxPenetrationM;
    case Accuracy::TrajectoryError:
        break;
    }
    return cell.trajectoryErrorM;
}

const char* accuracyName(Accuracy accuracy)
{
    switch (accuracy)
    {
    case Accuracy::JointGap:
        return "joint gap";
    case Accuracy::Penetration:
        return "penetration";
    case Accuracy::TrajectoryError:
        break;
    }
    return "trajectory error";
}

std::vector<std::size_t> paretoFront(const std::vector<SweepCell>& cells, Accuracy accuracy)
{
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < cells.size(); ++i)
    {
        const SweepCell& c = cells[i];
        if (c.survived && std::isfinite(c.secondsPerSimSecond) && std::isfinite(accuracyOf(c, accuracy)))
        {
            candidates.push_back(i);
        }
    }
    // By cost, then error: a cell is on the front when it is more accurate than every cheaper one.
    std::sort(candidates.begin(), candidates.end(),
              [&](std::size_t a, std::size_t b)
              {
                  if (cells[a].secondsPerSimSecond != cells[b].secondsPerSimSecond)
                  {
                      return cells[a].secondsPerSimSecond < cells[b].secondsPerSimSecond;
                  }
                  return accuracyOf(cells[a], accuracy) < accuracyOf(cells[b], accuracy);
              });
    std::vector<std::size_t> front;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i : candidates)
    {
        if (accuracyOf(cells[i], accuracy) < best)
        {
            front.push_back(i);
            best = accuracyOf(cells[i], accuracy);
        }
    }
    return front;
}

} // namespace frontier::study
