// tests/collision/test_models.h: small models built in code for the collision tests.
#pragma once

#include "collision/contacts.h"
#include "core/model.h"
#include "core/state.h"

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
