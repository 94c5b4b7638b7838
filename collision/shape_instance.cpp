// collision/shape_instance.cpp: the collision view of one model shape (sizes, bounds, pose).
#include "collision/internal.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace frontier::collision::detail
{

namespace
{

// Unique mesh vertices, in a deterministic (lexicographic) order.
std::vector<Vec3> uniqueVertices(const std::vector<Vec3>& vertices)
{
    std::vector<Vec3> out = vertices;
    auto less = [](const Vec3& p, const Vec3& q)
    { return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3); };
    std::sort(out.begin(), out.end(), less);
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

} // namespace

ShapeInstance makeShapeInstance(const core::Shape& shape, int body)
{
    ShapeInstance s;
    s.body = body;
    s.type = shape.type;
    s.R_BS = shape.rotation_BS.normalized().toRotationMatrix();
    s.p_BS = shape.position_BS;
    switch (shape.type)
    {
    case core::ShapeType::Box:
        s.halfExtents = 0.5 * shape.size;
        s.boundingRadius = s.halfExtents.norm();
        s.mergeDistance = 0.25 * shape.size.minCoeff();
        break;
    case core::ShapeType::Sphere:
        s.radius = shape.radius;
        s.boundingRadius = shape.radius;
        s.mergeDistance = 0.25 * shape.radius;
        break;
    case core::ShapeType::Capsule:
        s.radius = shape.radius;
        s.halfLength = 0.5 * shape.length;
        s.boundingRadius = s.radius + s.halfLength;
        s.mergeDistance = 0.25 * shape.radius;
        break;
    case core::ShapeType::Cylinder:
        s.radius = shape.radius;
        s.halfLength = 0.5 * shape.length;
        s.boundingRadius = std::hypot(s.radius, s.halfLength);
        s.mergeDistance = 0.25 * shape.radius;
        break;
    case core::ShapeType::Mesh:
        s.meshVertices = uniqueVertices(shape.vertices);
        for (const Vec3& v : s.meshVertices)
            s.boundingRadius = std::max(s.boundingRadius, v.norm());
        s.mergeDistance = 0.05 * s.boundingRadius;
        break;
    case core::ShapeType::Plane:
        break; // planes are not instances (contacts.cpp keeps them apart)
    }
    s.mergeDistance = std::max(s.mergeDistance, 1e-9);
    return s;
}

const std::array<std::array<double, 2>, cRimSamples>& rimDirections()
{
    static const auto table = []
    {
        std::array<std::array<double, 2>, cRimSamples> t{};
        for (int k = 0; k < cRimSamples; ++k)
        {
            const double angle = 2.0 * std::numbers::pi * k / cRimSamples;
            t[static_cast<std::size_t>(k)] = {std::cos(angle), std::sin(angle)};
        }
        return t;
    }();
    return table;
}

void setBodyPose(ShapeInstance& s, const Mat3& R_WB, const Vec3& p_WB)
{
    s.R_WS = R_WB * s.R_BS;
    s.p_WS = p_WB + R_WB * s.p_BS;
}

} // namespace frontier::collision::detail
