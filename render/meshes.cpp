// render/meshes.cpp: tessellation of boxes, spheres, capsules, cylinders and flat-shaded meshes.
#include "render/meshes.h"

#include <cmath>
#include <numbers>

namespace frontier::render
{
namespace
{

void pushVertex(MeshData& mesh, const core::Vec3& p, const core::Vec3& n)
{
    for (int k = 0; k < 3; ++k)
    {
        mesh.vertices.push_back(static_cast<float>(p[k]));
    }
    for (int k = 0; k < 3; ++k)
    {
        mesh.vertices.push_back(static_cast<float>(n[k]));
    }
}

// One point of a profile revolved about the z axis: distance from the axis, height, and the
// normal's radial and axial components.
struct ProfilePoint
{
    double r;
    double z;
    double nr;
    double nz;
};

// Revolves a profile strip (ordered so that (d/dtheta) x (d/dprofile) points outwards).
void revolve(MeshData& mesh, const std::vector<ProfilePoint>& strip, int slices)
{
    auto position = [](const ProfilePoint& p, double c, double s)
    { return core::Vec3(p.r * c, p.r * s, p.z); };
    auto normal = [](const ProfilePoint& p, double c, double s)
    { return core::Vec3(p.nr * c, p.nr * s, p.nz); };
    for (std::size_t i = 0; i + 1 < strip.size(); ++i)
    {
        const ProfilePoint& p0 = strip[i];
        const ProfilePoint& p1 = strip[i + 1];
        for (int j = 0; j < slices; ++j)
        {
            const double t0 = 2.0 * std::numbers::pi * j / slices;
            const double t1 = 2.0 * std::numbers::pi * (j + 1) / slices;
            const double c0 = std::cos(t0), s0 = std::sin(t0), c1 = std::cos(t1), s1 = std::sin(t1);
            // a = (i, j), b = (i, j+1), c = (i+1, j+1), d = (i+1, j)
            if (p0.r > 0.0)
            {
                pushVertex(mesh, position(p0, c0, s0), normal(p0, c0, s0));
                pushVertex(mesh, position(p0, c1, s1), normal(p0, c1, s1));
                pushVertex(mesh, position(p1, c1, s1), normal(p1, c1, s1));
            }
            if (p1.r > 0.0)
            {
                pushVertex(mesh, position(p0, c0, s0), normal(p0, c0, s0));
                pushVertex(mesh, position(p1, c1, s1), normal(p1, c1, s1));
                pushVertex(mesh, position(p1, c0, s0), normal(p1, c0, s0));
            }
        }
    }
}

// Points of a half sphere of `radius` centred at height zc, from latitude lat0 to lat1 (radians).
void appendArc(std::vector<ProfilePoint>& strip, double radius, double zc, double lat0, double lat1,
               int steps)
{
    for (int i = 0; i <= steps; ++i)
    {
        const double lat = lat0 + (lat1 - lat0) * i / steps;
        const double c = std::cos(lat), s = std::sin(lat);
        strip.push_back({std::abs(c) < 1e-12 ? 0.0 : radius * c, zc + radius * s, c, s});
    }
}

} // namespace

MeshData boxMesh(const core::Vec3& size)
{
    MeshData mesh;
    const core::Vec3 h = 0.5 * size.cwiseAbs();
    for (int axis = 0; axis < 3; ++axis)
    {
        for (int sign = -1; sign <= 1; sign += 2)
        {
            core::Vec3 n = core::Vec3::Zero();
            n[axis] = sign;
            // u, v span the face so that u x v = n.
            core::Vec3 u = core::Vec3::Zero();
            core::Vec3 v = core::Vec3::Zero();
            u[(axis + 1) % 3] = 1.0;
            v[(axis + 2) % 3] = 1.0;
            if (sign < 0)
            {
                std::swap(u, v);
            }
            const core::Vec3 c = n.cwiseProduct(h);
            const core::Vec3 du = u.cwiseProduct(h);
            const core::Vec3 dv = v.cwiseProduct(h);
            const core::Vec3 p00 = c - du - dv, p10 = c + du - dv, p11 = c + du + dv, p01 = c - du + dv;
            for (const core::Vec3& p : {p00, p10, p11, p00, p11, p01})
            {
                pushVertex(mesh, p, n);
            }
        }
    }
    return mesh;
}

MeshData sphereMesh(double radius, int slices, int stacks)
{
    MeshData mesh;
    std::vector<ProfilePoint> strip;
    appendArc(strip, radius, 0.0, -0.5 * std::numbers::pi, 0.5 * std::numbers::pi, stacks);
    revolve(mesh, strip, slices);
    return mesh;
}

MeshData capsuleMesh(double radius, double length, int slices, int stacksPerCap)
{
    MeshData mesh;
    std::vector<ProfilePoint> strip;
    appendArc(strip, radius, -0.5 * length, -0.5 * std::numbers::pi, 0.0, stacksPerCap);
    appendArc(strip, radius, 0.5 * length, 0.0, 0.5 * std::numbers::pi, stacksPerCap);
    revolve(mesh, strip, slices);
    return mesh;
}

MeshData cylinderMesh(double radius, double length, int slices)
{
    MeshData mesh;
    const double h = 0.5 * length;
    revolve(mesh, {{0.0, -h, 0.0, -1.0}, {radius, -h, 0.0, -1.0}}, slices);
    revolve(mesh, {{radius, -h, 1.0, 0.0}, {radius, h, 1.0, 0.0}}, slices);
    revolve(mesh, {{radius, h, 0.0, 1.0}, {0.0, h, 0.0, 1.0}}, slices);
    return mesh;
}

MeshData triangleMesh(const std::vector<core::Vec3>& vertices,
                      const std::vector<std::array<int, 3>>& triangles)
{
    MeshData mesh;
    const int count = static_cast<int>(vertices.size());
    for (const std::array<int, 3>& t : triangles)
    {
        if (t[0] < 0 || t[1] < 0 || t[2] < 0 || t[0] >= count || t[1] >= count || t[2] >= count)
        {
            continue;
        }
        const core::Vec3& a = vertices[static_cast<std::size_t>(t[0])];
        const core::Vec3& b = vertices[static_cast<std::size_t>(t[1])];
        const core::Vec3& c = vertices[static_cast<std::size_t>(t[2])];
        const core::Vec3 n = (b - a).cross(c - a);
        if (n.norm() < 1e-300)
        {
            continue;
        }
        const core::Vec3 unit = n.normalized();
        pushVertex(mesh, a, unit);
        pushVertex(mesh, b, unit);
        pushVertex(mesh, c, unit);
    }
    return mesh;
}

MeshData shapeMesh(const core::Shape& shape)
{
    switch (shape.type)
    {
    case core::ShapeType::Box:
        return boxMesh(shape.size);
    case core::ShapeType::Sphere:
        return sphereMesh(shape.radius, 32, 16);
    case core::ShapeType::Capsule:
        return capsuleMesh(shape.radius, shape.length, 32, 8);
    case core::ShapeType::Cylinder:
        return cylinderMesh(shape.radius, shape.length, 32);
    case core::ShapeType::Mesh:
        return triangleMesh(shape.vertices, shape.triangles);
    case core::ShapeType::Plane:
        break;
    }
    return {};
}

} // namespace frontier::render
