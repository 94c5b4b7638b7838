// collision/separation.cpp: a cheap proof that two shapes are farther apart than the margin, so
// the narrowphase (FCL's collide, the feature points, fcl::distance for the gap) can be skipped.
// The gap between two convex shapes is at least their separation along any unit axis u: the
// distance between their centres along u less each shape's half extent along u (its support
// function). Trying the line between the centres and the shapes' own axes (box face normals,
// capsule and cylinder axes) catches most pairs that the margin-grown AABBs let through. A
// convex hull's extent is exact (its corners); a triangle mesh counts as its bounding sphere.
#include "collision/contacts.h"
#include "collision/internal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace frontier::collision::detail
{

namespace
{

// The interval [lo, hi] (m) that (x - p_WS) . u covers over the shape, u unit. Not exact (a hull
// mesh by the box that holds it: three products instead of a pass over its corners): an interval
// that holds the exact one.
void extentAlong(const ShapeInstance& s, const Vec3& u, double& lo, double& hi, bool exact)
{
    double half = s.boundingRadius; // a triangle mesh: its bounding sphere
    switch (s.type)
    {
    case core::ShapeType::Box:
        half = s.halfExtents.x() * std::abs(s.R_WS.col(0).dot(u)) +
               s.halfExtents.y() * std::abs(s.R_WS.col(1).dot(u)) +
               s.halfExtents.z() * std::abs(s.R_WS.col(2).dot(u));
        break;
    case core::ShapeType::Sphere:
        half = s.radius;
        break;
    case core::ShapeType::Capsule:
        half = s.radius + s.halfLength * std::abs(s.R_WS.col(2).dot(u));
        break;
    case core::ShapeType::Cylinder:
    {
        const double c = std::abs(s.R_WS.col(2).dot(u));
        half = s.halfLength * c + s.radius * std::sqrt(std::max(0.0, 1.0 - c * c));
        break;
    }
    case core::ShapeType::Mesh:
        if (s.convexHull && !exact)
        {
            const Vec3 u_S = s.R_WS.transpose() * u;
            const double centre = u_S.dot(s.geometry->meshBoxCentre);
            const double reach = s.geometry->meshBoxHalf.dot(u_S.cwiseAbs());
            lo = centre - reach;
            hi = centre + reach;
            return;
        }
        if (s.convexHull)
        {
            // Exact: the hull's corners furthest either way, which need not be centred on the
            // shape origin.
            const Vec3 u_S = s.R_WS.transpose() * u;
            if (s.meshVertices().size() <= static_cast<std::size_t>(cHullCorners))
            {
                // Both ends in one pass over the corners (a capped hull's at most): cheaper than
                // two climbs from the seeds, and the same values.
                lo = std::numeric_limits<double>::infinity();
                hi = -lo;
                for (const Vec3& v : s.meshVertices())
                {
                    const double x = u_S.dot(v);
                    lo = std::min(lo, x);
                    hi = std::max(hi, x);
                }
                return;
            }
            lo = u_S.dot(s.meshVertices()[static_cast<std::size_t>(hullExtremeCorner(s, -u_S))]);
            hi = u_S.dot(s.meshVertices()[static_cast<std::size_t>(hullExtremeCorner(s, u_S))]);
            return;
        }
        break;
    case core::ShapeType::Plane:
        break;
    }
    lo = -half;
    hi = half;
}

// Separation of a and b along unit u (m); negative when their projections overlap.
double separationAlong(const ShapeInstance& a, const ShapeInstance& b, const Vec3& u, bool exact)
{
    double loA = 0.0, hiA = 0.0, loB = 0.0, hiB = 0.0;
    extentAlong(a, u, loA, hiA, exact);
    extentAlong(b, u, loB, hiB, exact);
    const double d = (b.p_WS - a.p_WS).dot(u); // b's origin relative to a's along u
    return std::max(d - hiA + loB, -d + loA - hiB);
}

// Separation along u beyond the margin: first by the hulls' boxes (cheap), then exactly. found
// receives the separation that exceeded the margin (a lower bound of the distance).
bool separatedAlong(const ShapeInstance& a, const ShapeInstance& b, const Vec3& u, double margin,
                    double& found)
{
    found = separationAlong(a, b, u, false);
    if (found > margin)
    {
        return true;
    }
    if (!(a.convexHull || b.convexHull))
        return false;
    found = separationAlong(a, b, u, true);
    return found > margin;
}

// Tries the shape's own axes (face normals of a box, the axis of a capsule or cylinder); the
// one that separates goes to axis.
bool separatedByOwnAxes(const ShapeInstance& s, const ShapeInstance& a, const ShapeInstance& b, double margin,
                        Vec3& axis, double& found)
{
    switch (s.type)
    {
    case core::ShapeType::Box:
        for (int k = 0; k < 3; ++k)
        {
            if (separatedAlong(a, b, s.R_WS.col(k), margin, found))
            {
                axis = s.R_WS.col(k);
                return true;
            }
        }
        return false;
    case core::ShapeType::Capsule:
    case core::ShapeType::Cylinder:
        axis = s.R_WS.col(2);
        return separatedAlong(a, b, axis, margin, found);
    default:
        return false;
    }
}

} // namespace

bool separatedBeyond(const ShapeInstance& a, const ShapeInstance& b, double margin, Vec3* axis,
                     double* separation)
{
    Vec3 found = Vec3::UnitZ();
    double by = 0.0;
    const Vec3 between = b.p_WS - a.p_WS;
    const double length = between.norm();
    bool apart = false;
    if (length > 0.0 && separatedAlong(a, b, between / length, margin, by))
    {
        found = between / length;
        apart = true;
    }
    else
        apart =
            separatedByOwnAxes(a, a, b, margin, found, by) || separatedByOwnAxes(b, a, b, margin, found, by);
    if (apart && axis != nullptr)
        *axis = found;
    if (apart && separation != nullptr)
        *separation = by;
    return apart;
}

bool separatedAlongAxis(const ShapeInstance& a, const ShapeInstance& b, const Vec3& u, double margin,
                        double* separation)
{
    double found = 0.0;
    const bool apart = separatedAlong(a, b, u, margin, found);
    if (apart && separation != nullptr)
        *separation = found;
    return apart;
}

} // namespace frontier::collision::detail
