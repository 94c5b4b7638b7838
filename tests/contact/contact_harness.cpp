// tests/contact/contact_harness.cpp: independent measurements for the contact tests.
#include "contact_harness.h"

#include <cmath>

namespace frontier::test
{

namespace
{
using core::Shape;
using core::ShapeType;
using core::Vec3;

// Smallest signed distance n . x - offset over the shape (m); negative inside the half-space.
double lowestAbovePlane(const Shape& shape, const core::BodyState& body, const Vec3& n, double offset)
{
    const core::Quat R = body.orientation_WB * shape.rotation_BS;
    const Vec3 c = body.position_W + body.orientation_WB * shape.position_BS;
    const double h = n.dot(c) - offset;
    switch (shape.type)
    {
    case ShapeType::Box:
    {
        double lowest = h;
        for (int k = 0; k < 3; ++k)
        {
            lowest -= 0.5 * shape.size(k) * std::abs(n.dot(R * Vec3::Unit(k)));
        }
        return lowest;
    }
    case ShapeType::Sphere:
        return h - shape.radius;
    case ShapeType::Capsule:
        return h - 0.5 * shape.length * std::abs(n.dot(R * Vec3::UnitZ())) - shape.radius;
    case ShapeType::Cylinder:
    {
        const double a = n.dot(R * Vec3::UnitZ());
        return h - 0.5 * shape.length * std::abs(a) - shape.radius * std::sqrt(std::max(0.0, 1.0 - a * a));
    }
    case ShapeType::Mesh:
    {
        double lowest = std::numeric_limits<double>::infinity();
        for (const Vec3& v : shape.vertices)
        {
            lowest = std::min(lowest, n.dot(c + R * v) - offset);
        }
        return lowest;
    }
    case ShapeType::Plane:
        break;
    }
    return std::numeric_limits<double>::infinity();
}

double boundingRadius(const core::Body& body)
{
    double r = 0.0;
    for (const Shape& s : body.shapes)
    {
        double extent = 0.0;
        switch (s.type)
        {
        case ShapeType::Box:
            extent = 0.5 * s.size.norm();
            break;
        case ShapeType::Sphere:
            extent = s.radius;
            break;
        case ShapeType::Capsule:
            extent = 0.5 * s.length + s.radius;
            break;
        case ShapeType::Cylinder:
            extent = std::hypot(0.5 * s.length, s.radius);
            break;
        case ShapeType::Mesh:
            for (const Vec3& v : s.vertices)
            {
                extent = std::max(extent, v.norm());
            }
            break;
        case ShapeType::Plane:
            break;
        }
        r = std::max(r, s.position_BS.norm() + extent);
    }
    return r;
}
} // namespace

double planePenetration(const core::Model& model, const core::State& state)
{
    double deepest = 0.0;
    for (const core::Body& floor : model.bodies)
    {
        if (!floor.isStatic)
        {
            continue;
        }
        for (const Shape& plane : floor.shapes)
        {
            if (plane.type != ShapeType::Plane)
            {
                continue;
            }
            for (std::size_t i = 0; i < model.bodies.size(); ++i)
            {
                if (model.bodies[i].isStatic)
                {
                    continue;
                }
                for (const Shape& shape : model.bodies[i].shapes)
                {
                    deepest = std::max(deepest,
                                       -lowestAbovePlane(shape, state.bodies[i], plane.normal, plane.offset));
                }
            }
        }
    }
    return deepest;
}

double maxPointSpeed(const core::Model& model, const core::State& state)
{
    double fastest = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            const core::BodyState& s = state.bodies[i];
            fastest = std::max(fastest, s.velocity_W.norm() +
                                            s.angularVelocity_W.norm() * boundingRadius(model.bodies[i]));
        }
    }
    return fastest;
}

double maxLinearSpeed(const core::Model& model, const core::State& state)
{
    double fastest = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            fastest = std::max(fastest, state.bodies[i].velocity_W.norm());
        }
    }
    return fastest;
}

double maxAngularSpeed(const core::Model& model, const core::State& state)
{
    double fastest = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            fastest = std::max(fastest, state.bodies[i].angularVelocity_W.norm());
        }
    }
    return fastest;
}

bool allFinite(const core::State& state)
{
    for (const core::BodyState& s : state.bodies)
    {
        if (!s.position_W.allFinite() || !s.orientation_WB.coeffs().allFinite() ||
            !s.velocity_W.allFinite() || !s.angularVelocity_W.allFinite())
        {
            return false;
        }
    }
    return true;
}

} // namespace frontier::test
