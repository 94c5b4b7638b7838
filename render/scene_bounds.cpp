// render/scene_bounds.cpp: world-space extents of the scene.
#include "render/scene_bounds.h"

#include <algorithm>
#include <iterator>

namespace frontier::render
{

core::Vec3 worldUp(const core::Model& model)
{
    const core::Vec3& g = model.simulation.gravity;
    return g.norm() > 1e-9 ? core::Vec3(-g.normalized()) : core::Vec3::UnitZ();
}

const std::vector<core::Shape>& drawnShapes(const core::Body& body)
{
    return body.visuals.empty() ? body.shapes : body.visuals;
}

namespace
{
// The shape's own bounding box corners in the world; false for planes and empty meshes.
bool shapeCorners(const core::Shape& shape, const core::BodyState& pose, core::Vec3 (&corners)[8])
{
    core::Vec3 lo = core::Vec3::Zero();
    core::Vec3 hi = core::Vec3::Zero();
    switch (shape.type)
    {
    case core::ShapeType::Box:
        hi = 0.5 * shape.size.cwiseAbs();
        lo = -hi;
        break;
    case core::ShapeType::Sphere:
        hi = core::Vec3::Constant(shape.radius);
        lo = -hi;
        break;
    case core::ShapeType::Capsule:
        hi = core::Vec3(shape.radius, shape.radius, 0.5 * shape.length + shape.radius);
        lo = -hi;
        break;
    case core::ShapeType::Cylinder:
        hi = core::Vec3(shape.radius, shape.radius, 0.5 * shape.length);
        lo = -hi;
        break;
    case core::ShapeType::Mesh:
        if (shape.vertices.empty())
        {
            return false;
        }
        lo = hi = shape.vertices.front();
        for (const core::Vec3& v : shape.vertices)
        {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        break;
    case core::ShapeType::Plane:
        return false;
    }
    const core::Quat q = pose.orientation_WB * shape.rotation_BS;
    const core::Vec3 origin = pose.position_W + pose.orientation_WB * shape.position_BS;
    for (int i = 0; i < 8; ++i)
    {
        const core::Vec3 corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                                (i & 4) ? hi.z() : lo.z());
        corners[i] = origin + q * corner;
    }
    return true;
}
} // namespace

Bounds shapeBounds(const core::Shape& shape, const core::BodyState& pose)
{
    core::Vec3 corners[8];
    Bounds b;
    if (shapeCorners(shape, pose, corners))
    {
        for (const core::Vec3& c : corners)
        {
            b.add(c);
        }
    }
    return b;
}

void addShapeCorners(const core::Model& model, const core::State& state, bool movingOnly,
                     std::vector<core::Vec3>& points)
{
    const std::size_t n = std::min(model.bodies.size(), state.bodies.size());
    for (std::size_t i = 0; i < n; ++i)
    {
        if (movingOnly && model.bodies[i].isStatic)
        {
            continue;
        }
        for (const core::Shape& shape : drawnShapes(model.bodies[i]))
        {
            core::Vec3 corners[8];
            if (shapeCorners(shape, state.bodies[i], corners))
            {
                points.insert(points.end(), std::begin(corners), std::end(corners));
            }
        }
    }
}

Bounds bodyBounds(const core::Model& model, const core::State& state, bool movingOnly)
{
    Bounds b;
    const std::size_t n = std::min(model.bodies.size(), state.bodies.size());
    for (std::size_t i = 0; i < n; ++i)
    {
        const core::Body& body = model.bodies[i];
        if (movingOnly && body.isStatic)
        {
            continue;
        }
        for (const core::Shape& shape : drawnShapes(body))
        {
            b.add(shapeBounds(shape, state.bodies[i]));
        }
    }
    return b;
}

Bounds withGround(const Bounds& box, const core::Model& model)
{
    if (!box.valid())
    {
        return box;
    }
    const core::Vec3 up = worldUp(model);
    Bounds out = box;
    for (const core::Body& body : model.bodies)
    {
        for (const core::Shape& shape : drawnShapes(body))
        {
            if (shape.type != core::ShapeType::Plane)
            {
                continue;
            }
            const core::Vec3 n = shape.normal.normalized();
            const double facing = n.dot(up);
            if (facing < 0.5)
            {
                continue; // a wall or a ceiling: nothing lands on it
            }
            for (int i = 0; i < 8; ++i)
            {
                const core::Vec3 c((i & 1) ? box.hi.x() : box.lo.x(), (i & 2) ? box.hi.y() : box.lo.y(),
                                   (i & 4) ? box.hi.z() : box.lo.z());
                const double height = n.dot(c) - shape.offset;
                if (height < 0.0)
                {
                    continue;
                }
                // Drop the corner along -up onto the plane.
                out.add(c - (height / facing) * up);
            }
        }
    }
    return out;
}

} // namespace frontier::render
