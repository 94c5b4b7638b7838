// app/batch/merge.cpp: `frontier batch --merge`: DIR/batch.csv (one row per job, in job order),
// DIR/summary.md, and with --chart X,Y the chart DIR/chart.png (drawn as the sweep's, by gnuplot).
#include "app/batch/batch.h"
#include "app/batch/scene.h"
#include "app/sweep_chart.h"
#include "io/atomic_file.h"
#include "io/csv_output.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/stats.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

struct MergedJob
{
    std::string status; // done, failed, missing, stale (done from inputs that have changed since)
    std::optional<io::RunStats> stats;
};

// The inputs digest of each job now (BatchScene::inputsDigest), "" when its scene does not load.
// Jobs that differ only in run settings and seed values read the same inputs, so each scene with
// its scene-path settings is loaded once.
class CurrentDigests
{
  public:
    CurrentDigests(const BatchPlan& plan, const io::UrdfOptions& urdf) : mPlan(plan), mUrdf(urdf) {}

    const std::string& of(const PlanJob& job)
    {
        std::string key = job.scenePath;
        for (const BatchSetting& s : job.settings)
        {
            if (s.key == "seed" || !isRunSetting(s.key)) // a seed's value changes no input
            {
                key += "\n" + s.key + (s.key == "seed" ? "" : "=" + s.value);
            }
        }
        const auto known = mDigests.find(key);
        return known != mDigests.end() ? known->second : mDigests[key] = load(job);
    }

  private:
    std::string load(const PlanJob& job) const
    {
        try
        {
            return loadBatchScene(mPlan, job, mUrdf).inputsDigest;
        }
        catch (const io::InputError& e)
        {
            std::cerr << "frontier: note: job " << job.id << ": its scene does not load now: " << e.what()
                      << "\n";
            return {};
        }
    }

    const BatchPlan& mPlan;
    const io::UrdfOptions& mUrdf;
    std::map<std::string, std::string> mDigests;
};

// Wall-clock keys of the stats: they differ from run to run, so they come last, named wall_*.
bool isWallClock(const std::string& key)
{
    return key == "wall_seconds" || key.rfind("seconds_per_step", 0) == 0;
}

std::string wallColumn(const std::string& key)
{
    return key.rfind("wall_", 0) == 0 ? key : "wall_" + key;
}

std::string number(double value)
{
    std::string out;
    io::appendNumber(out, value);
    return out;
}

// The value of a stats column as CSV text (empty when the job has no stats or lacks the key).
std::string statsField(const io::RunStats& s, const std::string& key)
{
    if (key == "solver")
        return s.solver;
    if (key == "integrator")
        return s.integrator;
    if (key == "pgs_iterations")
        return std::to_string(s.pgsIterations);
    if (key == "dt")
        return number(s.dt);
    if (key == "steps")
        return std::to_string(s.steps);
    if (key == "simulated_seconds")
        return number(s.simulatedSeconds);
    if (key == "bodies")
        return std::to_string(s.bodies);
    if (key == "static_bodies")
        return std::to_string(s.staticBodies);
    if (key == "joints")
        return std::to_string(s.joints);
    if (key == "constraint_rows")
        return std::to_string(s.constraintRows);
    if (key == "degrees_of_freedom")
        return std::to_string(s.degreesOfFreedom);
    if (key == "max_joint_error_m")
        return number(s.maxJointErrorM);
    if (key == "max_penetration_m")
        return number(s.maxPenetrationM);
    if (key == "energy_initial_j")
        return number(s.energyInitialJ);
    if (key == "energy_final_j")
        return number(s.energyFinalJ);
    if (key == "max_contacts")
        return std::to_string(s.maxContacts);
    if (key == "finite")
        return s.finite ? "true" : "false";
    if (key == "completed")
        return s.completed ? "true" : "false";
    if (key == "wall_seconds")
        return number(s.wallSeconds);
    if (key == "seconds_per_step")
        return number(s.secondsPerStep);
    const auto it = s.extra.find(key);
    return it == s.extra.end() ? std::string() : number(it->second);
}

// The figures of each actuator (io::ActuatorStats), a column each: actuator.<joint>.<figure>.
constexpr const char* cActuatorFigures[] = {"tracking_rms", "tracking_max", "effort_rms", "effort_max",
                                            "limit_steps"};

// The columns' prefix of an actuator of a job: actuator.<joint>, with .<coordinate> when two
// actuators of the job drive that joint (a cylindrical joint's slide and rotation).
std::string actuatorPrefix(const io::RunStats& s, const io::ActuatorStats& a)
{
    const auto drivers = std::count_if(s.actuators.begin(), s.actuators.end(),
                                       [&](const io::ActuatorStats& b) { return b.joint == a.joint; });
    return "actuator." + a.joint + (drivers > 1 ? "." + a.coordinate : "");
}

// A figure of an actuator as CSV text; empty where it does not exist (an effort actuator's tracking).
std::string actuatorField(const io::ActuatorStats& a, const std::string& figure)
{
    const double value = figure == "tracking_rms"   ? a.trackingRms
                         : figure == "tracking_max" ? a.trackingMax
                         : figure == "effort_rms"   ? a.effortRms
                         : figure == "effort_max"   ? a.effortMax
                                                    : static_cast<double>(a.limitSteps);
    return a.type == "effort" && figure.rfind("tracking", 0) == 0 ? std::string() : number(value);
}

std::string csvField(const std::string& text)
{
    std::string out;
    io::appendName(out, text);
    return out;
}

struct Table
{
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
};

// The stats columns: the stats JSON's keys (docs/files.md), then the extra ones; the wall-clock
// ones apart (they go last). The scene and the failure have columns of their own; the warnings and
// the inputs (digest and files) none; the actuators theirs (actuatorPrefixes); a varied setting has
// its column already (the value as the plan gives it).
struct StatsColumns
{
    std::vector<std::string> stats;
    std::vector<std::string> wall;
};

StatsColumns statsColumns(const BatchPlan& plan, const std::vector<MergedJob>& results)
{
    std::set<std::string> extra;
    for (const MergedJob& r : results)
    {
        if (r.stats)
        {
            for (const auto& [key, value] : r.stats->extra)
            {
                extra.insert(key);
            }
        }
    }
    StatsColumns columns;
    for (const std::string& key : io::statsKeys())
    {
        if (key != "scene" && key != "failure" && key != "warnings" && key != "inputs_digest" &&
            key != "input_files" && key != "actuators")
        {
            (isWallClock(key) ? columns.wall : columns.stats).push_back(key);
        }
    }
    for (const std::string& key : extra)
    {
        (isWallClock(key) ? columns.wall : columns.stats).push_back(key);
    }
    std::erase_if(
        columns.stats, [&](const std::string& key)
        { return std::find(plan.varyKeys.begin(), plan.varyKeys.end(), key) != plan.varyKeys.end(); });
    return columns;
}

// The actuators' column prefixes, grouped by actuator in the order the jobs first name them.
std::vector<std::string> actuatorPrefixes(const std::vector<MergedJob>& results)
{
    std::vector<std::string> prefixes;
    for (const MergedJob& r : results)
    {
        for (std::size_t a = 0; r.stats && a < r.stats->actuators.size(); ++a)
        {
            const std::string prefix = actuatorPrefix(*r.stats, r.stats->actuators[a]);
            if (std::find(prefixes.begin(), prefixes.end(), prefix) == prefixes.end())
            {
                prefixes.push_back(prefix);
            }
        }
    }
    return prefixes;
}

// job, scene, the varied settings, status, stats, actuators, failure, wall clock.
std::vector<std::string> tableHeader(const BatchPlan& plan, const StatsColumns& columns,
                                     const std::vector<std::string>& prefixes)
{
    std::vector<std::string> header = {"job", "scene"};
    header.insert(header.end(), plan.varyKeys.begin(), plan.varyKeys.end());
    header.push_back("status");
    header.insert(header.end(), columns.stats.begin(), columns.stats.end());
    for (const std::string& prefix : prefixes)
    {
        for (const char* figure : cActuatorFigures)
        {
            header.push_back(prefix + "." + figure);
        }
    }
    header.push_back("failure");
    for (const std::string& key : columns.wall)
    {
        header.push_back(wallColumn(key));
    }
    return header;
}

// One job's row, in the header's order.
std::vector<std::string> tableRow(const PlanJob& job, const MergedJob& r, const StatsColumns& columns,
                                  const std::vector<std::string>& prefixes)
{
    std::vector<std::string> row = {job.id, job.scene};
    for (const BatchSetting& s : job.variation)
    {
        row.push_back(s.value);
    }
    row.push_back(r.status);
    for (const std::string& key : columns.stats)
    {
        row.push_back(r.stats ? statsField(*r.stats, key) : "");
    }
    for (const std::string& prefix : prefixes)
    {
        const io::ActuatorStats* actuator = nullptr;
        for (std::size_t a = 0; r.stats && a < r.stats->actuators.size(); ++a)
        {
            if (actuatorPrefix(*r.stats, r.stats->actuators[a]) == prefix)
            {
                actuator = &r.stats->actuators[a];
            }
        }
        for (const char* figure : cActuatorFigures)
        {
            row.push_back(actuator ? actuatorField(*actuator, figure) : "");
        }
    }
    row.push_back(r.stats ? r.stats->failure : "");
    for (const std::string& key : columns.wall)
    {
        row.push_back(r.stats ? statsField(*r.stats, key) : "");
    }
    return row;
}

Table makeTable(const BatchPlan& plan, const std::vector<MergedJob>& results)
{
    const StatsColumns columns = statsColumns(plan, results);
    const std::vector<std::string> prefixes = actuatorPrefixes(results);
    Table table;
    table.header = tableHeader(plan, columns, prefixes);
    for (std::size_t j = 0; j < plan.jobs.size(); ++j)
    {
        table.rows.push_back(tableRow(plan.jobs[j], results[j], columns, prefixes));
    }
    return table;
}

void writeCsv(const std::string& path, const BatchPlan& plan, const Table& table)
{
    std::string header;
    for (const std::string& name : table.header)
    {
        header += (header.empty() ? "" : ",") + csvField(name);
    }
    io::CsvFile file(
        path, "batch",
        {{"plan", fs::path(plan.file).filename().string()}, {"jobs", std::to_string(plan.jobs.size())}},
        header.c_str());
    for (const std::vector<std::string>& row : table.rows)
    {
        std::string line;
        for (std::size_t k = 0; k < row.size(); ++k)
        {
            line += (k == 0 ? "" : ",") + csvField(row[k]);
        }
        file.writeRow(line);
    }
    file.commit();
}

// A markdown table cell: no line breaks, '|' escaped.
std::string cell(const std::string& text)
{
    std::string out;
    for (const char c : text)
    {
        out += c == '|' ? std::string("\\|") : std::string(1, c == '\n' || c == '\r' ? ' ' : c);
    }
    return out;
}

// summary.md's table of the failed jobs: id, scene, variation, message.
std::string failedJobsTable(const BatchPlan& plan, const std::vector<MergedJob>& results)
{
    std::string out = "\n## Failed jobs\n\n| job | scene | variation | message |\n|---|---|---|---|\n";
    for (std::size_t j = 0; j < plan.jobs.size(); ++j)
    {
        if (results[j].status == "failed")
        {
            out += "| " + plan.jobs[j].id + " | " + cell(plan.jobs[j].scene) + " | " +
                   cell(describeVariation(plan.jobs[j])) + " | " + cell(results[j].stats->failure) + " |\n";
        }
    }
    return out;
}

void writeSummary(const std::string& path, const BatchPlan& plan, const std::vector<MergedJob>& results)
{
    std::size_t done = 0, failed = 0, missing = 0, stale = 0;
    double simulatedS = 0.0, wallS = 0.0;
    for (const MergedJob& r : results)
    {
        done += r.status == "done";
        failed += r.status == "failed";
        missing += r.status == "missing";
        stale += r.status == "stale";
        if (r.stats)
        {
            simulatedS += r.stats->simulatedSeconds;
            wallS += r.stats->wallSeconds;
        }
    }
    char text[512];
    std::snprintf(text, sizeof text,
                  "# Batch %s\n\n%zu jobs: %zu done, %zu failed, %zu missing (not run, or not finished), "
                  "%zu stale (their inputs changed since they ran: run the batch again).\n"
                  "%.6g s simulated in %.3f s of wall time summed over the jobs.\n",
                  fs::path(plan.file).filename().c_str(), plan.jobs.size(), done, failed, missing, stale,
                  simulatedS, wallS);
    std::string out = text;
    if (failed > 0)
    {
        out += failedJobsTable(plan, results);
    }
    for (const auto& [status, count, title] :
         {std::tuple<const char*, std::size_t, const char*>{"missing", missing, "Missing jobs"},
          {"stale", stale, "Stale jobs (inputs changed since they ran)"}})
    {
        if (count > 0)
        {
            out += std::string("\n## ") + title + "\n\n";
            for (std::size_t j = 0; j < plan.jobs.size(); ++j)
            {
                if (results[j].status == status)
                {
                    out += "* " + plan.jobs[j].id + "\n";
                }
            }
        }
    }
    io::AtomicFile file(path);
    file.write(out);
    file.commit();
}

// DIR/chart.png: column y against column x over the done jobs (gnuplot, as the sweep's chart).
bool drawChart(const std::string& folder, const Table& table, const std::string& x, const std::string& y)
{
    auto column = [&](const std::string& name)
    {
        const auto it = std::find(table.header.begin(), table.header.end(), name);
        if (it == table.header.end())
        {
            std::string names;
            for (const std::string& h : table.header)
            {
                names += (names.empty() ? "" : ", ") + h;
            }
            throw io::InputError("--chart", 0, 0,
                                 "no column '" + name + "' in batch.csv; expected one of " + names);
        }
        return static_cast<std::size_t>(it - table.header.begin());
    };
    const std::size_t cx = column(x), cy = column(y), status = column("status");
    std::string data = "# " + x + " " + y + " job\n";
    for (const std::vector<std::string>& row : table.rows)
    {
        const std::optional<double> vx = io::detail::parseFiniteNumber(row[cx]);
        const std::optional<double> vy = io::detail::parseFiniteNumber(row[cy]);
        if (row[status] == "done" && vx && vy)
        {
            data += number(*vx) + " " + number(*vy) + " " + row[0] + "\n";
        }
    }
    const std::string script =
        "# chart.gp: `gnuplot chart.gp` in this folder draws chart.png from chart.dat\n"
        "if (!exists('out')) out = 'chart.png'\n"
        "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
        "    set terminal pngcairo size 900,600 enhanced font ',10'\n"
        "} else {\n"
        "    set terminal png size 900,600 enhanced\n"
        "}\n"
        "set output out\n"
        "set title " +
        gnuplotQuote(y + " against " + x) +
        " noenhanced\n"
        "set xlabel " +
        gnuplotQuote(x) + " noenhanced\nset ylabel " + gnuplotQuote(y) +
        " noenhanced\n"
        "set grid\n"
        "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n"
        "plot 'chart.dat' using 1:2 with points pt 7 ps 1.2 notitle\n";
    return drawGnuplotChart(folder, {"chart.gp", script, "chart.dat", data, "chart.png"});
}
} // namespace

namespace
{
// Each job's status (done, failed, missing, stale) and stats, from its folder.
std::vector<MergedJob> readJobs(const BatchPlan& plan, const BatchOptions& options)
{
    std::vector<MergedJob> results(plan.jobs.size());
    CurrentDigests digests(plan, options.urdf);
    for (std::size_t j = 0; j < plan.jobs.size(); ++j)
    {
        const JobOutputs files = jobOutputs(plan, options.out, plan.jobs[j]);
        std::error_code error;
        results[j].status = "missing";
        if (!fs::is_regular_file(files.stats, error))
        {
            continue;
        }
        try
        {
            results[j].stats = io::readStats(files.stats);
        }
        catch (const io::InputError& e)
        {
            std::cerr << "frontier: " << e.what() << "\n";
            continue;
        }
        const JobState state = jobState(plan, files, digests.of(plan.jobs[j]));
        results[j].status = state == JobState::Complete        ? "done"
                            : state == JobState::InputsChanged ? "stale"
                            : results[j].stats->completed      ? "missing"
                                                               : "failed";
    }
    return results;
}

// DIR/batch.csv, DIR/summary.md, with --chart DIR/chart.png. Throws io::InputError,
// io::OutputError, ChartError, std::filesystem::filesystem_error.
void writeMerge(const BatchPlan& plan, const BatchOptions& options, const std::vector<MergedJob>& results)
{
    const Table table = makeTable(plan, results);
    const fs::path folder(options.out);
    fs::create_directories(folder);
    writeCsv((folder / "batch.csv").string(), plan, table);
    writeSummary((folder / "summary.md").string(), plan, results);
    if (options.chart.empty())
    {
        return;
    }
    if (options.chart.size() != 2)
    {
        throw io::InputError("--chart", 0, 0, "expected two column names X,Y");
    }
    if (!drawChart(options.out, table, options.chart[0], options.chart[1]))
    {
        std::cerr << "frontier: note: gnuplot is not installed, so there is no chart; `cd " << options.out
                  << " && gnuplot chart.gp` draws it\n";
    }
}

// The first jobs not done are named here; summary.md lists them all (a study of 10 000 jobs merged
// halfway would otherwise print thousands of lines). Returns how many are not done.
std::size_t reportNotDone(const BatchPlan& plan, const std::vector<MergedJob>& results,
                          const fs::path& folder)
{
    constexpr std::size_t cNamedAtMost = 20;
    std::size_t bad = 0;
    for (std::size_t j = 0; j < results.size(); ++j)
    {
        if (results[j].status != "done" && ++bad <= cNamedAtMost)
        {
            std::cerr << "frontier: job " << plan.jobs[j].id << " " << results[j].status
                      << (results[j].status == "failed" ? ": " + results[j].stats->failure : std::string())
                      << "\n";
        }
    }
    if (bad > cNamedAtMost)
    {
        std::cerr << "frontier: ... and " << bad - cNamedAtMost << " more jobs not done ("
                  << (folder / "summary.md").string() << " lists them)\n";
    }
    return bad;
}
} // namespace

int mergeBatch(const BatchPlan& plan, const BatchOptions& options)
{
    const std::vector<MergedJob> results = readJobs(plan, options);
    try
    {
        writeMerge(plan, options, results);
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    catch (const io::OutputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    catch (const ChartError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitFailed;
    }
    catch (const fs::filesystem_error& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    const fs::path folder(options.out);
    const std::size_t bad = reportNotDone(plan, results, folder);
    std::printf("Wrote %s and %s: %zu jobs, %zu not done.\n", (folder / "batch.csv").c_str(),
                (folder / "summary.md").c_str(), plan.jobs.size(), bad);
    return bad > 0 ? cExitFailed : cExitOk;
}

} // namespace frontier::app
