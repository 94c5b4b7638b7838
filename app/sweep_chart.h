// app/sweep_chart.h: the chart of `frontier sweep`, drawn by gnuplot.
//
// DIR/sweep.gp (the script) and DIR/sweep.dat (its data) are always written; gnuplot then runs in
// DIR as a child process (no shell) and draws DIR/sweep.png: trajectory error (m) against cost
// (wall seconds per simulated second), log-log, one line per method with its points labelled by
// dt, and the Pareto front as a highlighted step line. `cd DIR && gnuplot sweep.gp` redraws it.
#pragma once

#include "study/sweep.h"

#include <stdexcept>
#include <string>

namespace frontier::app
{

// The sweep's results (study/sweep.h).
using study::paretoFront;
using study::SweepCell;
using study::SweepResult;

// gnuplot ran but failed (exit code 1 of the command).
class ChartError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// gnuplot on the PATH, or empty when it is not installed.
std::string findGnuplot();

// Writes folder/sweep.gp and folder/sweep.dat and, when gnuplot is installed, runs it to draw
// folder/sweep.png. Returns false when gnuplot is not installed (no PNG; an older sweep.png is
// removed so it cannot pass for this sweep's). Throws io::OutputError when a file cannot be
// written, ChartError when gnuplot fails.
bool drawSweepChart(const std::string& folder, const std::string& sceneName, const SweepResult& result);

} // namespace frontier::app
