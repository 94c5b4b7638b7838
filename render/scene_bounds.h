// render/scene_bounds.h: world-space extents of the scene, used to place the camera, the floor
// and the shadow map.
#pragma once

#include "core/model.h"
#include "core/state.h"

namespace frontier::render
{

struct Bounds
{
    core::Vec3 lo = core::Vec3::Constant(1e300);
    core::Vec3 hi = core::Vec3::Constant(-1e300);

    bool valid() const { return lo.x() <= hi.x(); }
    void add(const core::Vec3& p)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    void add(const Bounds& b)
    {
        if (b.valid())
        {
            add(b.lo);
            add(b.hi);
        }
    }
    core::Vec3 centre() const { return 0.5 * (lo + hi); }
    double radius() const { return 0.5 * (hi - lo).norm(); }
};

// Unit "up" of the world: against gravity, or +z without gravity.
core::Vec3 worldUp(const core::Model& model);

// What the renderer draws for a body: its render-only visuals, or its collision shapes when it
// has none. Everything in render/ (meshes, floors, bounds) goes through this.
const std::vector<core::Shape>& drawnShapes(const core::Body& body);

// Axis-aligned world bounds of one non-plane shape of a body in the given pose (conservative).
Bounds shapeBounds(const core::Shape& shape, const core::BodyState& pose);

// Appends the eight corners of the oriented bounding box of every drawn non-plane shape of the
// moving bodies (of all bodies when `movingOnly` is false) in this state to `points`.
void addShapeCorners(const core::Model& model, const core::State& state, bool movingOnly,
                     std::vector<core::Vec3>& points);

// Bounds of all drawn non-plane shapes of the moving bodies (or of all bodies when `movingOnly` is
// false).
Bounds bodyBounds(const core::Model& model, const core::State& state, bool movingOnly);

// `box` grown by its projection onto every drawn plane shape that faces up and lies below it, so a
// camera framing the result also sees where falling bodies will land.
Bounds withGround(const Bounds& box, const core::Model& model);

} // namespace frontier::render
