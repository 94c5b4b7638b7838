// io/mass_properties.cpp: composite mass properties (parallel-axis theorem) and inertia checks.
#include "io/mass_properties.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

namespace frontier::io::detail
{

CompositeMass combineMassParts(const std::vector<MassPart>& parts)
{
    CompositeMass out;
    for (const MassPart& part : parts)
    {
        out.mass += part.mass;
    }
    if (!(out.mass > 0.0))
    {
        out.mass = 0.0;
        return out;
    }
    for (const MassPart& part : parts)
    {
        out.centre += part.mass / out.mass * part.centre;
    }
    for (const MassPart& part : parts)
    {
        if (part.mass == 0.0)
        {
            continue;
        }
        const core::Vec3 d = part.centre - out.centre;
        out.inertia +=
            part.inertia + part.mass * (d.squaredNorm() * core::Mat3::Identity() - d * d.transpose());
    }
    return out;
}

CompositeMass compositeMassProperties(const std::vector<core::Shape>& shapes, double density)
{
    std::vector<MassPart> parts;
    for (const core::Shape& shape : shapes)
    {
        if (shape.type == core::ShapeType::Plane)
        {
            continue;
        }
        const core::MassProperties mp = core::shapeMassProperties(shape, density);
        const core::Mat3 r = shape.rotation_BS.toRotationMatrix();
        parts.push_back({mp.mass, shape.position_BS + r * mp.centre, r * mp.inertia * r.transpose()});
    }
    return combineMassParts(parts);
}

bool isPositiveDefinite(const core::Mat3& inertia)
{
    if (!inertia.allFinite() ||
        (inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * inertia.norm())
    {
        return false;
    }
    const Eigen::SelfAdjointEigenSolver<core::Mat3> solver(inertia, Eigen::EigenvaluesOnly);
    return solver.info() == Eigen::Success && solver.eigenvalues().minCoeff() > 0.0;
}

std::string inertiaDefect(const core::Mat3& inertia, double mass)
{
    if (!inertia.allFinite())
    {
        return "is not finite";
    }
    if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12 * inertia.norm())
    {
        return "is not symmetric";
    }
    const Eigen::SelfAdjointEigenSolver<core::Mat3> solver(inertia, Eigen::EigenvaluesOnly);
    if (solver.info() != Eigen::Success)
    {
        return "has no principal moments";
    }
    const core::Vec3 moments = solver.eigenvalues(); // ascending
    std::ostringstream out;
    if (!(moments(0) > 0.0))
    {
        out << "is not positive-definite (principal moments " << moments(0) << ", " << moments(1) << ", "
            << moments(2) << " kg m^2)";
        return out.str();
    }
    // I1 + I2 >= I3 holds for every mass distribution (equality for a flat one); allow round-off.
    if (moments(0) + moments(1) < moments(2) * (1.0 - 1e-6))
    {
        out << "has principal moments " << moments(0) << ", " << moments(1) << ", " << moments(2)
            << " kg m^2, which no mass distribution has (the two smaller must add up to the largest)";
        return out.str();
    }
    if (mass > 0.0 && std::sqrt(moments(0) / mass) < cMinGyrationRadius)
    {
        out << "is nearly zero (principal moment " << moments(0) << " kg m^2 at mass " << mass
            << " kg: a radius of gyration of " << std::sqrt(moments(0) / mass) << " m)";
        return out.str();
    }
    return {};
}

} // namespace frontier::io::detail
