// io/mass_properties.h: mass properties of several parts together, and what makes an inertia
// impossible for a rigid body.
#pragma once

#include "core/model.h"

#include <string>
#include <vector>

namespace frontier::io::detail
{

// One part of a composite, in a common frame D.
struct MassPart
{
    double mass = 0.0;                       // kg
    core::Vec3 centre = core::Vec3::Zero();  // its centre of mass in D (m)
    core::Mat3 inertia = core::Mat3::Zero(); // kg m^2 about its own centre, axes of D
};

// Sum over parts (parallel-axis theorem), all in a common frame D.
struct CompositeMass
{
    double mass = 0.0;                       // kg
    core::Vec3 centre = core::Vec3::Zero();  // centre of mass in D (m)
    core::Mat3 inertia = core::Mat3::Zero(); // kg m^2 about the centre, axes of D
};
// Parts of zero mass add nothing; a single massive part comes out exactly as it went in.
CompositeMass combineMassParts(const std::vector<MassPart>& parts);

// Shapes (poses position_BS/rotation_BS in a common frame D) at one density (kg/m^3). Planes
// have no volume and are skipped.
CompositeMass compositeMassProperties(const std::vector<core::Shape>& shapes, double density);

// Symmetric with strictly positive eigenvalues.
bool isPositiveDefinite(const core::Mat3& inertia);

// Smallest radius of gyration (m) a body may have about a principal axis: below it the mass would
// sit within a tenth of a millimetre of an axis, which no rigid part does (and which makes the
// joint equations nearly singular).
inline constexpr double cMinGyrationRadius = 1e-4;

// Why `inertia` (kg m^2, about the centre of mass) cannot be that of a rigid body of `mass` (kg):
// not finite or not symmetric, not positive-definite, principal moments that break the triangle
// inequality (I1 + I2 >= I3), or a radius of gyration below cMinGyrationRadius. "" when it can.
std::string inertiaDefect(const core::Mat3& inertia, double mass);

} // namespace frontier::io::detail
