// io/mass_properties.h: mass properties of a body's shapes together, and inertia checks.
#pragma once

#include "core/model.h"

#include <vector>

namespace frontier::io::detail
{

// Sum over shapes (poses position_BS/rotation_BS in a common frame D) at one density (kg/m^3).
struct CompositeMass
{
    double mass = 0.0;                       // kg
    core::Vec3 centre = core::Vec3::Zero();  // centre of mass in D (m)
    core::Mat3 inertia = core::Mat3::Zero(); // kg m^2 about the centre, axes of D
};
// Planes have no volume and are skipped.
CompositeMass compositeMassProperties(const std::vector<core::Shape>& shapes, double density);

// Symmetric with strictly positive eigenvalues.
bool isPositiveDefinite(const core::Mat3& inertia);

} // namespace frontier::io::detail
