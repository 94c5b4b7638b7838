// collision/plane_manifold.cpp: contacts of a shape against the ground half-space, made here
// rather than by FCL, which returns a single point for box, capsule and cylinder against a
// half-space and so cannot hold a body at rest. Every candidate point on the
// shape's surface (box vertices, the deepest points of the capsule end spheres, cylinder rim
// points, mesh vertices) whose signed distance to the plane is below the margin becomes a
// contact; mergeAndReduce() then keeps at most four of them.
#include "collision/internal.h"

#include <array>
#include <cmath>

namespace frontier::collision::detail
{

namespace
{

// Eight directions around a circle (cos, sin), for cylinder rims.

struct PlaneSink
{
    const Vec3& n;
    double offset;
    double margin;
    std::vector<RawContact>& out;

    // q: a point on the shape's surface (m). Its separation from the plane is n . q - offset.
    void add(const Vec3& q) const
    {
        const double separation = n.dot(q) - offset;
        if (separation < margin)
            out.push_back({q - 0.5 * separation * n, -n, -separation});
    }
};

} // namespace

void planeContacts(const ShapeInstance& s, const Vec3& n, double offset, double margin,
                   std::vector<RawContact>& out)
{
    const PlaneSink sink{n, offset, margin, out};
    const Mat3& R = s.R_WS;
    const Vec3& p = s.p_WS;
    switch (s.type)
    {
    case core::ShapeType::Box:
        for (int k = 0; k < 8; ++k)
        {
            const Vec3 corner = boxCorner(s.halfExtents, k);
            sink.add(p + R * corner);
        }
        break;
    case core::ShapeType::Sphere:
        sink.add(p - s.radius * n);
        break;
    case core::ShapeType::Capsule:
    {
        const Vec3 axis = R.col(2) * s.halfLength;
        sink.add(p + axis - s.radius * n);
        sink.add(p - axis - s.radius * n);
        break;
    }
    case core::ShapeType::Cylinder:
    {
        const Vec3 axisUnit = R.col(2);
        const Vec3 axis = axisUnit * s.halfLength;
        const Vec3 u = R.col(0);
        const Vec3 v = R.col(1);
        // The deepest point of each rim (towards -n), unless the cylinder stands upright.
        const Vec3 down = -n + n.dot(axisUnit) * axisUnit;
        const double downNorm = down.norm();
        for (const double side : {1.0, -1.0})
        {
            const Vec3 centre = p + side * axis;
            if (downNorm > 1e-9)
                sink.add(centre + (s.radius / downNorm) * down);
            for (const auto& [c, sn] : rimDirections())
                sink.add(centre + s.radius * (c * u + sn * v));
        }
        break;
    }
    case core::ShapeType::Mesh:
    {
        // Each vertex's separation in the shape frame first (a dot product, not a rotation): only
        // those within the margin, give or take a nanometre for the rounding, are put in the world
        // and tested as before.
        const Vec3 n_S = R.transpose() * n;
        const double above = n.dot(p) - offset; // m, the shape origin's separation
        for (const Vec3& vertex : s.meshVertices())
            if (above + n_S.dot(vertex) < margin + 1e-9)
                sink.add(p + R * vertex);
        break;
    }
    case core::ShapeType::Plane:
        break;
    }
}

} // namespace frontier::collision::detail
