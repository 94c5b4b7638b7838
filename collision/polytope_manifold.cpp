// collision/polytope_manifold.cpp: the contact patch of two convex polytopes (a moving mesh's
// convex hull against another hull or a box) by clipping one face against the other, as
// Box2D's polygon manifold and Bullet's clipHullAgainstHull do.
//
// libccd (through FCL) returns one point for two convex polytopes, found by MPR, whose normal
// need not be the face normal of the touching faces and whose depth can overestimate the
// minimal one. Vertices tested against the other shape (feature_manifold.cpp) miss the patch
// corners where edges cross (two equal cubes shifted against each other touch on a rectangle
// whose two other corners are edge crossings). So:
//   1. Axis: from FCL's normal m (a -> b), the face of a turned most along m, the face of b
//      turned most against m, and m itself are candidates; the one with the least overlap of
//      the two shapes' extents along it wins (each overlap is an upper bound of the true
//      penetration depth, exact for the minimal axis). A face of a wins ties over a face of b,
//      a face over m: a face contact is a patch, stable to hold a body at rest.
//   2. Face contact: the incident face (of the other shape, turned most against the reference
//      face) is clipped to the prism over the reference face (Sutherland-Hodgman); each clipped
//      corner closer than the margin to the reference plane is a contact, normal the reference
//      face's, depth its distance below that plane, point halfway.
//   3. Otherwise (edge against edge, where m is the better axis): FCL's single point.
// mergeAndReduce() then keeps at most four points.
// A polytope against a triangle mesh (concave: terrain, fixtures) is clipped the same way
// against each triangle FCL reports touching, the triangle taken as a flat polytope of two
// faces; the union of the clipped patches is the manifold.
#include "collision/internal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace frontier::collision::detail
{

namespace
{

// The face of p (world) whose outward normal has the largest dot product with d_W.
std::size_t faceAlong(const ShapeInstance& p, const Vec3& d_W)
{
    const Vec3 d = p.R_WS.transpose() * d_W;
    std::size_t best = 0;
    for (std::size_t k = 1; k < p.hull().normals.size(); ++k)
        if (d.dot(p.hull().normals[k]) > d.dot(p.hull().normals[best]))
            best = k;
    return best;
}

// max over p of u_W . x (m), over its corners.
double supportAlong(const ShapeInstance& p, const Vec3& u_W)
{
    const Vec3 u = p.R_WS.transpose() * u_W;
    double best = -std::numeric_limits<double>::infinity();
    for (const Vec3& v : p.hull().vertices)
        best = std::max(best, u.dot(v));
    return best + u_W.dot(p.p_WS);
}

// Overlap of a and b along the unit u (a -> b): how far b must move along u to clear a (m);
// negative: the gap between them along u.
double overlapAlong(const ShapeInstance& a, const ShapeInstance& b, const Vec3& u)
{
    return supportAlong(a, u) + supportAlong(b, -u);
}

Vec3 worldCorner(const ShapeInstance& p, int index)
{
    return p.p_WS + p.R_WS * p.hull().vertices[static_cast<std::size_t>(index)];
}

// Corners of face k of p in the world, in their counter-clockwise order.
void faceCorners(const ShapeInstance& p, std::size_t k, std::vector<Vec3>& out)
{
    out.clear();
    const auto start = static_cast<std::size_t>(p.hull().faceStart[k]);
    const int n = p.hull().faces[start];
    for (int i = 1; i <= n; ++i)
        out.push_back(worldCorner(p, p.hull().faces[start + static_cast<std::size_t>(i)]));
}

// Keeps the part of the polygon where s . (x - q) >= 0 (Sutherland-Hodgman, one plane).
void clipPolygon(const std::vector<Vec3>& in, const Vec3& s, const Vec3& q, std::vector<Vec3>& out)
{
    out.clear();
    const std::size_t n = in.size();
    for (std::size_t i = 0; i < n; ++i)
    {
        const Vec3& p0 = in[i];
        const Vec3& p1 = in[(i + 1) % n];
        const double d0 = s.dot(p0 - q);
        const double d1 = s.dot(p1 - q);
        if (d0 >= 0.0)
            out.push_back(p0);
        if ((d0 >= 0.0) != (d1 >= 0.0))
            out.push_back(p0 + (d0 / (d0 - d1)) * (p1 - p0));
    }
}

// The clipped incident face of `incident` against face `k` of `reference`, reported with the
// normal `sign` * (the reference face's outward normal), sign = +1 when the reference shape is
// a of the pair, -1 when it is b (normals run from a to b).
void clipFaces(const ShapeInstance& reference, std::size_t k, const ShapeInstance& incident, double sign,
               double margin, std::vector<RawContact>& out)
{
    thread_local std::vector<Vec3> polygon, clipped, referenceCorners; // reused: no allocation per step
    const Vec3 n = reference.R_WS * reference.hull().normals[k];
    faceCorners(incident, faceAlong(incident, -n), polygon);
    faceCorners(reference, k, referenceCorners);
    const std::size_t count = referenceCorners.size();
    for (std::size_t i = 0; i < count && !polygon.empty(); ++i)
    {
        const Vec3& q0 = referenceCorners[i];
        const Vec3& q1 = referenceCorners[(i + 1) % count];
        clipPolygon(polygon, n.cross(q1 - q0), q0, clipped); // n x edge points into the face
        std::swap(polygon, clipped);
    }
    const double offset = n.dot(referenceCorners.front());
    for (const Vec3& x : polygon)
    {
        const double separation = n.dot(x) - offset; // < 0: x is below the reference face
        if (separation < margin)
            out.push_back({x - 0.5 * separation * n, sign * n, -separation});
    }
}

} // namespace

bool setTrianglePolytope(const Vec3& t0_W, const Vec3& t1_W, const Vec3& t2_W, ShapeGeometry& geometry,
                         ShapeInstance& out)
{
    const Vec3 normal = (t1_W - t0_W).cross(t2_W - t0_W);
    if (!(normal.norm() > 0.0))
        return false; // a degenerate triangle has no face to clip against
    const Vec3 n = normal.normalized();
    out.R_WS.setIdentity();
    out.p_WS.setZero();
    ConvexHull& h = geometry.hull; // assign() keeps the capacity: no allocation after the first call
    h.vertices.assign({t0_W, t1_W, t2_W});
    h.faces.assign({3, 0, 1, 2, 3, 0, 2, 1});
    h.faceStart.assign({0, 4});
    h.normals.assign({n, -n});
    h.offsets.assign({n.dot(t0_W), -n.dot(t0_W)});
    return true;
}

void polytopeContacts(const ShapeInstance& a, const ShapeInstance& b, const RawContact& reference,
                      double margin, std::vector<RawContact>& out)
{
    const Vec3& m = reference.normal_W;
    const std::size_t faceA = faceAlong(a, m);
    const std::size_t faceB = faceAlong(b, -m);
    const Vec3 nA = a.R_WS * a.hull().normals[faceA];
    const Vec3 nB = b.R_WS * b.hull().normals[faceB];
    const double overlapA = overlapAlong(a, b, nA);
    const double overlapB = overlapAlong(a, b, -nB);
    const double overlapM = overlapAlong(a, b, m);
    // Below this (m) two overlaps count as equal: a face is then preferred (a patch). A face
    // chosen over a slightly better edge axis overstates the depth by at most this much.
    const double tolerance = 1e-3 * margin + 1e-12;
    const double overlapFace = std::min(overlapA, overlapB);
    const std::size_t before = out.size();
    if (overlapFace <= overlapM + tolerance)
    {
        if (overlapA <= overlapB + tolerance)
            clipFaces(a, faceA, b, 1.0, margin, out);
        else
            clipFaces(b, faceB, a, -1.0, margin, out);
    }
    // Edge against edge, or a clip that left nothing (the faces chosen from a poor normal):
    // the reference point alone.
    if (out.size() == before && reference.depth > -margin)
        out.push_back(reference);
}

} // namespace frontier::collision::detail
