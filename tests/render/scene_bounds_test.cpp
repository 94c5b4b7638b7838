// tests/render/scene_bounds_test.cpp: the extents the camera frames are those of what is drawn.
#include "render/scene_bounds.h"

#include <gtest/gtest.h>

namespace frontier::render
{
namespace
{

core::Shape boxShape(const core::Vec3& size, const core::Vec3& position_BS)
{
    core::Shape s;
    s.type = core::ShapeType::Box;
    s.size = size;
    s.position_BS = position_BS;
    return s;
}

core::Model bodyWithCollisionBox()
{
    core::Model model;
    core::Body body;
    body.name = "b";
    body.mass = 1.0;
    body.inertia_B = core::Mat3::Identity();
    body.position_W = core::Vec3(1.0, 2.0, 3.0);
    body.shapes.push_back(boxShape(core::Vec3(0.2, 0.2, 0.2), core::Vec3::Zero()));
    model.bodies.push_back(body);
    return model;
}

TEST(SceneBounds, CollisionShapesWhenThereAreNoVisuals)
{
    const core::Model model = bodyWithCollisionBox();
    const Bounds b = bodyBounds(model, core::initialState(model), true);
    EXPECT_TRUE(b.lo.isApprox(core::Vec3(0.9, 1.9, 2.9), 1e-12)) << b.lo.transpose();
    EXPECT_TRUE(b.hi.isApprox(core::Vec3(1.1, 2.1, 3.1), 1e-12)) << b.hi.transpose();
}

TEST(SceneBounds, VisualsReplaceTheCollisionShapes)
{
    core::Model model = bodyWithCollisionBox();
    // Two visuals: a 1 m cube 2 m along x from the body origin, and a 0.1 m one at the origin.
    model.bodies[0].visuals.push_back(boxShape(core::Vec3(1.0, 1.0, 1.0), core::Vec3(2.0, 0.0, 0.0)));
    model.bodies[0].visuals.push_back(boxShape(core::Vec3(0.1, 0.1, 0.1), core::Vec3::Zero()));
    const Bounds b = bodyBounds(model, core::initialState(model), true);
    EXPECT_TRUE(b.lo.isApprox(core::Vec3(0.95, 1.5, 2.5), 1e-12)) << b.lo.transpose();
    EXPECT_TRUE(b.hi.isApprox(core::Vec3(3.5, 2.5, 3.5), 1e-12)) << b.hi.transpose();
    EXPECT_EQ(&drawnShapes(model.bodies[0]), &model.bodies[0].visuals);
}

} // namespace
} // namespace frontier::render
