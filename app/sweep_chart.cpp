// app/sweep_chart.cpp: sweep.gp and sweep.dat, and gnuplot run with posix_spawn in the output folder.
#include "app/sweep_chart.h"

#include "io/atomic_file.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

extern char** environ;

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

constexpr const char* cScript = cSweepChartFiles[0];
constexpr const char* cData = cSweepChartFiles[1];
constexpr const char* cChart = cSweepChartFiles[2];

} // namespace

std::string gnuplotQuote(const std::string& text)
{
    std::string out = "'";
    for (char c : text)
    {
        if (c == '\'')
        {
            out += "''";
        }
        else
        {
            out += (static_cast<unsigned char>(c) < 0x20) ? ' ' : c;
        }
    }
    return out + "'";
}

namespace
{

bool plottable(const SweepCell& c, Accuracy accuracy)
{
    const double y = accuracyOf(c, accuracy);
    return c.survived && std::isfinite(c.secondsPerSimSecond) && c.secondsPerSimSecond > 0.0 &&
           std::isfinite(y) && y > 0.0;
}

std::string point(const SweepCell& c, Accuracy accuracy)
{
    char text[128];
    std::snprintf(text, sizeof text, "%.9g %.9g \"%g ms\"\n", c.secondsPerSimSecond, accuracyOf(c, accuracy),
                  c.dt * 1e3);
    return text;
}

// The y axis's label and the data file's name for the column.
std::string accuracyAxis(Accuracy accuracy)
{
    switch (accuracy)
    {
    case Accuracy::JointGap:
        return "joint gap (m): largest positional joint error over the run";
    case Accuracy::Penetration:
        return "penetration (m): deepest contact overlap over the run";
    case Accuracy::TrajectoryError:
        break;
    }
    return "trajectory error (m): largest centre-of-mass distance to the reference";
}

void writeFile(const fs::path& path, const std::string& text)
{
    io::AtomicFile file(path.string());
    file.write(text);
    file.commit();
}

// Runs gnuplot (the executable `gnuplot`) in `folder` with `arguments`; returns its exit status
// and fills `errors` with what it wrote to stderr. Throws ChartError when it cannot be started.
int runInFolder(const std::string& gnuplot, const std::string& folder,
                const std::vector<std::string>& arguments, std::string& errors)
{
    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0)
    {
        throw ChartError(std::string("cannot start gnuplot: pipe: ") + std::strerror(errno));
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDERR_FILENO);
    std::vector<std::string> args = {gnuplot};
    args.insert(args.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& arg : args)
    {
        argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = ::posix_spawn(&pid, gnuplot.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipeFds[1]);
    if (spawned != 0)
    {
        ::close(pipeFds[0]);
        throw ChartError("cannot start " + gnuplot + ": " + std::strerror(spawned));
    }
    char buffer[4096];
    for (;;)
    {
        const ssize_t n = ::read(pipeFds[0], buffer, sizeof buffer);
        if (n > 0)
        {
            errors.append(buffer, static_cast<std::size_t>(n));
        }
        else if (n == 0 || errno != EINTR)
        {
            break;
        }
    }
    ::close(pipeFds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
    {
        if (errno != EINTR)
        {
            throw ChartError(std::string("waiting for gnuplot: ") + std::strerror(errno));
        }
    }
    if (WIFEXITED(status))
    {
        return WEXITSTATUS(status);
    }
    errors += "gnuplot was killed by signal " + std::to_string(WTERMSIG(status));
    return -1;
}
} // namespace

std::string findGnuplot()
{
    const char* path = std::getenv("PATH");
    if (path == nullptr)
    {
        return {};
    }
    const std::string folders = path;
    std::size_t begin = 0;
    while (begin <= folders.size())
    {
        const std::size_t end = std::min(folders.find(':', begin), folders.size());
        const std::string folder = folders.substr(begin, end - begin);
        begin = end + 1;
        if (folder.empty() || folder.front() != '/')
        {
            continue; // only absolute folders: the child runs in the output folder
        }
        const std::string candidate = folder + "/gnuplot";
        struct stat info;
        if (::stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
            ::access(candidate.c_str(), X_OK) == 0)
        {
            return candidate;
        }
    }
    return {};
}

namespace
{
// The chart's geometry (pixels of the PNG, y up from the bottom edge) as the script sets it.
constexpr double cWidthPx = 1100.0;
constexpr double cHeightPx = 720.0;
constexpr double cLeft = 0.085; // plot area edges, fractions of the image
constexpr double cRight = 0.975;
constexpr double cTop = 0.92;
constexpr double cKeyRowPx = 17.0;    // one legend row at the 10 pt font
constexpr double cBelowAxisPx = 52.0; // tick labels and the axis label under the plot
constexpr double cLabelCharPx = 6.2;  // one character of a dt label at the 8 pt font
constexpr double cLabelHeightPx = 11.0;
constexpr double cMarkerPx = 5.0; // half size of a method's point (pt 7 ps 1.2)
constexpr double cRingPx = 10.0;  // half size of a Pareto front ring (pt 6 ps 2.4)

struct Rect
{
    double x0, y0, x1, y1;
    bool overlaps(const Rect& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Whole decades around [lo, hi] (at least one decade).
void decades(double lo, double hi, double& logLo, double& logHi)
{
    logLo = std::floor(std::log10(lo));
    logHi = std::ceil(std::log10(hi));
    if (logHi <= logLo)
    {
        logHi = logLo + 1.0;
    }
}

struct Axes
{
    double logX0 = -3, logX1 = 0, logY0 = -6, logY1 = 0; // decades
    double bottom = 0.2;                                 // fraction of the image under the plot
    double px(double x) const
    {
        return cLeft * cWidthPx + (std::log10(x) - logX0) / (logX1 - logX0) * (cRight - cLeft) * cWidthPx;
    }
    double py(double y) const
    {
        return bottom * cHeightPx + (std::log10(y) - logY0) / (logY1 - logY0) * (cTop - bottom) * cHeightPx;
    }
    double x(double px) const
    {
        return std::pow(10.0,
                        logX0 + (px - cLeft * cWidthPx) / ((cRight - cLeft) * cWidthPx) * (logX1 - logX0));
    }
    double y(double py) const
    {
        return std::pow(10.0,
                        logY0 + (py - bottom * cHeightPx) / ((cTop - bottom) * cHeightPx) * (logY1 - logY0));
    }
    Rect area() const
    {
        return {cLeft * cWidthPx + 2, bottom * cHeightPx + 2, cRight * cWidthPx - 2, cTop * cHeightPx - 2};
    }
};

std::string dtLabel(const SweepCell& c)
{
    char text[64];
    std::snprintf(text, sizeof text, "%g ms", c.dt * 1e3);
    return text;
}

std::string number(double v)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
}

// Small boxes along the segment from a to b (pixels), every few pixels.
void addSegment(std::vector<Rect>& obstacles, double ax, double ay, double bx, double by, double halfWidth)
{
    const double length = std::hypot(bx - ax, by - ay);
    const int pieces = std::max(1, static_cast<int>(length / 4.0));
    for (int i = 0; i <= pieces; ++i)
    {
        const double t = static_cast<double>(i) / pieces;
        const double x = ax + t * (bx - ax);
        const double y = ay + t * (by - ay);
        obstacles.push_back({x - halfWidth, y - halfWidth, x + halfWidth, y + halfWidth});
    }
}

struct Chart
{
    std::string data;
    std::string script;
};

// One method's line: its cells, coarse to fine.
struct Series
{
    int lineType = 0;
    std::vector<std::size_t> cells;
};

// The chart's data blocks (the Pareto front, then one block per method; blocks separated by two
// blank lines, gnuplot's `index`) and the plot command of each.
struct ChartPlots
{
    std::string data;
    std::vector<std::string> plots;
    std::vector<std::size_t> frontShown; // the front's cells drawn
    std::vector<Series> series;
    int keyEntries = 0;
    int blocks = 0;
};

// The methods' labels, in the order of their first cell.
std::vector<std::string> methodLabels(const std::vector<SweepCell>& cells)
{
    std::vector<std::string> labels;
    for (const SweepCell& c : cells)
    {
        if (std::find(labels.begin(), labels.end(), cellLabel(c)) == labels.end())
        {
            labels.push_back(cellLabel(c));
        }
    }
    return labels;
}

// The Pareto front first, under the methods' lines.
void addFront(const SweepResult& result, Accuracy accuracy, ChartPlots& chart)
{
    std::string frontPoints;
    for (std::size_t i : paretoFront(result.cells, accuracy))
    {
        if (plottable(result.cells[i], accuracy))
        {
            frontPoints += point(result.cells[i], accuracy);
            chart.frontShown.push_back(i);
        }
    }
    if (frontPoints.empty())
    {
        return;
    }
    chart.data += "# Pareto front\n" + frontPoints;
    chart.plots.push_back("data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no "
                          "other cell both cheaper and more accurate)'");
    chart.plots.push_back("data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle");
    ++chart.blocks;
    ++chart.keyEntries;
}

// One block and line per method with a cell to draw.
void addSeries(const SweepResult& result, Accuracy accuracy, ChartPlots& chart)
{
    for (const std::string& label : methodLabels(result.cells))
    {
        Series one;
        std::string points;
        for (std::size_t i = 0; i < result.cells.size(); ++i)
        {
            const SweepCell& c = result.cells[i];
            if (cellLabel(c) == label && plottable(c, accuracy))
            {
                points += point(c, accuracy);
                one.cells.push_back(i);
            }
        }
        if (points.empty())
        {
            continue;
        }
        chart.data += (chart.blocks > 0 ? "\n\n" : "") + std::string("# ") + label + "\n" + points;
        one.lineType = static_cast<int>(chart.series.size()) + 1;
        const std::string lt = std::to_string(one.lineType);
        chart.plots.push_back("data index " + std::to_string(chart.blocks) +
                              " using 1:2 with linespoints lt " + lt + " lw 2 pt 7 ps 1.2 title " +
                              gnuplotQuote(label));
        chart.series.push_back(one);
        ++chart.blocks;
        ++chart.keyEntries;
    }
}

// Geometry: the legend's rows set the bottom margin; the ranges are whole decades.
Axes chartAxes(const SweepResult& result, Accuracy accuracy, const ChartPlots& chart)
{
    Axes axes;
    const int keyRows = (chart.keyEntries + 1) / 2;
    axes.bottom = (cBelowAxisPx + keyRows * cKeyRowPx + 18.0) / cHeightPx;
    double xLo = 1e300, xHi = -1e300, yLo = 1e300, yHi = -1e300;
    for (const SweepCell& c : result.cells)
    {
        if (plottable(c, accuracy))
        {
            xLo = std::min(xLo, c.secondsPerSimSecond);
            xHi = std::max(xHi, c.secondsPerSimSecond);
            yLo = std::min(yLo, accuracyOf(c, accuracy));
            yHi = std::max(yHi, accuracyOf(c, accuracy));
        }
    }
    if (!chart.plots.empty())
    {
        decades(xLo, xHi, axes.logX0, axes.logX1);
        decades(yLo, yHi, axes.logY0, axes.logY1);
    }
    return axes;
}

// What a dt label must not cover: the front's rings and steps, the methods' markers and lines.
std::vector<Rect> labelObstacles(const SweepResult& result, Accuracy accuracy, const Axes& axes,
                                 const ChartPlots& chart)
{
    std::vector<Rect> obstacles;
    const std::vector<std::size_t>& frontShown = chart.frontShown;
    for (std::size_t i : frontShown)
    {
        const SweepCell& c = result.cells[i];
        const double x = axes.px(c.secondsPerSimSecond);
        const double y = axes.py(accuracyOf(c, accuracy));
        obstacles.push_back({x - cRingPx, y - cRingPx, x + cRingPx, y + cRingPx});
    }
    for (std::size_t k = 1; k < frontShown.size(); ++k) // steps: across, then down
    {
        const SweepCell& a = result.cells[frontShown[k - 1]];
        const SweepCell& b = result.cells[frontShown[k]];
        addSegment(obstacles, axes.px(a.secondsPerSimSecond), axes.py(accuracyOf(a, accuracy)),
                   axes.px(b.secondsPerSimSecond), axes.py(accuracyOf(a, accuracy)), 4.0);
        addSegment(obstacles, axes.px(b.secondsPerSimSecond), axes.py(accuracyOf(a, accuracy)),
                   axes.px(b.secondsPerSimSecond), axes.py(accuracyOf(b, accuracy)), 4.0);
    }
    for (const Series& one : chart.series)
    {
        for (std::size_t k = 0; k < one.cells.size(); ++k)
        {
            const SweepCell& c = result.cells[one.cells[k]];
            const double x = axes.px(c.secondsPerSimSecond);
            const double y = axes.py(accuracyOf(c, accuracy));
            obstacles.push_back({x - cMarkerPx, y - cMarkerPx, x + cMarkerPx, y + cMarkerPx});
            if (k > 0)
            {
                const SweepCell& p = result.cells[one.cells[k - 1]];
                addSegment(obstacles, axes.px(p.secondsPerSimSecond), axes.py(accuracyOf(p, accuracy)), x, y,
                           1.5);
            }
        }
    }
    return obstacles;
}

// dt labels: each placed at the first free spot around its point, or left out. The gnuplot
// commands, numbered from 1.
std::string dtLabels(const SweepResult& result, Accuracy accuracy, const Axes& axes, const ChartPlots& chart)
{
    std::vector<Rect> obstacles = labelObstacles(result, accuracy, axes, chart);
    const std::vector<std::size_t>& frontShown = chart.frontShown;
    const Rect area = axes.area();
    std::string labelCommands;
    int labelCount = 0;
    for (const Series& one : chart.series)
    {
        for (std::size_t i : one.cells)
        {
            const SweepCell& c = result.cells[i];
            const std::string text = dtLabel(c);
            const double x = axes.px(c.secondsPerSimSecond);
            const double y = axes.py(accuracyOf(c, accuracy));
            const bool onFront = std::find(frontShown.begin(), frontShown.end(), i) != frontShown.end();
            const double gap = (onFront ? cRingPx : cMarkerPx) + 2.0;
            const double w = cLabelCharPx * static_cast<double>(text.size());
            const double h = cLabelHeightPx;
            // Left edge and vertical centre of each candidate, in order of preference.
            const double candidates[][2] = {{x + gap, y + 0.6 * h},
                                            {x + gap, y - 0.6 * h},
                                            {x - gap - w, y + 0.6 * h},
                                            {x - gap - w, y - 0.6 * h},
                                            {x + gap + 2, y},
                                            {x - gap - 2 - w, y},
                                            {x - 0.5 * w, y + gap + 0.5 * h},
                                            {x - 0.5 * w, y - gap - 0.5 * h}};
            for (const auto& cand : candidates)
            {
                const Rect r{cand[0], cand[1] - 0.5 * h, cand[0] + w, cand[1] + 0.5 * h};
                if (r.x0 < area.x0 || r.x1 > area.x1 || r.y0 < area.y0 || r.y1 > area.y1)
                {
                    continue;
                }
                if (std::any_of(obstacles.begin(), obstacles.end(),
                                [&](const Rect& o) { return o.overlaps(r); }))
                {
                    continue;
                }
                obstacles.push_back(r);
                labelCommands += "set label " + std::to_string(++labelCount) + " " + gnuplotQuote(text) +
                                 " at " + number(axes.x(r.x0)) + ", " + number(axes.y(cand[1])) +
                                 " left font ',8' tc lt " + std::to_string(one.lineType) +
                                 " front noenhanced\n";
                break;
            }
        }
    }
    return labelCommands;
}

// The title: the scene and what the chart compares.
std::string chartTitle(const std::string& sceneName, const SweepResult& result, Accuracy accuracy)
{
    char title[512];
    if (accuracy == Accuracy::TrajectoryError)
        std::snprintf(
            title, sizeof title,
            "%s: speed against accuracy (reference %s at dt %g s, %g s simulated, %zu sample time%s)",
            sceneName.c_str(), result.reference.method.label().c_str(), result.reference.dt,
            result.schedule.durationS(), result.schedule.sampleUnits.size(),
            result.schedule.sampleUnits.size() == 1 ? "" : "s");
    else
        std::snprintf(title, sizeof title, "%s: %s against cost (%g s simulated)", sceneName.c_str(),
                      accuracy == Accuracy::JointGap ? "joint gap" : "penetration",
                      result.schedule.durationS());
    std::string titleExpression = gnuplotQuote(title);
    if (accuracy == Accuracy::TrajectoryError && errorRanksNothing(result.cells))
    {
        titleExpression +=
            " . \"\\n\" . " + gnuplotQuote("(chaotic: error does not rank the methods; no method's "
                                           "error falls as dt is refined)");
    }
    return titleExpression;
}

// The plot command: every line and point set, or a note that there is nothing to draw.
std::string plotCommand(const std::vector<std::string>& plots)
{
    if (plots.empty())
    {
        return "set label 1 'no cell survived: nothing to draw' at graph 0.5, graph 0.5 center\n"
               "plot NaN notitle\n";
    }
    std::string command = "plot ";
    for (std::size_t i = 0; i < plots.size(); ++i)
    {
        command += (i > 0 ? ", \\\n     " : "") + plots[i];
    }
    return command + "\n";
}

// The gnuplot script: terminal, title, margins, ranges, key, labels, plots.
std::string chartScript(const std::string& titleExpression, const Axes& axes, Accuracy accuracy,
                        const ChartPlots& chart, const std::string& labelCommands)
{
    const int keyRows = (chart.keyEntries + 1) / 2;
    const std::vector<std::string>& plots = chart.plots;
    const double keyTop = axes.bottom - cBelowAxisPx / cHeightPx;
    std::string script =
        "# sweep.gp: the chart of `frontier sweep`; `gnuplot sweep.gp` in this folder draws sweep.png\n"
        "# from sweep.dat (the Pareto front, then one block per method).\n"
        "if (!exists('out')) out = '" +
        std::string(cChart) +
        "'\n"
        "data = '" +
        cData +
        "'\n"
        "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
        "    set terminal pngcairo size 1100,720 enhanced font ',10'\n"
        "} else {\n"
        "    set terminal png size 1100,720 enhanced\n"
        "}\n"
        "set output out\n"
        // gnuplot's line types repeat after 8: eight more colours, so that up to 16 series differ.
        "set linetype 9 lc rgb '#8c564b'\nset linetype 10 lc rgb '#7f7f7f'\n"
        "set linetype 11 lc rgb '#bcbd22'\nset linetype 12 lc rgb '#17becf'\n"
        "set linetype 13 lc rgb '#e377c2'\nset linetype 14 lc rgb '#393b79'\n"
        "set linetype 15 lc rgb '#637939'\nset linetype 16 lc rgb '#ad494a'\n"
        "set title " +
        titleExpression +
        " noenhanced\n"
        "set lmargin at screen " +
        number(cLeft) + "\nset rmargin at screen " + number(cRight) + "\nset tmargin at screen " +
        number(cTop) + "\nset bmargin at screen " + number(axes.bottom) +
        "\n"
        "set logscale xy\n"
        "set xrange [" +
        number(std::pow(10.0, axes.logX0)) + ":" + number(std::pow(10.0, axes.logX1)) + "]\nset yrange [" +
        number(std::pow(10.0, axes.logY0)) + ":" + number(std::pow(10.0, axes.logY1)) +
        "]\n"
        "set xtics 10\nset ytics 10\nset mxtics 10\nset mytics 10\n"
        "set format x '1e%T'\nset format y '1e%T'\n" // one style per axis: 1e-3, 1e0, 1e2
        "set xlabel 'cost: wall seconds per simulated second' noenhanced\n"
        "set ylabel " +
        gnuplotQuote(accuracyAxis(accuracy)) +
        " noenhanced\n"
        "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
        // Under the axis label, two columns: never over a cell or a label.
        "set key at screen 0.5, screen " +
        number(keyTop) + " center top vertical maxrows " + std::to_string(std::max(keyRows, 1)) +
        " box Left reverse width 2 noenhanced\n" + labelCommands;
    return script + plotCommand(plots);
}

Chart buildChart(const std::string& sceneName, const SweepResult& result, Accuracy accuracy)
{
    ChartPlots plots;
    plots.data = "# frontier sweep chart data: wall seconds per simulated second, " + accuracyAxis(accuracy) +
                 ", dt\n";
    addFront(result, accuracy, plots);
    addSeries(result, accuracy, plots);
    const Axes axes = chartAxes(result, accuracy, plots);
    const std::string labelCommands = dtLabels(result, accuracy, axes, plots);
    Chart chart;
    chart.data = plots.data;
    chart.script = chartScript(chartTitle(sceneName, result, accuracy), axes, accuracy, plots, labelCommands);
    return chart;
}
} // namespace

bool errorRanksNothing(const std::vector<SweepCell>& cells)
{
    std::vector<std::string> labels;
    for (const SweepCell& c : cells)
    {
        if (std::find(labels.begin(), labels.end(), cellLabel(c)) == labels.end())
        {
            labels.push_back(cellLabel(c));
        }
    }
    bool judged = false;
    for (const std::string& label : labels)
    {
        std::vector<std::pair<double, double>> runs; // dt (s), error (m)
        for (const SweepCell& c : cells)
        {
            if (cellLabel(c) == label && c.survived && std::isfinite(c.trajectoryErrorM) &&
                c.trajectoryErrorM > 0.0 && c.dt > 0.0)
            {
                runs.emplace_back(c.dt, c.trajectoryErrorM);
            }
        }
        if (runs.size() < 2)
        {
            continue;
        }
        judged = true;
        std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        bool converging = true;
        for (std::size_t k = 1; k < runs.size() && converging; ++k)
        {
            const double allowed =
                runs[k - 1].second * std::pow(runs[k].first / runs[k - 1].first, cConvergenceOrder);
            converging = runs[k].second <= allowed;
        }
        if (converging)
        {
            return false;
        }
    }
    return judged;
}

const std::map<std::string, Accuracy>& accuracyNames()
{
    static const std::map<std::string, Accuracy> names = {{"error", Accuracy::TrajectoryError},
                                                          {"joint-gap", Accuracy::JointGap},
                                                          {"penetration", Accuracy::Penetration}};
    return names;
}

std::string sweepChartScript(const std::string& sceneName, const SweepResult& result, Accuracy accuracy)
{
    return buildChart(sceneName, result, accuracy).script;
}

bool drawGnuplotChart(const std::string& folder, const GnuplotChart& chart)
{
    const fs::path dir(folder);
    const std::string chartTemp = chart.chart + ".tmp"; // renamed to the chart when gnuplot succeeded
    writeFile(dir / chart.dataName, chart.data);
    writeFile(dir / chart.scriptName, chart.script);
    std::error_code ignored;
    fs::remove(dir / chartTemp, ignored);
    const std::string gnuplot = findGnuplot();
    if (gnuplot.empty())
    {
        fs::remove(dir / chart.chart, ignored);
        return false;
    }
    std::string errors;
    const int code =
        runInFolder(gnuplot, folder, {"-e", "out = '" + chartTemp + "'", chart.scriptName}, errors);
    if (code != 0 || !fs::exists(dir / chartTemp))
    {
        fs::remove(dir / chartTemp, ignored);
        fs::remove(dir / chart.chart, ignored);
        throw ChartError("gnuplot failed on " + (dir / chart.scriptName).string() + " (exit code " +
                         std::to_string(code) + ")" + (errors.empty() ? std::string() : ": " + errors));
    }
    std::error_code renamed;
    fs::rename(dir / chartTemp, dir / chart.chart, renamed);
    if (renamed)
    {
        throw io::OutputError((dir / chart.chart).string() + ": cannot write file: " + renamed.message());
    }
    return true;
}

bool drawSweepChart(const std::string& folder, const std::string& sceneName, const SweepResult& result,
                    Accuracy accuracy)
{
    const Chart chart = buildChart(sceneName, result, accuracy);
    return drawGnuplotChart(folder, {cScript, chart.script, cData, chart.data, cChart});
}

} // namespace frontier::app
