// collision/shape_instance.cpp: the collision view of one model shape (sizes, bounds, pose).
#include "collision/internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace frontier::collision::detail
{

namespace
{

// Hulls of at most this many corners find their extreme corner in one pass over them.
constexpr std::size_t cLinearScanCorners = 40;

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

// A box as a polytope: corner k as boxCorner(half, k), faces counter-clockwise from outside.
ConvexHull boxPolytope(const Vec3& half)
{
    ConvexHull box;
    for (int k = 0; k < 8; ++k)
        box.vertices.push_back(boxCorner(half, k));
    for (int i = 0; i < 3; ++i)
    {
        // Corners of the face normal to axis i, by their signs along axes j and k = i + 1, i + 2
        // (e_i = e_j x e_k): (-,-), (+,-), (+,+), (-,+) turns counter-clockwise about +e_i.
        const int j = (i + 1) % 3;
        const int k = (i + 2) % 3;
        const int around[4] = {0, 1 << j, (1 << j) | (1 << k), 1 << k};
        for (const int side : {1, -1})
        {
            box.faceStart.push_back(static_cast<int>(box.faces.size()));
            box.faces.push_back(4);
            for (int c = 0; c < 4; ++c)
                box.faces.push_back((side > 0 ? 1 << i : 0) | around[side > 0 ? c : (4 - c) % 4]);
            box.normals.push_back(static_cast<double>(side) * Vec3::Unit(i));
            box.offsets.push_back(half[i]);
        }
    }
    return box;
}

// The hull of a mesh that collides as one (meshAsHull), of at most maxHullCorners corners when
// that is positive (collision/README.md "Meshes"): the capped hull lies inside the full one, at
// most hullDeviation from it. Should qhull fail on the subset (it never has), the full hull stays.
// False when the mesh has no 3-d hull (flat, collinear, under 4 points): it keeps its triangles,
// and still collides as before; a flat plate has no volume for GJK/EPA to work in.
bool buildHull(const core::Shape& shape, bool meshAsHull, int maxHullCorners, ShapeGeometry& g)
{
    std::string reason;
    if (!meshAsHull || !computeConvexHull(shape.vertices, g.hull, reason))
        return false;
    if (maxHullCorners > 0 && g.hull.vertices.size() > static_cast<std::size_t>(maxHullCorners))
    {
        ConvexHull capped;
        if (capConvexHull(g.hull, maxHullCorners, capped, reason))
        {
            g.fullHullCorners = static_cast<int>(g.hull.vertices.size());
            g.hullDeviation = hullDeviation(g.hull, capped);
            g.hull = std::move(capped);
        }
    }
    if (g.fullHullCorners == 0)
        g.fullHullCorners = static_cast<int>(g.hull.vertices.size());
    return true;
}

// Each hull corner's neighbours along its edges, and the seeds of the climb (hullExtremeCorner).
void buildHullClimb(ShapeGeometry& g)
{
    g.hullNeighbours.assign(g.hull.vertices.size(), {});
    for (const int start : g.hull.faceStart)
    {
        const int n = g.hull.faces[static_cast<std::size_t>(start)];
        for (int k = 0; k < n; ++k)
        {
            const int i = g.hull.faces[static_cast<std::size_t>(start + 1 + k)];
            const int j = g.hull.faces[static_cast<std::size_t>(start + 1 + (k + 1) % n)];
            g.hullNeighbours[static_cast<std::size_t>(i)].push_back(j); // each edge is in two faces,
        }                                                               // once either way round
    }
    g.hullSeeds = {0};
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x != 0 || y != 0 || z != 0)
                    g.hullSeeds.push_back(hullExtremeCorner(g, Vec3(x, y, z)));
    std::sort(g.hullSeeds.begin(), g.hullSeeds.end());
    g.hullSeeds.erase(std::unique(g.hullSeeds.begin(), g.hullSeeds.end()), g.hullSeeds.end());
}

// The box along the shape frame's axes that holds the mesh's vertices.
void setMeshBox(ShapeGeometry& g)
{
    if (g.meshVertices.empty())
        return;
    Vec3 lo = g.meshVertices.front(), hi = lo;
    for (const Vec3& v : g.meshVertices)
    {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    g.meshBoxCentre = 0.5 * (lo + hi);
    g.meshBoxHalf = 0.5 * (hi - lo);
}

// A mesh's sizes and geometry: its hull (Hull) or its unique vertices (Triangles).
void setMesh(const core::Shape& shape, bool meshAsHull, int maxHullCorners, ShapeInstance& s,
             ShapeGeometry& g)
{
    s.convexHull = buildHull(shape, meshAsHull, maxHullCorners, g);
    s.kind = s.convexHull ? CollisionKind::Hull : CollisionKind::Triangles;
    // Only the hull's corners can be a deepest point (against a plane, a face, along an axis), so
    // the plane and feature contacts, bounds and support functions use them.
    g.meshVertices = s.convexHull ? g.hull.vertices : uniqueVertices(shape.vertices);
    for (const Vec3& v : g.meshVertices)
        s.boundingRadius = std::max(s.boundingRadius, v.norm());
    if (s.convexHull)
        buildHullClimb(g);
    setMeshBox(g);
    s.mergeDistance = 0.05 * s.boundingRadius;
}

// The sizes of a primitive (box, sphere, capsule, cylinder); a box's polytope into g when built.
void setPrimitive(const core::Shape& shape, bool buildGeometry, ShapeInstance& s, ShapeGeometry& g)
{
    switch (shape.type)
    {
    case core::ShapeType::Box:
        s.kind = CollisionKind::Box;
        s.halfExtents = 0.5 * shape.size;
        if (buildGeometry)
            g.hull = boxPolytope(s.halfExtents);
        s.boundingRadius = s.halfExtents.norm();
        s.mergeDistance = 0.25 * shape.size.minCoeff();
        break;
    case core::ShapeType::Sphere:
        s.kind = CollisionKind::Sphere;
        s.radius = shape.radius;
        s.boundingRadius = shape.radius;
        s.mergeDistance = 0.25 * shape.radius;
        break;
    case core::ShapeType::Capsule:
        s.kind = CollisionKind::Capsule;
        s.radius = shape.radius;
        s.halfLength = 0.5 * shape.length;
        s.boundingRadius = s.radius + s.halfLength;
        s.mergeDistance = 0.25 * shape.radius;
        break;
    case core::ShapeType::Cylinder:
        s.kind = CollisionKind::Cylinder;
        s.radius = shape.radius;
        s.halfLength = 0.5 * shape.length;
        s.boundingRadius = std::hypot(s.radius, s.halfLength);
        s.mergeDistance = 0.25 * shape.radius;
        break;
    case core::ShapeType::Mesh:
    case core::ShapeType::Plane:
        break; // a mesh: setMesh; planes are not instances (contacts.cpp keeps them apart)
    }
}

} // namespace

const char* collisionKindName(CollisionKind kind)
{
    static constexpr std::array<const char*, cCollisionKinds> names = {"sphere",   "capsule", "box",
                                                                       "cylinder", "hull",    "triangles"};
    return names[static_cast<std::size_t>(kind)];
}

ShapeInstance makeShapeInstance(const core::Shape& shape, int body, bool meshAsHull,
                                std::shared_ptr<const ShapeGeometry> shared, int maxHullCorners)
{
    ShapeInstance s;
    if (shape.type == core::ShapeType::Mesh)
        shared = nullptr; // a mesh's geometry is its own
    std::shared_ptr<ShapeGeometry> own = shared ? nullptr : std::make_shared<ShapeGeometry>();
    ShapeGeometry unused;
    ShapeGeometry& g = own ? *own : unused; // what the steps below build
    s.body = body;
    s.type = shape.type;
    s.R_BS = shape.rotation_BS.normalized().toRotationMatrix();
    s.p_BS = shape.position_BS;
    if (shape.type == core::ShapeType::Mesh)
        setMesh(shape, meshAsHull, maxHullCorners, s, g);
    else
        setPrimitive(shape, own != nullptr, s, g);
    s.mergeDistance = std::max(s.mergeDistance, 1e-9);
    s.geometry = shared ? std::move(shared) : std::move(own);
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

int hullExtremeCorner(const ShapeInstance& s, const Vec3& u_S)
{
    return hullExtremeCorner(*s.geometry, u_S);
}

int hullExtremeCorner(const ShapeGeometry& s, const Vec3& u_S)
{
    int best = 0;
    double bestValue = u_S.dot(s.meshVertices.front());
    if (s.meshVertices.size() <= cLinearScanCorners)
    {
        // Few corners: one pass over them is cheaper than the seeds and the climb.
        for (std::size_t k = 1; k < s.meshVertices.size(); ++k)
        {
            const double value = u_S.dot(s.meshVertices[k]);
            if (value > bestValue)
            {
                best = static_cast<int>(k);
                bestValue = value;
            }
        }
        return best;
    }
    for (const int seed : s.hullSeeds)
    {
        const double value = u_S.dot(s.meshVertices[static_cast<std::size_t>(seed)]);
        if (value > bestValue)
        {
            best = seed;
            bestValue = value;
        }
    }
    for (bool moved = true; moved;)
    {
        moved = false;
        for (const int next : s.hullNeighbours[static_cast<std::size_t>(best)])
        {
            const double value = u_S.dot(s.meshVertices[static_cast<std::size_t>(next)]);
            if (value > bestValue)
            {
                best = next;
                bestValue = value;
                moved = true;
            }
        }
    }
    return best;
}

} // namespace frontier::collision::detail
