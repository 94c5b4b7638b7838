// study/study.h: the public API of the studies, the engines behind `frontier sweep` and `frontier
// stability` (library frontier_study). They run a scene many times with the run loop of `frontier
// run` (run/run_loop.h), each run named by its app::Method, and return plain results; the
// commands in app/ parse the flags, call them and print.
//
// study/sweep.h         the grid of time steps x solvers x integrators against a reference run:
//                       parseTimeSteps, parseSolvers, parseIntegrators, defaultTimeSteps,
//                       planSchedule, makeSweepGrid, runSweep, paretoFront
// study/sweep_report.h  the sweep's results as sweep.csv and as a terminal table
// study/stability.h     the stability suite: runStabilityCell per scene and method (with the
//                       scene's own criteria, study/stability_criteria.h), largestHoldingDt,
//                       and the markdown report (stabilityMarkdown)
#pragma once

#include "study/stability.h"
#include "study/sweep.h"
#include "study/sweep_report.h"
