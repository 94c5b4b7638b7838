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
#include <vector>

extern char** environ;

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

constexpr const char* cScript = "sweep.gp";
constexpr const char* cData = "sweep.dat";
constexpr const char* cChart = "sweep.png";
constexpr const char* cChartTemp = "sweep.png.tmp"; // renamed to sweep.png when gnuplot succeeded

// A gnuplot single-quoted string: no escapes inside but '' for a quote; control characters (a
// line break would end the command) become spaces.
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

bool plottable(const SweepCell& c)
{
    return c.survived && std::isfinite(c.secondsPerSimSecond) && c.secondsPerSimSecond > 0.0 &&
           std::isfinite(c.trajectoryErrorM) && c.trajectoryErrorM > 0.0;
}

std::string point(const SweepCell& c)
{
    char text[128];
    std::snprintf(text, sizeof text, "%.9g %.9g \"%g ms\"\n", c.secondsPerSimSecond, c.trajectoryErrorM,
                  c.dt * 1e3);
    return text;
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

bool drawSweepChart(const std::string& folder, const std::string& sceneName, const SweepResult& result)
{
    // The data: the Pareto front, then one block per method (cost, error, dt label); blocks are
    // separated by two blank lines (gnuplot's `index`).
    std::string data =
        "# frontier sweep chart data: wall seconds per simulated second, trajectory error (m), dt\n";
    int block = 0;
    std::vector<std::string> labels;
    for (const SweepCell& c : result.cells)
    {
        if (std::find(labels.begin(), labels.end(), c.method.label()) == labels.end())
        {
            labels.push_back(c.method.label());
        }
    }
    // The Pareto front first, under the methods' lines.
    const std::vector<std::size_t> front = paretoFront(result.cells);
    std::string frontPoints;
    for (std::size_t i : front)
    {
        if (plottable(result.cells[i]))
        {
            frontPoints += point(result.cells[i]);
        }
    }
    std::vector<std::string> plots;
    if (!frontPoints.empty())
    {
        data += "# Pareto front\n" + frontPoints;
        plots.push_back("data index 0 using 1:2 with steps lw 7 lc rgb '#a0d62728' title 'Pareto front (no "
                        "other cell both cheaper and more accurate)'");
        plots.push_back("data index 0 using 1:2 with points pt 6 ps 2.4 lw 2 lc rgb '#d62728' notitle");
        ++block;
    }
    int style = 0;
    for (const std::string& label : labels)
    {
        std::string points;
        for (const SweepCell& c : result.cells)
        {
            if (c.method.label() == label && plottable(c))
            {
                points += point(c);
            }
        }
        if (points.empty())
        {
            continue;
        }
        data += (block > 0 ? "\n\n" : "") + std::string("# ") + label + "\n" + points;
        const std::string index = std::to_string(block);
        const std::string lt = std::to_string(++style);
        plots.push_back("data index " + index + " using 1:2 with linespoints lt " + lt +
                        " lw 2 pt 7 ps 1.2 title " + gnuplotQuote(label));
        plots.push_back("data index " + index +
                        " using 1:2:3 with labels left offset char 0.6,0.6 font ',8' tc lt " + lt +
                        " notitle");
        ++block;
    }

    char title[512];
    std::snprintf(title, sizeof title,
                  "%s: speed against accuracy (reference %s at dt %g s, %g s simulated, %zu sample times)",
                  sceneName.c_str(), result.reference.method.label().c_str(), result.reference.dt,
                  result.schedule.durationS(), result.schedule.sampleUnits.size());
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
        "set title " +
        gnuplotQuote(title) +
        " noenhanced\n"
        "set logscale xy\n"
        "set xlabel 'cost: wall seconds per simulated second' noenhanced\n"
        "set ylabel 'trajectory error (m): largest centre-of-mass distance to the reference' noenhanced\n"
        "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
        "set format xy '%g'\n"
        "set key below box Left reverse noenhanced\n"; // under the plot: never over a cell
    if (plots.empty())
    {
        script += "set label 1 'no cell survived: nothing to draw' at graph 0.5, graph 0.5 center\n"
                  "set xrange [1e-3:1]\nset yrange [1e-6:1]\nplot NaN notitle\n";
    }
    else
    {
        script += "plot ";
        for (std::size_t i = 0; i < plots.size(); ++i)
        {
            script += (i > 0 ? ", \\\n     " : "") + plots[i];
        }
        script += "\n";
    }

    const fs::path dir(folder);
    writeFile(dir / cData, data);
    writeFile(dir / cScript, script);
    std::error_code ignored;
    fs::remove(dir / cChartTemp, ignored);
    const std::string gnuplot = findGnuplot();
    if (gnuplot.empty())
    {
        fs::remove(dir / cChart, ignored);
        return false;
    }
    std::string errors;
    const int code =
        runInFolder(gnuplot, folder, {"-e", "out = '" + std::string(cChartTemp) + "'", cScript}, errors);
    if (code != 0 || !fs::exists(dir / cChartTemp))
    {
        fs::remove(dir / cChartTemp, ignored);
        fs::remove(dir / cChart, ignored);
        throw ChartError("gnuplot failed on " + (dir / cScript).string() + " (exit code " +
                         std::to_string(code) + ")" + (errors.empty() ? std::string() : ": " + errors));
    }
    std::error_code renamed;
    fs::rename(dir / cChartTemp, dir / cChart, renamed);
    if (renamed)
    {
        throw io::OutputError((dir / cChart).string() + ": cannot write file: " + renamed.message());
    }
    return true;
}

} // namespace frontier::app
