// app/sweep_chart.h: the chart of `frontier sweep`, drawn by gnuplot.
//
// DIR/sweep.gp (the script) and DIR/sweep.dat (its data) are always written; gnuplot then runs in
// DIR as a child process (no shell) and draws DIR/sweep.png: trajectory error (m) against cost
// (wall seconds per simulated second), log-log, one line per method with its points labelled by
// dt, and the Pareto front as a highlighted step line. `cd DIR && gnuplot sweep.gp` redraws it.
// The y axis may instead be the joint gap or the penetration (study::Accuracy), for scenes whose
// trajectories are chaotic.
//
// Layout: fixed margins and axis ranges (whole decades around the data), ticks at every decade
// written "1e-3" on both axes, the legend below the axis label in two columns (never over the
// data), and each dt label placed by the script writer where it overlaps no point, line or other
// label (or left out when no place is free). A sweep where the error does not fall with dt for any
// method (errorRanksNothing) says so in the title.
#pragma once

#include "study/sweep.h"

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace frontier::app
{

// The sweep's results (study/sweep.h).
using study::Accuracy;
using study::cellLabel;
using study::paretoFront;
using study::SweepCell;
using study::SweepResult;

// gnuplot ran but failed (exit code 1 of the command).
class ChartError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// The relative drop in error per refinement of dt a method must show to count as converging: its
// error at each finer dt at most (finer dt / coarser dt)^cConvergenceOrder times the one before
// (a factor 0.84 per halving: an observed order of accuracy of at least 1/4).
inline constexpr double cConvergenceOrder = 0.25;

// True when the error ranks nothing: at least one method has two or more surviving cells, and no
// method's trajectory error falls at every refinement of dt as cConvergenceOrder asks. Then the
// scene is chaotic at these time steps (a pile of contacts: tiny differences grow until every
// run is as far from the reference as any other), and the chart compares noise, not methods.
bool errorRanksNothing(const std::vector<SweepCell>& cells);

// The names of the chart's accuracies on the command line (`--chart-accuracy`): error,
// joint-gap, penetration.
const std::map<std::string, Accuracy>& accuracyNames();

// The text of sweep.gp (for the data sweep.dat that drawSweepChart writes alongside it).
std::string sweepChartScript(const std::string& sceneName, const SweepResult& result,
                             Accuracy accuracy = Accuracy::TrajectoryError);

// A gnuplot single-quoted string: no escapes inside but '' for a quote; control characters (a
// line break would end the command) become spaces.
std::string gnuplotQuote(const std::string& text);

// A chart drawn by gnuplot: the script (which writes the PNG named by the variable `out`) and its
// data, written as files of the chart's folder.
struct GnuplotChart
{
    std::string scriptName; // "sweep.gp"
    std::string script;
    std::string dataName; // "sweep.dat"
    std::string data;
    std::string chart; // "sweep.png"
};

// Writes the script and data into `folder` and, when gnuplot is installed, runs it there to draw
// the chart (through a temporary name, renamed when gnuplot succeeded). Returns false when gnuplot
// is not installed (no PNG; an older one is removed). Throws io::OutputError, ChartError.
bool drawGnuplotChart(const std::string& folder, const GnuplotChart& chart);

// gnuplot on the PATH, or empty when it is not installed.
std::string findGnuplot();

// The files drawSweepChart writes in its folder: the script, its data, the chart, and the name
// gnuplot draws the chart under before it is renamed (drawGnuplotChart).
inline constexpr const char* cSweepChartFiles[] = {"sweep.gp", "sweep.dat", "sweep.png", "sweep.png.tmp"};

// Writes folder/sweep.gp and folder/sweep.dat and, when gnuplot is installed, runs it to draw
// folder/sweep.png. Returns false when gnuplot is not installed (no PNG; an older sweep.png is
// removed so it cannot pass for this sweep's). Throws io::OutputError when a file cannot be
// written, ChartError when gnuplot fails.
bool drawSweepChart(const std::string& folder, const std::string& sceneName, const SweepResult& result,
                    Accuracy accuracy = Accuracy::TrajectoryError);

} // namespace frontier::app
