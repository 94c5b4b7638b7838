// app/model_overrides.h: command-line flags override the scene file's simulation settings.
#pragma once

#include "app/commands.h"
#include "core/model.h"

#include <string>
#include <vector>

namespace frontier::app
{

// The most steps a run may take: more could only come from a typo (1e12 steps take days at the
// fastest step rates, and a count near 2^63 would overflow).
inline constexpr double cMaxSteps = 1e12;
// The largest time step and duration a run takes (s), from the flags, a batch plan or a scene:
// the ranges of core/model.h.
inline constexpr double cMaxTimeStepS = core::cMaxTimeStep;
inline constexpr double cMaxDurationS = core::cMaxDuration;

// round(duration / dt), at least 1; throws io::InputError naming `source` (the scene or the flags)
// when dt or duration is not a finite positive number or the count exceeds cMaxSteps.
long checkedStepCount(double duration, double dt, const std::string& source);

// Applies --dt, --duration/--steps, --solver, --pgs-iterations, --integrator and the contact
// tolerances. Returns the step count; throws io::InputError when it is not a sane one
// (checkedStepCount).
long applyOverrides(const RunOptions& options, core::Model& model);

// "" when `steps` of `dt` (s) simulate the duration asked (s); else a note that the run simulates
// steps x dt instead, rounded to whole steps.
std::string roundedDurationNote(double duration, long steps, double dt);

// A warning for each load of the model that starts at or after `end` (s), the time the run stops:
// it never acts.
std::vector<std::string> loadsAfterTheEnd(const core::Model& model, double end);

} // namespace frontier::app
