// io/mass_properties.cpp: composite mass properties (parallel-axis theorem) and inertia checks.
#include "io/mass_properties.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace frontier::io::detail
{

CompositeMass compositeMassProperties(const std::vector<core::Shape>& shapes, double density)
{
    struct Part
    {
        double mass;
        core::Vec3 centre;
        core::Mat3 inertia;
    };
    std::vector<Part> parts;
    CompositeMass out;
    for (const core::Shape& shape : shapes)
    {
        if (shape.type == core::ShapeType::Plane)
        {
            continue;
        }
        const core::MassProperties mp = core::shapeMassProperties(shape, density);
        const core::Mat3 r = shape.rotation_BS.toRotationMatrix();
        parts.push_back({mp.mass, shape.position_BS + r * mp.centre, r * mp.inertia * r.transpose()});
        out.mass += mp.mass;
    }
    if (!(out.mass > 0.0))
    {
        return out;
    }
    for (const Part& part : parts)
    {
        out.centre += part.mass / out.mass * part.centre;
    }
    for (const Part& part : parts)
    {
        const core::Vec3 d = part.centre - out.centre;
        out.inertia +=
            part.inertia + part.mass * (d.squaredNorm() * core::Mat3::Identity() - d * d.transpose());
    }
    return out;
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

} // namespace frontier::io::detail
