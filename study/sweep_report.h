// study/sweep_report.h: the results of `frontier sweep` as DIR/sweep.csv and as a table for the
// terminal, with the Pareto front in words.
#pragma once

#include "study/sweep.h"

#include <string>

namespace frontier::study
{

// The CSV's column header (its second line, after the "# frontier sweep: ..." comment line).
// Columns, one row per cell (README.md, "Speed against accuracy"):
//   scene, integrator, solver (linear|dense|pgs), pgs_iterations (pgs only, else empty),
//   dt (s), steps, bodies (moving), survived (true|false), wall_seconds (the step loop),
//   seconds_per_sim_second, us_per_body_step, trajectory_error_m (largest centre-of-mass distance
//   to the reference over bodies and sample times), final_error_m (the last sample time alone),
//   worst_body (the body of final_error_m), max_joint_error_m, max_joint_error_rad,
//   energy_drift_j (largest |E(t) - E(0)|), energy_drift_rel (energy_drift_j / |E(0)|),
//   max_penetration_m, failure (the message when the run failed).
// Numbers are written with the shortest text that reads back to the same double; "nan" where a
// quantity does not exist (a failed run's errors, a run that never stepped).
extern const char* const cSweepCsvHeader;

// Writes the CSV atomically (throws io::OutputError).
void writeSweepCsv(const std::string& path, const std::string& scene, const SweepResult& result);

// The table (aligned columns, one line per cell), the failures below it (each message once) and
// the Pareto front on `accuracy` in one line (paretoFront, as the chart draws it).
std::string formatSweepTable(const SweepResult& result, Accuracy accuracy = Accuracy::TrajectoryError);

// One line describing the reference run.
std::string describeReference(const SweepResult& result);

} // namespace frontier::study
