// collision/convex_hull.h: the convex hull of a point set (qhull's reentrant library, kept out
// of this header). The detector makes every moving mesh collide as its hull
// (collision/README.md "Meshes"); this is public so that tools can show what a mesh collides as.
#pragma once

#include "core/model.h"

#include <limits>
#include <string>
#include <vector>

namespace frontier::collision
{

// A convex polytope, in the frame of the points it was built from.
struct ConvexHull
{
    std::vector<core::Vec3> vertices; // its corners (m), lexicographic order (nverts)
    std::vector<int> faces;           // [n, i0, ..., in-1] per face, counter-clockwise seen from
                                      // outside (the layout of fcl::Convex)
    std::vector<int> faceStart;       // per face: the index in `faces` of its count n (nfaces)
    std::vector<core::Vec3> normals;  // per face: unit outward normal (nfaces)
    std::vector<double> offsets;      // per face: the solid is normal . x <= offset (m) (nfaces)
};

// The convex hull of the points (duplicates, interior points and points on faces allowed;
// coplanar faces are merged: a cube has 6 square faces). False, with the reason, when there is
// no 3-d hull: fewer than 4 distinct points, all of them on a plane or a line, a non-finite
// coordinate, or any other qhull error. Never exits, never writes to stderr.
bool computeConvexHull(const std::vector<core::Vec3>& points, ConvexHull& out, std::string& reason);

// The hull of at most maxCorners (>= 4) of the hull's corners, picked as the hull changes least:
// qhull's greedy insertion, each next corner the one farthest outside the hull of those picked so
// far (options Q9 Qf TA), so the result lies inside `full` and every corner left out is as near
// to it as this order makes it (collision/README.md "Meshes"). A hull of at most maxCorners
// corners is copied as it is. False, with the reason, when qhull fails (`out` is then empty).
bool capConvexHull(const ConvexHull& full, int maxCorners, ConvexHull& out, std::string& reason);

// Signed distance (m) from p to the hull (same frame): inside (or on it) the largest face-plane
// distance, exact; outside the distance to the nearest face polygon among those facing p, exact
// but O(faces x corners), so only computed when the largest face-plane distance (a lower bound of
// it) is below exactBelow, otherwise that lower bound. grad: the unit outward direction at p.
double hullSignedDistance(const ConvexHull& h, const core::Vec3& p, core::Vec3& grad,
                          double exactBelow = std::numeric_limits<double>::infinity());

// How far the hull `capped` (inside `full`, as capConvexHull makes it) is from `full`: the
// largest distance (m) of a corner of `full` outside `capped`, which is the largest distance of
// any point of `full` from `capped` (0 when it kept every corner).
double hullDeviation(const ConvexHull& full, const ConvexHull& capped);

} // namespace frontier::collision
