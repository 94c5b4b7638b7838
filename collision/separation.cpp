// collision/separation.cpp: a cheap proof that two shapes are farther apart than the margin, so
// the narrowphase (FCL's collide, the feature points, fcl::distance for the gap) can be skipped.
// The gap between two convex shapes is at least their separation along any unit axis u: the
// distance between their centres along u less each shape's half extent along u (its support
// function). Trying the line between the centres and the shapes' own axes (box face normals,
// capsule and cylinder axes) catches most pairs that the margin-grown AABBs let through.
#include "collision/internal.h"

#include <algorithm>
#include <cmath>

namespace frontier::collision::detail
{

namespace
{

// Half extent of the shape along unit u (m): max over the shape of (x - p_WS) . u.
double halfExtent(const ShapeInstance& s, const Vec3& u)
{
    switch (s.type)
    {
    case core::ShapeType::Box:
        return s.halfExtents.x() * std::abs(s.R_WS.col(0).dot(u)) +
               s.halfExtents.y() * std::abs(s.R_WS.col(1).dot(u)) +
               s.halfExtents.z() * std::abs(s.R_WS.col(2).dot(u));
    case core::ShapeType::Sphere:
        return s.radius;
    case core::ShapeType::Capsule:
        return s.radius + s.halfLength * std::abs(s.R_WS.col(2).dot(u));
    case core::ShapeType::Cylinder:
    {
        const double c = std::abs(s.R_WS.col(2).dot(u));
        return s.halfLength * c + s.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
    }
    case core::ShapeType::Mesh:
    case core::ShapeType::Plane:
        break;
    }
    return s.boundingRadius;
}

// Separation of a and b along unit u (m); negative when their projections overlap.
double separationAlong(const ShapeInstance& a, const ShapeInstance& b, const Vec3& u)
{
    return std::abs((b.p_WS - a.p_WS).dot(u)) - halfExtent(a, u) - halfExtent(b, u);
}

// Tries the shape's own axes (face normals of a box, the axis of a capsule or cylinder).
bool separatedByOwnAxes(const ShapeInstance& s, const ShapeInstance& a, const ShapeInstance& b, double margin)
{
    switch (s.type)
    {
    case core::ShapeType::Box:
        for (int k = 0; k < 3; ++k)
        {
            if (separationAlong(a, b, s.R_WS.col(k)) > margin)
            {
                return true;
            }
        }
        return false;
    case core::ShapeType::Capsule:
    case core::ShapeType::Cylinder:
        return separationAlong(a, b, s.R_WS.col(2)) > margin;
    default:
        return false;
    }
}

} // namespace

bool separatedBeyond(const ShapeInstance& a, const ShapeInstance& b, double margin)
{
    const Vec3 between = b.p_WS - a.p_WS;
    const double length = between.norm();
    if (length > 0.0 && separationAlong(a, b, between / length) > margin)
    {
        return true;
    }
    return separatedByOwnAxes(a, a, b, margin) || separatedByOwnAxes(b, a, b, margin);
}

} // namespace frontier::collision::detail
