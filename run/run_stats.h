// run/run_stats.h: the stats file of a run (io/stats.h, `--stats`) from its summary: what `frontier
// run`, batch jobs and the Python module's recordings write.
#pragma once

#include "io/stats.h"
#include "run/run_loop.h"

#include <string>

namespace frontier::run
{

// The figures of `summary` for a run of `scene` (its path as given) with the model's settings;
// the caller adds completed, failure, warnings and inputs.
io::RunStats runStats(const std::string& scene, const core::Model& model, const RunSummary& summary);

} // namespace frontier::run
