// study/sweep_report.cpp: sweep.csv and the terminal table.
#include "study/sweep_report.h"

#include "io/atomic_file.h"
#include "run/run_loop.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

namespace frontier::study
{

const char* const cSweepCsvHeader =
    "scene,integrator,solver,pgs_iterations,dt,steps,bodies,survived,wall_seconds,seconds_per_sim_second,"
    "us_per_body_step,trajectory_error_m,final_error_m,worst_body,max_joint_error_m,max_joint_error_rad,"
    "energy_drift_j,energy_drift_rel,max_penetration_m,failure";

namespace
{
// The shortest text that reads back to the same double ("nan" for NaN).
std::string exact(double value)
{
    if (std::isnan(value))
    {
        return "nan";
    }
    char text[64];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    return error == std::errc() ? std::string(text, end) : std::string("nan");
}

// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180); line breaks
// become spaces so every record stays on one line.
std::string csvField(std::string text)
{
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    if (text.find_first_of(",\"") == std::string::npos)
    {
        return text;
    }
    std::string quoted = "\"";
    for (char c : text)
    {
        quoted += (c == '"') ? std::string("\"\"") : std::string(1, c);
    }
    return quoted + "\"";
}

// "%.3g", or "-" for a quantity that does not exist.
std::string brief(double value)
{
    if (std::isnan(value))
    {
        return "-";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

std::string formatDt(double dt)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", dt);
    return text;
}

// Columns padded to their widest entry: text left-aligned, numbers right-aligned.
std::string alignColumns(const std::vector<std::vector<std::string>>& rows,
                         const std::vector<bool>& leftAligned)
{
    std::vector<std::size_t> widths(leftAligned.size(), 0);
    for (const auto& row : rows)
    {
        for (std::size_t c = 0; c < row.size(); ++c)
        {
            widths[c] = std::max(widths[c], row[c].size());
        }
    }
    std::string out;
    for (const auto& row : rows)
    {
        std::string line;
        for (std::size_t c = 0; c < row.size(); ++c)
        {
            const std::string pad(widths[c] - row[c].size(), ' ');
            line += (c > 0 ? "  " : "") + (leftAligned[c] ? row[c] + pad : pad + row[c]);
        }
        line.erase(line.find_last_not_of(' ') + 1);
        out += line + "\n";
    }
    return out;
}
} // namespace

std::string describeReference(const SweepResult& result)
{
    const SweepReference& r = result.reference;
    char text[512];
    if (!r.external.empty())
    {
        std::snprintf(
            text, sizeof text,
            "reference: %s (not made by a run); errors are the distance of its body's centre of mass "
            "to it over %zu sample times, the last at t = %.6g s",
            r.external.c_str(), result.schedule.sampleUnits.size(), result.schedule.durationS());
        return text;
    }
    std::snprintf(text, sizeof text,
                  "reference: %s at dt %s s (the finest dt / %d), %ld steps in %.3g s wall; errors are the "
                  "largest centre-of-mass distance to it over %zu sample times, the last at t = %.6g s",
                  r.method.label().c_str(), formatDt(r.dt).c_str(), cReferenceRefinement, r.steps,
                  r.wallSeconds, result.schedule.sampleUnits.size(), result.schedule.durationS());
    std::string line = text;
    if (!r.fallback.empty())
    {
        line += " (not " + r.fallback + ")";
    }
    return line;
}

void writeSweepCsv(const std::string& path, const std::string& scene, const SweepResult& result)
{
    io::AtomicFile file(path);
    const SweepReference& r = result.reference;
    std::string text = "# frontier sweep: scene=" + csvField(scene) +
                       " duration=" + exact(result.schedule.durationS()) +
                       " samples=" + std::to_string(result.schedule.sampleUnits.size()) +
                       " reference_integrator=" + core::integratorName(r.method.integrator) +
                       " reference_solver=" + r.method.solverLabel() + " reference_dt=" + exact(r.dt);
    if (result.contact.tolerance)
    {
        text += " contact_tolerance=" + exact(*result.contact.tolerance);
    }
    if (result.contact.relativeTolerance)
    {
        text += " contact_relative_tolerance=" + exact(*result.contact.relativeTolerance);
    }
    if (result.interruptedBy != 0) // the cells finished before the signal, not the whole grid
    {
        text += " interrupted=" + run::signalName(result.interruptedBy);
    }
    text += "\n";
    text += cSweepCsvHeader;
    text += "\n";
    for (const SweepCell& c : result.cells)
    {
        const bool pgs = c.method.solver == core::SolverKind::Pgs;
        const std::string fields[] = {csvField(scene),
                                      core::integratorName(c.method.integrator),
                                      core::solverName(c.method.solver),
                                      pgs ? std::to_string(c.method.pgsIterations) : std::string(),
                                      exact(c.dt),
                                      std::to_string(c.steps),
                                      std::to_string(c.bodies),
                                      c.survived ? "true" : "false",
                                      exact(c.wallSeconds),
                                      exact(c.secondsPerSimSecond),
                                      exact(c.usPerBodyStep),
                                      exact(c.trajectoryErrorM),
                                      exact(c.finalErrorM),
                                      csvField(c.worstBody),
                                      exact(c.maxJointErrorM),
                                      exact(c.maxJointErrorRad),
                                      exact(c.energyDriftJ),
                                      exact(c.energyDriftRel),
                                      exact(c.maxPenetrationM),
                                      csvField(c.failure)};
        for (std::size_t f = 0; f < std::size(fields); ++f)
        {
            text += (f > 0 ? "," : "") + fields[f];
        }
        text += "\n";
    }
    file.write(text);
    file.commit();
}

std::string formatSweepTable(const SweepResult& result, Accuracy accuracy)
{
    std::vector<std::vector<std::string>> rows = {
        {"method", "dt (s)", "steps", "s/sim s", "us/body-step", "traj err (m)", "final err (m)",
         "worst body", "joint gap (m)", "(rad)", "energy drift (J)", "(rel)", "penetration (m)", "result"}};
    const std::vector<bool> left = {true, false, false, false, false, false, false,
                                    true, false, false, false, false, false, true};
    std::map<std::string, int> failureNumbers;
    std::vector<std::string> failures;
    for (const SweepCell& c : result.cells)
    {
        std::string outcome = "ok";
        if (!c.survived)
        {
            auto [it, added] = failureNumbers.emplace(c.failure, static_cast<int>(failures.size()) + 1);
            if (added)
            {
                failures.push_back(c.failure);
            }
            outcome = "FAILED [" + std::to_string(it->second) + "]";
        }
        rows.push_back({c.method.label(), formatDt(c.dt), std::to_string(c.steps),
                        brief(c.secondsPerSimSecond), brief(c.usPerBodyStep), brief(c.trajectoryErrorM),
                        brief(c.finalErrorM), c.worstBody.empty() ? "-" : c.worstBody,
                        brief(c.maxJointErrorM), brief(c.maxJointErrorRad), brief(c.energyDriftJ),
                        brief(c.energyDriftRel), brief(c.maxPenetrationM), outcome});
    }
    std::string out = alignColumns(rows, left);
    for (std::size_t i = 0; i < failures.size(); ++i)
    {
        out += "[" + std::to_string(i + 1) + "] " + failures[i] + "\n";
    }
    const std::vector<std::size_t> front = paretoFront(result.cells, accuracy);
    const std::string measure = accuracyName(accuracy);
    if (front.empty())
    {
        out += "Pareto front on " + measure + ": empty (no cell survived)\n";
        return out;
    }
    out +=
        "Pareto front on " + measure + " (cheapest first; no other cell is both cheaper and more accurate):";
    for (std::size_t k = 0; k < front.size(); ++k)
    {
        const SweepCell& c = result.cells[front[k]];
        out += (k > 0 ? "," : "") + std::string(" ") + c.method.label() + " dt " + formatDt(c.dt) + " s (" +
               brief(c.secondsPerSimSecond) + " s/sim s, " + brief(accuracyOf(c, accuracy)) + " m)";
    }
    out += "\n";
    return out;
}

} // namespace frontier::study
