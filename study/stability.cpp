// study/stability.cpp: the stability suite's runs and its markdown report.
#include "study/stability.h"

#include "collision/filter.h"
#include "core/impulse_solver.h"
#include "core/state.h"
#include "core/step/drift_correction.h"
#include "run/run_loop.h"
#include "study/stability_criteria.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <thread>

namespace frontier::study
{

// The run loop of `frontier run` (run/run_loop.h).
using run::Recorder;
using run::RunSettings;
using run::runSimulation;
using run::RunSummary;
using run::stepsFor;

std::vector<run::Method> defaultStabilityMethods()
{
    using core::IntegratorKind;
    using core::SolverKind;
    return {{SolverKind::Linear, 20, IntegratorKind::Euler},
            {SolverKind::Linear, 20, IntegratorKind::Rattle},
            {SolverKind::Dense, 20, IntegratorKind::Euler},
            {SolverKind::Pgs, 20, IntegratorKind::Euler},
            {SolverKind::Pgs, 100, IntegratorKind::Euler}};
}

namespace
{

// No gravity, no static body, no joint to the world: total angular momentum is conserved.
bool isFreeSystem(const core::Model& model)
{
    if (model.simulation.gravity.norm() > 0.0)
    {
        return false;
    }
    for (const core::Body& body : model.bodies)
    {
        if (body.isStatic)
        {
            return false;
        }
    }
    for (const core::Joint& joint : model.joints)
    {
        if (joint.parent == core::cWorld)
        {
            return false;
        }
    }
    return true;
}

// A static box or plane that moving centres of mass must never pass through.
struct Barrier
{
    int body = 0;       // the static body
    bool plane = false; // else a box
    core::Vec3 normal = core::Vec3::UnitZ();
    double offset = 0.0;
    core::Vec3 centre_W = core::Vec3::Zero();
    core::Quat rotation_WS = core::Quat::Identity();
    core::Vec3 halfSize = core::Vec3::Zero(); // m
};

std::vector<Barrier> barriers(const core::Model& model)
{
    std::vector<Barrier> out;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const core::Body& body = model.bodies[i];
        if (!body.isStatic)
        {
            continue;
        }
        for (const core::Shape& shape : body.shapes)
        {
            Barrier barrier;
            barrier.body = static_cast<int>(i);
            if (shape.type == core::ShapeType::Plane)
            {
                barrier.plane = true;
                barrier.normal = shape.normal;
                barrier.offset = shape.offset;
            }
            else if (shape.type == core::ShapeType::Box)
            {
                barrier.centre_W = body.position_W + body.orientation_WB * shape.position_BS;
                barrier.rotation_WS = body.orientation_WB * shape.rotation_BS;
                barrier.halfSize = 0.5 * shape.size;
            }
            else
            {
                continue;
            }
            out.push_back(barrier);
        }
    }
    return out;
}

bool insideBox(const Barrier& barrier, const core::Vec3& p_W)
{
    const core::Vec3 p = barrier.rotation_WS.conjugate() * (p_W - barrier.centre_W);
    return (p.cwiseAbs() - barrier.halfSize).maxCoeff() < 0.0;
}

// True when the segment from a to b (world, both outside the box) passes through the box.
bool segmentCrossesBox(const Barrier& barrier, const core::Vec3& a_W, const core::Vec3& b_W)
{
    const core::Quat toBox = barrier.rotation_WS.conjugate();
    const core::Vec3 a = toBox * (a_W - barrier.centre_W);
    const core::Vec3 d = toBox * (b_W - barrier.centre_W) - a;
    double enter = 0.0;
    double leave = 1.0;
    for (int k = 0; k < 3; ++k)
    {
        const double h = barrier.halfSize[k];
        if (std::abs(d[k]) < 1e-300)
        {
            if (std::abs(a[k]) >= h)
            {
                return false;
            }
            continue;
        }
        double t0 = (-h - a[k]) / d[k];
        double t1 = (h - a[k]) / d[k];
        if (t0 > t1)
        {
            std::swap(t0, t1);
        }
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
        if (enter > leave)
        {
            return false;
        }
    }
    return true;
}

std::string format(const char* pattern, double value)
{
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// From a core::SimulationError: "came apart at t = 0.533 s (joint 'wrist_left', 0.033 rad)" for a
// joint that let go, "blew up at t = ... s" for a runaway quantity.
std::string failureNote(const std::optional<core::SimulationFailure>& failure, double fallbackTime)
{
    const double time = failure ? failure->time : fallbackTime;
    std::string note = "at t = " + format("%.3g", time) + " s";
    if (!failure || !failure->joint || !failure->gap)
    {
        return "blew up " + note;
    }
    return "came apart " + note + " (joint '" + failure->jointName + "', " + format("%.2g", *failure->gap) +
           (failure->gapInRadians() ? " rad" : " m") + ")";
}

} // namespace

double stabilityEnergyScale(const core::Model& model)
{
    const core::State state = core::initialState(model);
    double mass = 0.0;
    core::Vec3 low = core::Vec3::Constant(std::numeric_limits<double>::infinity());
    core::Vec3 high = -low;
    for (const core::Body& body : model.bodies)
    {
        if (!body.isStatic)
        {
            mass += body.mass;
            low = low.cwiseMin(body.position_W);
            high = high.cwiseMax(body.position_W);
        }
    }
    const double diagonal = mass > 0.0 ? (high - low).norm() : 0.0;
    return std::max(core::kineticEnergy(model, state) + mass * model.simulation.gravity.norm() * diagonal,
                    1e-9);
}

int denseRows(const core::Model& model)
{
    int rows = 0;
    for (const core::Body& body : model.bodies)
    {
        rows += body.isStatic ? 0 : 6;
    }
    for (const core::Joint& joint : model.joints)
    {
        rows += core::jointRowCount(joint.type);
    }
    return rows;
}

namespace
{
// Centres tunnelling through static barriers, watched on every recorded state. A centre tunnels
// when it ends below a static plane, or leaves a static box on the other side from where it
// came: lastOutside keeps, per body and box, its last position outside the box, and the segment
// from there to the next position outside must not cross the box (a centre that sinks into a box
// and is pushed back out the way it came stays on one side of the face it entered by, so that
// segment misses the box).
class TunnelWatch
{
  public:
    explicit TunnelWatch(const core::Model& model)
        : mModel(model), mWalls(barriers(model)), mBodies(model.bodies.size()),
          mWatched(mWalls.size() * mBodies, 0), mSeenOutside(mWalls.size() * mBodies, 0),
          mLastOutside(mWalls.size() * mBodies, core::Vec3::Zero())
    {
        const collision::PairFilter pairs(model);
        for (std::size_t w = 0; w < mWalls.size(); ++w)
        {
            for (std::size_t i = 0; i < mBodies; ++i)
            {
                mWatched[w * mBodies + i] =
                    !model.bodies[i].isStatic && pairs.allowed(static_cast<int>(i), mWalls[w].body);
            }
        }
    }

    // Sets tunnelled ("'body' through 'static' at t = ... s") at the first centre through.
    void observe(const core::State& state, std::string& tunnelled)
    {
        for (std::size_t w = 0; w < mWalls.size(); ++w)
        {
            const Barrier& wall = mWalls[w];
            for (std::size_t i = 0; i < mBodies; ++i)
            {
                const std::size_t k = w * mBodies + i;
                if (!mWatched[k])
                {
                    continue;
                }
                const core::Vec3& p = state.bodies[i].position_W;
                bool through = false;
                if (wall.plane)
                {
                    through = wall.normal.dot(p) < wall.offset;
                }
                else if (!insideBox(wall, p))
                {
                    through = mSeenOutside[k] && segmentCrossesBox(wall, mLastOutside[k], p);
                    mSeenOutside[k] = 1;
                    mLastOutside[k] = p;
                }
                if (through && tunnelled.empty())
                {
                    tunnelled = "'" + mModel.bodies[i].name + "' through '" +
                                mModel.bodies[static_cast<std::size_t>(wall.body)].name +
                                "' at t = " + format("%.4g", state.time) + " s";
                }
            }
        }
    }

  private:
    const core::Model& mModel;
    std::vector<Barrier> mWalls;
    std::size_t mBodies;
    std::vector<char> mWatched; // moving body i can collide with wall w
    std::vector<char> mSeenOutside;
    std::vector<core::Vec3> mLastOutside;
};

// Energy (into the cell) and the drift of the total angular momentum over the recorded states.
struct ConservationTrack
{
    void observe(const core::Model& model, const core::State& state, StabilityCell& cell)
    {
        const double energy = core::totalEnergy(model, state);
        const core::Vec3 momentum = core::totalMomentum(model, state).angular;
        if (first)
        {
            cell.energyInitialJ = cell.energyMaxJ = cell.energyMinJ = energy;
            momentum0 = momentum;
            first = false;
        }
        cell.energyMaxJ = std::max(cell.energyMaxJ, energy);
        cell.energyMinJ = std::min(cell.energyMinJ, energy);
        momentumDrift = std::max(momentumDrift, (momentum - momentum0).norm());
    }

    core::Vec3 momentum0 = core::Vec3::Zero();
    double momentumDrift = 0.0;
    bool first = true;
};

// The scene with the method's solver and integrator, and limits.dt and limits.duration when given.
core::Model cellModel(const core::Model& scene, const run::Method& method, const StabilityLimits& limits)
{
    core::Model model = scene;
    method.applyTo(model.simulation);
    if (limits.duration)
    {
        model.simulation.duration = *limits.duration;
    }
    if (limits.dt)
    {
        model.simulation.dt = *limits.dt;
    }
    return model;
}

// A run that ended still fails when a centre tunnelled or a joint came apart beyond the limits.
void judgeSurvivor(const StabilityLimits& limits, StabilityCell& cell)
{
    if (cell.outcome != StabilityOutcome::Survived)
    {
        return;
    }
    if (!cell.tunnelled.empty())
    {
        cell.outcome = StabilityOutcome::Failed;
        cell.note = "tunnelled: " + cell.tunnelled;
    }
    else if (cell.maxJointGapM > limits.maxJointGapM || cell.maxJointGapRad > limits.maxJointGapRad)
    {
        cell.outcome = StabilityOutcome::Failed;
        cell.note = cell.maxJointGapM > limits.maxJointGapM
                        ? "came apart (gap " + format("%.2g", cell.maxJointGapM) + " m)"
                        : "came apart (gap " + format("%.2g", cell.maxJointGapRad) + " rad)";
    }
}
// Runs the cell's model, its figures into the cell; false when the method cannot run the model.
bool simulateCell(const core::Model& model, const run::Recorder& record, StabilityCell& cell)
{
    run::RunSettings settings;
    settings.steps = cell.steps;
    try
    {
        const run::RunSummary summary = run::runSimulation(model, settings, record);
        cell.wallSeconds = summary.wallSeconds;
        cell.maxJointGapM = summary.maxJointErrorM;
        cell.maxJointGapRad = summary.maxJointErrorRad;
        cell.maxPenetrationM = summary.maxPenetrationM;
        if (!summary.finite)
        {
            cell.outcome = StabilityOutcome::Failed;
            cell.note =
                failureNote(summary.failureDetails, static_cast<double>(summary.steps) * model.simulation.dt);
            cell.failure = summary.failure;
        }
    }
    catch (const core::UnsupportedModelError&)
    {
        cell.outcome = StabilityOutcome::Unavailable;
        cell.note = "not available";
        return false;
    }
    catch (const core::SingularJointError& e)
    {
        cell.outcome = StabilityOutcome::Failed;
        cell.failure = e.what();
        cell.note = "singular joint '" + e.jointName() + "' at t = " +
                    format("%.3g", static_cast<double>(cell.stepsRun + 1) * model.simulation.dt) + " s";
    }
    return true;
}
} // namespace

StabilityCell runStabilityCell(const core::Model& scene, const std::string& sceneName,
                               const run::Method& method, const StabilityLimits& limits,
                               const io::SceneStabilityCriteria& criteria)
{
    const core::Model model = cellModel(scene, method, limits);
    StabilityCell cell;
    cell.scene = sceneName;
    cell.method = method.label();
    cell.dt = model.simulation.dt;
    cell.steps = std::max(1L, run::stepsFor(model.simulation.duration, model.simulation.dt));
    cell.energyScaleJ = stabilityEnergyScale(model);
    cell.passive = run::isPassive(model);
    if (method.solver == core::SolverKind::Dense && denseRows(model) > limits.maxDenseRows)
    {
        cell.outcome = StabilityOutcome::Skipped;
        cell.note = "skipped (dense, " + std::to_string(denseRows(model)) + " rows)";
        return cell;
    }

    // Measured on every recorded state: energy, angular momentum, centres tunnelling, speeds and
    // the scene's own criteria.
    const bool free = isFreeSystem(model);
    TunnelWatch tunnels(model);
    ConservationTrack conservation;
    CriteriaWatch watch(model, criteria);
    const run::Recorder record = [&](const core::State& state, const core::Simulator*)
    {
        conservation.observe(model, state, cell);
        cell.stepsRun = state.step;
        tunnels.observe(state, cell.tunnelled);
        watch.observe(state, cell);
    };

    if (!simulateCell(model, record, cell))
    {
        return cell;
    }
    if (free)
    {
        cell.momentumDrift = conservation.momentumDrift / std::max(conservation.momentum0.norm(), 1e-300);
    }
    judgeSurvivor(limits, cell);
    watch.judge(cell);
    return cell;
}

namespace
{

std::string sci(double value)
{
    if (value == 0.0)
    {
        return "0";
    }
    return format("%.1e", value);
}

std::string percent(double fraction)
{
    if (std::abs(fraction) < 5e-7)
    {
        return "0";
    }
    return format(std::abs(fraction) < 1e-2 ? "%.2g%%" : "%.3g%%", 100.0 * fraction);
}

std::string overviewText(const StabilityCell& cell)
{
    switch (cell.outcome)
    {
    case StabilityOutcome::Survived:
        // Energy gained is a failure of its own kind (energy lost may be physics: contacts), where
        // nothing in the scene adds energy (actuators and loads may).
        return cell.passive && cell.energyRise() > 0.01 ? "ok, but energy +" + percent(cell.energyRise())
                                                        : std::string("ok");
    case StabilityOutcome::Failed:
        return "**FAILED**: " + cell.note;
    case StabilityOutcome::Unavailable:
        return "not available";
    case StabilityOutcome::Skipped:
        return cell.note;
    }
    return "";
}

// "1/240 s (4.17 ms)": a step of the halving from 1/30 s as its fraction, others as seconds.
std::string stepText(double dt)
{
    const double inverse = 1.0 / dt;
    const std::string exact = std::abs(inverse - std::round(inverse)) < 1e-9 * inverse
                                  ? "1/" + format("%.0f", inverse) + " s"
                                  : format("%.3g", dt) + " s";
    return exact + (dt >= 1e-3 ? format(" (%.3g ms)", 1e3 * dt) : format(" (%.3g us)", 1e6 * dt));
}

std::string largestText(const LargestDtCell& cell)
{
    switch (cell.outcome)
    {
    case StabilityOutcome::Survived:
        return cell.dt ? stepText(*cell.dt) : std::string("");
    case StabilityOutcome::Failed:
        return "none down to " + stepText(cell.smallestTriedDt) + ": " + cell.note;
    case StabilityOutcome::Unavailable:
        return "not available";
    case StabilityOutcome::Skipped:
        return cell.note;
    }
    return "";
}

// The watched joints of a cell: "-0.02 .. 4.00 rad; off target 3.1e-04 rad".
std::string watchedText(const StabilityCell& cell)
{
    std::string text;
    if (cell.angleLowRad && cell.angleHighRad)
    {
        text = format("%.3g", *cell.angleLowRad) + " .. " + format("%.3g", *cell.angleHighRad) + " rad";
    }
    if (cell.maxTrackingErrorRad)
    {
        text += (text.empty() ? "" : "; ") + ("off target " + sci(*cell.maxTrackingErrorRad) + " rad");
    }
    return text;
}

// Cells by (scene, method label).
template <class Cell>
std::map<std::pair<std::string, std::string>, const Cell*> cellsByKey(const std::vector<Cell>& cells)
{
    std::map<std::pair<std::string, std::string>, const Cell*> byKey;
    for (const Cell& cell : cells)
    {
        byKey[{cell.scene, cell.method}] = &cell;
    }
    return byKey;
}

// A table of a row per scene and a column per method, each cell text(cell), empty where there is
// no cell.
template <class Cell>
void writeMethodTable(std::ostream& out, const std::vector<std::string>& sceneNames,
                      const std::vector<run::Method>& methods,
                      const std::map<std::pair<std::string, std::string>, const Cell*>& byKey,
                      std::string (*text)(const Cell&))
{
    out << "| scene |";
    for (const run::Method& method : methods)
    {
        out << " " << method.label() << " |";
    }
    out << "\n|---|";
    for (std::size_t m = 0; m < methods.size(); ++m)
    {
        out << "---|";
    }
    out << "\n";
    for (const std::string& scene : sceneNames)
    {
        out << "| " << scene << " |";
        for (const run::Method& method : methods)
        {
            const auto it = byKey.find({scene, method.label()});
            out << " " << (it == byKey.end() ? std::string("") : text(*it->second)) << " |";
        }
        out << "\n";
    }
}

// The scenes' table: moving bodies, joint rows, dt, duration, E_ref and own criteria.
void writeSceneTable(std::ostream& out, const std::vector<core::Model>& scenes,
                     const std::vector<std::string>& sceneNames, const StabilityLimits& limits,
                     const StabilityReportExtras& extras)
{
    out << "\nThe scenes: energy drift is relative to E_ref = initial kinetic energy + M |g| D (M the moving "
           "mass, D the diagonal of the box holding the initial centres of mass). A scene's own criteria "
           "(its `stability:` map) fail a run that survives but breaks one.\n\n"
           "| scene | moving bodies | joint rows | dt (s) | duration (s) | E_ref (J) | own criteria "
           "|\n|---|---|---|---|---|---|---|\n";
    for (std::size_t s = 0; s < scenes.size(); ++s)
    {
        const core::Model& model = scenes[s];
        int moving = 0;
        for (const core::Body& body : model.bodies)
        {
            moving += body.isStatic ? 0 : 1;
        }
        const double duration = limits.duration ? *limits.duration : model.simulation.duration;
        const double dt = limits.dt ? *limits.dt : model.simulation.dt;
        out << "| " << sceneNames[s] << " | " << moving << " | " << denseRows(model) - 6 * moving << " | "
            << format("%.4g", dt) << " | " << format("%g", duration) << " | "
            << format("%.4g", stabilityEnergyScale(model)) << " | "
            << (s < extras.criteria.size() ? criteriaText(model, extras.criteria[s]) : std::string())
            << " |\n";
    }
}

// A row of the details table.
void writeDetailRow(std::ostream& out, const std::string& scene, const StabilityCell& c)
{
    out << "| " << scene << " | " << c.method << " | ";
    if (c.outcome == StabilityOutcome::Unavailable || c.outcome == StabilityOutcome::Skipped)
    {
        out << c.note << " | | | | | | | | | |\n";
        return;
    }
    out << (c.survived() ? std::string("ok") : "**FAILED**: " + c.note) << " | " << sci(c.maxJointGapM)
        << " | " << sci(c.maxJointGapRad) << " | " << percent(c.energyRise()) << " | "
        << percent(c.energyLoss()) << " | " << (c.momentumDrift ? sci(*c.momentumDrift) : "") << " | "
        << sci(c.maxPenetrationM) << " | " << format("%.3g", c.maxSpeedMps) << " | " << watchedText(c)
        << " | " << format("%.2f", c.wallSeconds) << " |\n";
}

void writeDetailTable(std::ostream& out, const std::vector<std::string>& sceneNames,
                      const std::vector<run::Method>& methods,
                      const std::map<std::pair<std::string, std::string>, const StabilityCell*>& byKey)
{
    out << "\nDetails: the largest joint gap over the run (positional, angular), the energy's largest rise "
           "above and fall below its initial value (relative to E_ref), the total angular momentum's "
           "largest relative change (free systems only), the deepest contact overlap, the largest speed of a "
           "centre of mass, the watched joints' angle range and distance from their servo's target, and the "
           "wall time.\n\n"
           "| scene | method | result | joint gap (m) | joint gap (rad) | energy rise | energy loss | "
           "L drift | penetration (m) | max speed (m/s) | watched joints | wall (s) "
           "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& scene : sceneNames)
    {
        for (const run::Method& method : methods)
        {
            const auto it = byKey.find({scene, method.label()});
            if (it != byKey.end())
            {
                writeDetailRow(out, scene, *it->second);
            }
        }
    }
}

} // namespace

std::string stabilityMarkdown(const std::vector<core::Model>& scenes,
                              const std::vector<std::string>& sceneNames,
                              const std::vector<run::Method>& methods,
                              const std::vector<StabilityCell>& cells, const StabilityLimits& limits,
                              const std::string& machine, const StabilityReportExtras& extras)
{
    const auto byKey = cellsByKey(cells);
    std::ostringstream out;
    out << "Each scene (`scenes/stability/`) run for its duration with each method (`solver/integrator`). "
           "A run fails when it blows up, a joint comes apart (gap above "
        << format("%g", limits.maxJointGapM) << " m or " << format("%g", limits.maxJointGapRad)
        << " rad over the run, or above " << format("%g", core::cJointBlowUp)
        << " m or rad after a step's drift correction), a joint block becomes singular, or a centre of mass "
           "tunnels through a static box or plane. Wall times on "
        << machine << ", one run at a time.\n\n";
    writeMethodTable(out, sceneNames, methods, byKey, overviewText);
    writeSceneTable(out, scenes, sceneNames, limits, extras);
    if (!extras.largest.empty())
    {
        out << "\nWhere it ends: the largest time step at which each scene still holds (survives and meets "
               "its own criteria), halving from "
            << stepText(extras.search.start) << ", each run for the scene's duration or "
            << format("%g", extras.search.duration)
            << " s if shorter (a failure that comes later is not seen), stopping at the first step that "
               "holds or after the first step below the scene's own that fails.\n\n";
        writeMethodTable(out, sceneNames, methods, cellsByKey(extras.largest), largestText);
    }
    writeDetailTable(out, sceneNames, methods, byKey);
    return out.str();
}

std::string machineDescription()
{
    std::string model = "an unknown CPU";
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line))
    {
        if (line.rfind("model name", 0) == 0)
        {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos)
            {
                model = line.substr(colon + 1);
                model.erase(0, model.find_first_not_of(" \t"));
            }
            break;
        }
    }
    const unsigned cores = std::thread::hardware_concurrency();
    return std::to_string(cores) + (cores == 1 ? " core, " : " cores, ") + model;
}

} // namespace frontier::study
