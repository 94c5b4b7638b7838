// tests/collision/test_models.h: small models built in code for the collision tests.
#pragma once

#include "collision/contacts.h"
#include "core/model.h"
#include "core/state.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace frontier::collision::test
{

using core::Quat;
using core::Vec3;

inline core::Shape box(double x, double y, double z)
{
    core::Shape s;
    s.type = core::ShapeType::Box;
    s.size = Vec3(x, y, z);
    return s;
}

inline core::Shape sphere(double r)
{
    core::Shape s;
    s.type = core::ShapeType::Sphere;
    s.radius = r;
    return s;
}

inline core::Shape capsule(double r, double length)
{
    core::Shape s;
    s.type = core::ShapeType::Capsule;
    s.radius = r;
    s.length = length;
    return s;
}

inline core::Shape cylinder(double r, double length)
{
    core::Shape s;
    s.type = core::ShapeType::Cylinder;
    s.radius = r;
    s.length = length;
    return s;
}

// A cube of the given side as 12 triangles (counter-clockwise seen from outside), centred.
inline core::Shape cubeMesh(double side)
{
    core::Shape s;
    s.type = core::ShapeType::Mesh;
    const double h = 0.5 * side;
    for (int k = 0; k < 8; ++k)
        s.vertices.emplace_back((k & 1) ? h : -h, (k & 2) ? h : -h, (k & 4) ? h : -h);
    s.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    return s;
}

// A closed prism of the given height along z over a simple polygon (counter-clockwise in the xy
// plane, a fan from its first corner must cover it), centred on z = 0.
inline core::Shape prismMesh(const std::vector<std::array<double, 2>>& polygon, double height)
{
    core::Shape s;
    s.type = core::ShapeType::Mesh;
    const int n = static_cast<int>(polygon.size());
    for (const double z : {-0.5 * height, 0.5 * height})
        for (const auto& [x, y] : polygon)
            s.vertices.emplace_back(x, y, z);
    for (int i = 1; i + 1 < n; ++i)
    {
        s.triangles.push_back({0, i + 1, i});         // bottom, seen from below
        s.triangles.push_back({n, n + i, n + i + 1}); // top
    }
    for (int i = 0; i < n; ++i)
    {
        const int j = (i + 1) % n;
        s.triangles.push_back({i, j, n + j});
        s.triangles.push_back({i, n + j, n + i});
    }
    return s;
}

// An L: the 2 x 2 square less its upper right quarter, times `unit` (m), `height` thick.
inline core::Shape lShapeMesh(double unit, double height)
{
    return prismMesh({{0, 0}, {2 * unit, 0}, {2 * unit, unit}, {unit, unit}, {unit, 2 * unit}, {0, 2 * unit}},
                     height);
}

// A closed, star-shaped and in general non-convex triangle mesh: a sphere of `rings` latitude
// bands and `segments` longitudes whose vertex radii vary in radius (1 +- jitter), pseudo-random
// from `seed` (the same every run).
inline core::Shape rockMesh(double radius, int rings, int segments, double jitter, unsigned seed)
{
    core::Shape s;
    s.type = core::ShapeType::Mesh;
    unsigned state = seed * 2654435761u + 1u;
    auto random = [&state]
    {
        state = state * 1664525u + 1013904223u; // a fixed LCG: portable and deterministic
        return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
    };
    auto point = [&](double theta, double phi)
    {
        const double r = radius * (1.0 + jitter * (2.0 * random() - 1.0));
        return Vec3(r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                    r * std::cos(theta));
    };
    const double pi = 3.14159265358979323846;
    s.vertices.push_back(point(0.0, 0.0)); // north pole, 0
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j)
            s.vertices.push_back(point(pi * i / rings, 2.0 * pi * j / segments));
    s.vertices.push_back(point(pi, 0.0)); // south pole
    const int south = static_cast<int>(s.vertices.size()) - 1;
    auto at = [segments](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
    for (int j = 0; j < segments; ++j)
    {
        s.triangles.push_back({0, at(1, j), at(1, j + 1)});
        for (int i = 1; i + 1 < rings; ++i)
        {
            s.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
            s.triangles.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
        }
        s.triangles.push_back({at(rings - 1, j), south, at(rings - 1, j + 1)});
    }
    return s;
}

inline core::Body moving(const std::string& name, const core::Shape& shape, const Vec3& position,
                         const Quat& orientation = Quat::Identity())
{
    core::Body b;
    b.name = name;
    b.mass = 1.0;
    b.inertia_B = core::Mat3::Identity();
    b.shapes.push_back(shape);
    b.position_W = position;
    b.orientation_WB = orientation;
    return b;
}

// A moving body of one mesh of the given density (kg/m^3), its mass properties from the mesh and
// its centre of mass at `centre` (the shape is placed so that the mesh keeps its shape frame).
inline core::Body movingMesh(const std::string& name, core::Shape mesh, const Vec3& centre,
                             double density = 1000.0, const Quat& orientation = Quat::Identity())
{
    const core::MassProperties props = core::shapeMassProperties(mesh, density);
    mesh.position_BS = -props.centre;
    core::Body b = moving(name, mesh, centre, orientation);
    b.mass = props.mass;
    b.inertia_B = props.inertia;
    return b;
}

inline core::Body fixed(const std::string& name, const core::Shape& shape, const Vec3& position,
                        const Quat& orientation = Quat::Identity())
{
    core::Body b = moving(name, shape, position, orientation);
    b.isStatic = true;
    b.mass = 0.0;
    return b;
}

// The ground: the solid half-space z <= 0.
inline core::Body floorBody()
{
    core::Shape s;
    s.type = core::ShapeType::Plane;
    s.normal = Vec3::UnitZ();
    s.offset = 0.0;
    core::Body b;
    b.name = "floor";
    b.isStatic = true;
    b.shapes.push_back(s);
    return b;
}

inline core::Joint ballJoint(int parent, int child, bool collideConnected = false)
{
    core::Joint j;
    j.name = "j" + std::to_string(parent) + "_" + std::to_string(child);
    j.parent = parent;
    j.child = child;
    j.collideConnected = collideConnected;
    return j;
}

inline std::vector<Contact> detectAll(const core::Model& model, double margin = 1e-3)
{
    ContactDetector detector(model, margin);
    std::vector<Contact> contacts;
    detector.detect(core::initialState(model), contacts);
    return contacts;
}

inline Quat rotation(double angle, const Vec3& axis)
{
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

} // namespace frontier::collision::test
