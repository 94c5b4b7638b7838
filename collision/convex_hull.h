// collision/convex_hull.h: the convex hull of a point set (qhull's reentrant library, kept out
// of this header). The detector makes every moving mesh collide as its hull
// (collision/README.md "Meshes"); this is public so that tools can show what a mesh collides as.
#pragma once

#include "core/model.h"

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

} // namespace frontier::collision
