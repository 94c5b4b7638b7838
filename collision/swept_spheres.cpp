// collision/swept_spheres.cpp: spheres and capsules against each other in closed form. Both are
// sphere-swept segments (a sphere's segment has length zero), so their distance is the distance
// between two segments less the radii, and the contact sits on the line joining the segments'
// closest points. FCL runs libccd's iterative MPR (penetration) or GJK (distance) for a capsule
// pair; this is exact, a few dozen flops, and gives the same single point (the feature points
// of feature_manifold.cpp complete the manifold as for FCL's point).
#include "collision/internal.h"

#include <algorithm>
#include <cmath>

namespace frontier::collision::detail
{

namespace
{

struct Segment
{
    Vec3 start = Vec3::Zero();
    Vec3 end = Vec3::Zero();
};

Segment axisOf(const ShapeInstance& s)
{
    if (s.type == core::ShapeType::Sphere)
    {
        return {s.p_WS, s.p_WS};
    }
    const Vec3 half = s.halfLength * s.R_WS.col(2); // capsule axis: shape z
    return {s.p_WS - half, s.p_WS + half};
}

// Closest points of two segments (Ericson, Real-Time Collision Detection, 5.1.9): parameters s
// on the first and t on the second, both in [0, 1]. Parallel segments take s = 0.
void closestParameters(const Segment& one, const Segment& two, double& s, double& t)
{
    constexpr double cTiny = 1e-24; // m^2: a segment shorter than 1e-12 m is a point
    const Vec3 d1 = one.end - one.start;
    const Vec3 d2 = two.end - two.start;
    const Vec3 r = one.start - two.start;
    const double a = d1.squaredNorm();
    const double e = d2.squaredNorm();
    const double f = d2.dot(r);
    if (a <= cTiny && e <= cTiny)
    {
        s = t = 0.0;
        return;
    }
    if (a <= cTiny)
    {
        s = 0.0;
        t = std::clamp(f / e, 0.0, 1.0);
        return;
    }
    const double c = d1.dot(r);
    if (e <= cTiny)
    {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
        return;
    }
    const double b = d1.dot(d2);
    const double denominator = a * e - b * b; // >= 0
    s = denominator > 1e-12 * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
    t = (b * s + f) / e;
    if (t < 0.0)
    {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
    }
    else if (t > 1.0)
    {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
    }
}

} // namespace

bool sweptSphereContact(const ShapeInstance& a, const ShapeInstance& b, double margin, RawContact& out,
                        double* separation)
{
    const Segment one = axisOf(a);
    const Segment two = axisOf(b);
    double s = 0.0, t = 0.0;
    closestParameters(one, two, s, t);
    const Vec3 ca = one.start + s * (one.end - one.start);
    const Vec3 cb = two.start + t * (two.end - two.start);
    const Vec3 between = cb - ca;
    const double distance = between.norm();
    const double depth = a.radius + b.radius - distance;
    if (separation != nullptr)
        *separation = -depth;
    if (!(depth > -margin))
    {
        return false;
    }
    Vec3 normal = Vec3::Zero();
    if (distance > 1e-12)
    {
        normal = between / distance;
    }
    else
    {
        // The axes cross: the normal is across both axes, or along the centres when they are
        // parallel; from a towards b.
        normal = (one.end - one.start).cross(two.end - two.start);
        if (normal.norm() <= 1e-12)
        {
            normal = b.p_WS - a.p_WS;
            if (normal.norm() <= 1e-12)
            {
                normal = Vec3::UnitZ();
            }
        }
        normal.normalize();
        if (normal.dot(b.p_WS - a.p_WS) < 0.0)
        {
            normal = -normal;
        }
    }
    out.normal_W = normal;
    out.depth = depth;
    out.point_W = ca + (a.radius - 0.5 * depth) * normal; // the middle of the overlap (or gap)
    return true;
}

} // namespace frontier::collision::detail
