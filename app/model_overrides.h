// app/model_overrides.h: command-line flags override the scene file's simulation settings.
#pragma once

#include "app/commands.h"
#include "core/model.h"

namespace frontier::app
{

// Applies --dt, --duration/--steps, --solver, --pgs-iterations, --integrator. Returns the step count.
long applyOverrides(const RunOptions& options, core::Model& model);

} // namespace frontier::app
