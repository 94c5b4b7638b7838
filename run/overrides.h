// run/overrides.h: settings given beside a scene (`frontier run` flags, Python's load keywords,
// batch plans) over the scene file's own: the time step, the method and the contact tolerances.
#pragma once

#include "core/model.h"

#include <optional>
#include <string>

namespace frontier::run
{

struct SettingOverrides
{
    std::optional<double> dt;              // s
    std::optional<std::string> solver;     // linear, dense, pgs
    std::optional<int> pgsIterations;      // sweeps of pgs
    std::optional<std::string> integrator; // euler, rattle, rattle4
    core::ContactTolerances contact;
};

// Applies the overrides given to model.simulation and model.contact. Throws io::InputError naming
// model.sourceFile for a dt outside (0, core::cMaxTimeStep] s, an unknown solver or integrator
// name (the message lists the known ones) or a pgs sweep count outside 1..cMaxPgsIterations.
void applySettingOverrides(const SettingOverrides& overrides, core::Model& model);

} // namespace frontier::run
