// bench/peers/harness.cpp
#include "bench/peers/harness.h"

#include "bench/peers/contacts.h"
#include "bench/peers/measures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace frontier::peers
{
namespace
{

constexpr double cNan = std::numeric_limits<double>::quiet_NaN();

// Checks that an engine starts where the model does: a translation error shows here, before any
// step.
void checkStartPose(const core::Model& model, const std::vector<Pose>& poses, const std::string& engine)
{
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
    {
        const double dx = (poses[b].position_W - model.bodies[b].position_W).norm();
        const double dq = poses[b].orientation_WB.angularDistance(model.bodies[b].orientation_WB);
        if (dx > 1e-9 || dq > 1e-9)
            throw std::logic_error(engine + " starts body '" + model.bodies[b].name + "' " +
                                   std::to_string(dx) + " m and " + std::to_string(dq) +
                                   " rad from the model's pose");
    }
}

// A message as one line of a table cell: line breaks become spaces, '|' becomes '/'.
std::string oneLine(std::string s)
{
    for (char& c : s)
        c = c == '\n' || c == '\r' ? ' ' : c == '|' ? '/' : c;
    while (!s.empty() && s.back() == ' ')
        s.pop_back();
    return s;
}

const EngineWarning* firstFullBuffer(const EngineRun& run)
{
    for (const EngineWarning& w : run.warnings)
        if (w.bufferFull)
            return &w;
    return nullptr;
}

// When a warning came: "step 15 first, 186 steps", "at set-up and in 200 steps".
std::string when(const EngineWarning& w)
{
    const auto steps = [](long n) { return std::to_string(n) + (n == 1 ? " step" : " steps"); };
    if (w.firstStep == 0)
        return w.steps == 1 ? "at set-up" : "at set-up and in " + steps(w.steps - 1);
    return "step " + std::to_string(w.firstStep) + " first, " + steps(w.steps);
}

// The engine for the model; none, with the run's failure said, when it refuses the model or fails
// to set up.
std::unique_ptr<Engine> setUpEngine(const std::string& name, const core::Model& model,
                                    const EngineOptions& options, EngineRun& run)
{
    try
    {
        return makeEngine(name, model, options);
    }
    catch (const Unsupported& e)
    {
        run.refused = true;
        run.failure = oneLine(e.what());
    }
    catch (const EngineError& e)
    {
        run.failure = oneLine(e.what()) + " (at set-up)";
    }
    return nullptr;
}

// What is measured on the engine's poses after each step: the joint gap, the penetration and the
// energy by central differences over the last three poses.
struct StepMeasures
{
    const core::Model& model;
    double h; // s
    std::vector<Pose> before{}, middle{}, after{};
    PenetrationMeter penetration{model};
    double firstEnergy = cNan, lastEnergy = cNan, maxKinetic = 0.0; // J

    // After step k (0-based); false when the run blew up.
    bool measure(Engine& engine, long k, EngineRun& run)
    {
        std::swap(before, middle);
        std::swap(middle, after);
        engine.poses(after);
        run.maxGapM = std::max(run.maxGapM, jointGap(model, after));
        run.maxPenetrationM = std::max(run.maxPenetrationM, penetration.deepest(after));
        if (!std::isfinite(run.maxGapM))
        {
            run.failure = "blew up at step " + std::to_string(k + 1);
            return false;
        }
        if (k >= 1)
        {
            const Energy e = energyByDifferences(model, before, middle, after, h);
            if (std::isnan(firstEnergy))
                firstEnergy = e.total;
            lastEnergy = e.total;
            maxKinetic = std::max(maxKinetic, e.kinetic);
        }
        return true;
    }
};

} // namespace

double EngineRun::secondsPerStep() const
{
    return steps > 0 ? secondsStepping / static_cast<double>(steps) : cNan;
}

EngineRun runEngine(const std::string& name, const core::Model& model, const std::vector<Pose>& reference,
                    const RunSettings& settings, const EngineOptions& options)
{
    EngineRun run;
    run.engine = name;
    run.dt = model.simulation.dt;
    run.bufferGrowth = options.bufferGrowth;
    const std::unique_ptr<Engine> engine = setUpEngine(name, model, options, run);
    if (!engine)
        return run;
    run.buffers = engine->bufferSizes();
    const double h = model.simulation.dt;
    const long steps = std::lround(settings.duration / h);
    StepMeasures measures{model, h};
    engine->poses(measures.after);
    checkStartPose(model, measures.after, name);
    using Clock = std::chrono::steady_clock;
    for (long k = 0; k < steps && run.failure.empty(); ++k)
    {
        const auto t0 = Clock::now();
        try
        {
            engine->step();
        }
        catch (const EngineError& e)
        {
            run.failure = oneLine(e.what()) + " (step " + std::to_string(k + 1) + ": the run stopped)";
            break;
        }
        run.secondsStepping += std::chrono::duration<double>(Clock::now() - t0).count();
        ++run.steps;
        engine->checkStep();
        if (!measures.measure(*engine, k, run))
            break;
        if (run.secondsStepping > settings.maxSeconds)
        {
            run.timedOut = true;
            run.failure = "stopped after " + std::to_string(run.steps) + " steps (--max-seconds)";
        }
    }
    run.warnings = engine->warnings();
    if (!run.failure.empty())
        return run;
    run.energyChangeJ = measures.lastEnergy - measures.firstEnergy;
    run.energyChangePercent =
        measures.maxKinetic > 0.0 ? 100.0 * run.energyChangeJ / measures.maxKinetic : cNan;
    if (!reference.empty())
        run.errorM = positionError(measures.after, reference);
    return run;
}

EngineRun runGrowingBuffers(const std::string& name, const core::Model& model,
                            const std::vector<Pose>& reference, const RunSettings& settings,
                            EngineOptions options)
{
    EngineRun run = runEngine(name, model, reference, settings, options);
    std::string grownAfter;
    while (firstFullBuffer(run) && !run.buffers.empty() &&
           2 * options.bufferGrowth <= settings.maxBufferGrowth)
    {
        if (grownAfter.empty())
            grownAfter = oneLine(firstFullBuffer(run)->text) + " (" + run.buffers + ", " +
                         when(*firstFullBuffer(run)) + ")";
        options.bufferGrowth *= 2;
        run = runEngine(name, model, reference, settings, options);
    }
    if (!grownAfter.empty())
        run.grownAfter = "rerun with buffers grown " + std::to_string(options.bufferGrowth) + "x (" +
                         run.buffers + ") after: " + grownAfter;
    return run;
}

std::string note(const EngineRun& run)
{
    std::vector<std::string> parts;
    if (!run.failure.empty())
        parts.push_back(run.failure);
    if (!run.grownAfter.empty())
        parts.push_back(run.grownAfter);
    for (const EngineWarning& w : run.warnings)
        parts.push_back(oneLine(w.text) + " (" + when(w) + ")");
    std::string out;
    for (const std::string& part : parts)
        out += (out.empty() ? "" : "; ") + part;
    return out;
}

Spread spread(std::vector<double> values)
{
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }),
                 values.end());
    Spread out;
    if (values.empty())
        return out;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    out.median = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    out.min = values.front();
    out.max = values.back();
    return out;
}

std::vector<double> pairedRatios(const std::vector<double>& a, const std::vector<double>& b)
{
    std::vector<double> out;
    for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
        out.push_back(a[k] / b[k]);
    return out;
}

Accuracy worstAccuracy(const std::vector<EngineRun>& runs)
{
    Accuracy out;
    if (runs.empty())
        return out;
    const auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
    const auto larger = [](double x, double y) {
        return std::isnan(x) ? y : std::isnan(y) ? x : std::max(x, y);
    };
    const EngineRun& first = runs.front();
    out.maxGapM = first.maxGapM;
    out.maxPenetrationM = first.maxPenetrationM;
    out.energyChangeJ = first.energyChangeJ;
    out.energyChangePercent = first.energyChangePercent;
    out.errorM = first.errorM;
    for (const EngineRun& r : runs)
    {
        out.agree = out.agree && r.steps == first.steps && same(r.maxGapM, first.maxGapM) &&
                    same(r.maxPenetrationM, first.maxPenetrationM) &&
                    same(r.energyChangeJ, first.energyChangeJ) && same(r.errorM, first.errorM);
        out.maxGapM = larger(out.maxGapM, r.maxGapM);
        out.maxPenetrationM = larger(out.maxPenetrationM, r.maxPenetrationM);
        out.errorM = larger(out.errorM, r.errorM);
        if (std::isnan(out.energyChangeJ) ||
            (!std::isnan(r.energyChangeJ) && std::abs(r.energyChangeJ) > std::abs(out.energyChangeJ)))
        {
            out.energyChangeJ = r.energyChangeJ;
            out.energyChangePercent = r.energyChangePercent;
        }
    }
    return out;
}

} // namespace frontier::peers
