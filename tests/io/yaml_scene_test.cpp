// tests/io/yaml_scene_test.cpp: what a valid YAML scene turns into.
#include "io/scene.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

const char* const cFullScene = R"(
name: two links
simulation: {dt: 0.002, duration: 3.5, gravity: [0, 0, -1.62], solver: pgs, pgs_iterations: 40, integrator: rattle}
contact:
  friction: 0.8
  restitution: 0.25
  tolerance: 1.0e-4
  relative_tolerance: 0.01
  ignore: [[upper, lower]]
camera: {position: [4, -4, 2], look_at: [0, 0, 1], fov: 60}
bodies:
  - name: floor
    static: true
    position: [5, 0, 0]
    orientation: [0.9, 0.1, 0.2, 0.3]
    shape: {type: plane, normal: [0, 0, 2], offset: -0.5}
  - name: upper
    shape: {type: box, size: [0.1, 0.1, 0.5]}
    mass: 2
    position: [0, 0, 1.75]
    velocity: [1, 0, 0]
    angular_velocity: [0, 0.5, 0]
    color: [1, 0, 0]
    group: arm
  - name: lower
    shape: {type: capsule, radius: 0.05, length: 0.4}
    density: 500
    position: [0, 0, 1.25]
    orientation: [2, 0, 0, 0]
    group: arm
joints:
  - {name: shoulder, type: revolute, parent: floor, child: upper, anchor: [0, 0, 2], axis: [0, 3, 0], limits: [-1.5, 0.5], damping: 0.3, friction: 0.05}
  - {name: elbow, type: ball, parent: upper, child: lower, anchor: [0, 0, 1.5], collide: true}
  - {name: weld, type: fixed, parent: world, child: lower}
)";

TEST(YamlScene, EverySectionIsRead)
{
    const core::Model model = loadSceneFromString(text(cFullScene), "dir/two.yaml");
    EXPECT_EQ(model.name, "two links");
    EXPECT_EQ(model.sourceFile, "dir/two.yaml");
    EXPECT_EQ(model.simulation.dt, 0.002);
    EXPECT_EQ(model.simulation.duration, 3.5);
    EXPECT_EQ(model.simulation.gravity, core::Vec3(0, 0, -1.62));
    EXPECT_EQ(model.simulation.solver, core::SolverKind::Pgs);
    EXPECT_EQ(model.simulation.pgsIterations, 40);
    EXPECT_EQ(model.simulation.integrator, core::IntegratorKind::Rattle);
    EXPECT_EQ(model.contact.friction, 0.8);
    EXPECT_EQ(model.contact.restitution, 0.25);
    EXPECT_EQ(model.contact.tolerance, 1e-4);
    EXPECT_EQ(model.contact.relativeTolerance, 0.01);
    ASSERT_EQ(model.contact.ignore.size(), 1u);
    EXPECT_EQ(model.contact.ignore[0], (std::array<int, 2>{1, 2}));
    EXPECT_FALSE(model.camera.automatic);
    EXPECT_EQ(model.camera.position, core::Vec3(4, -4, 2));
    EXPECT_EQ(model.camera.lookAt, core::Vec3(0, 0, 1));
    EXPECT_EQ(model.camera.fovDegrees, 60.0);

    ASSERT_EQ(model.bodies.size(), 3u);
    const core::Body& floor = model.bodies[0];
    EXPECT_TRUE(floor.isStatic);
    EXPECT_EQ(floor.mass, 0.0);
    const core::Shape& plane = floor.shapes.at(0);
    EXPECT_EQ(plane.normal, core::Vec3(0, 0, 1)); // normalised, world frame
    EXPECT_EQ(plane.offset, -0.5);
    // The plane's frame is the world frame whatever the body pose.
    const core::Quat worldRotation = floor.orientation_WB * plane.rotation_BS;
    const core::Vec3 worldOrigin = floor.position_W + floor.orientation_WB * plane.position_BS;
    EXPECT_LT(worldRotation.angularDistance(core::Quat::Identity()), 1e-12);
    EXPECT_LT(worldOrigin.norm(), 1e-12);

    const core::Body& upper = model.bodies[1];
    EXPECT_EQ(upper.mass, 2.0);
    EXPECT_EQ(upper.position_W, core::Vec3(0, 0, 1.75));
    EXPECT_EQ(upper.velocity_W, core::Vec3(1, 0, 0));
    EXPECT_EQ(upper.angularVelocity_W, core::Vec3(0, 0.5, 0));
    EXPECT_EQ(upper.color, core::Vec3(1, 0, 0));
    EXPECT_EQ(upper.group, "arm");

    const core::Body& lower = model.bodies[2];
    EXPECT_EQ(lower.orientation_WB.coeffs(), core::Quat::Identity().coeffs()); // [2,0,0,0] normalised
    EXPECT_EQ(lower.shapes.at(0).type, core::ShapeType::Capsule);
    EXPECT_EQ(lower.shapes.at(0).position_BS, core::Vec3::Zero());

    ASSERT_EQ(model.joints.size(), 3u);
    const core::Joint& shoulder = model.joints[0];
    EXPECT_EQ(shoulder.type, core::JointType::Revolute);
    EXPECT_EQ(shoulder.parent, 0); // a static parent keeps its index
    EXPECT_EQ(shoulder.child, 1);
    EXPECT_LT((shoulder.anchorChild - core::Vec3(0, 0, 0.25)).norm(), 1e-15);
    EXPECT_LT((upper.orientation_WB * shoulder.axisChild - core::Vec3(0, 1, 0)).norm(), 1e-15);
    ASSERT_TRUE(shoulder.limits.has_value());
    EXPECT_EQ(*shoulder.limits, (std::array<double, 2>{-1.5, 0.5}));
    EXPECT_EQ(shoulder.damping, 0.3);
    EXPECT_EQ(shoulder.friction, 0.05);
    EXPECT_FALSE(shoulder.collideConnected);

    const core::Joint& elbow = model.joints[1];
    EXPECT_EQ(elbow.type, core::JointType::Ball);
    EXPECT_EQ(elbow.damping, 0.0);
    EXPECT_EQ(elbow.friction, 0.0);
    EXPECT_TRUE(elbow.collideConnected);
    EXPECT_LT((elbow.anchorParent - core::Vec3(0, 0, -0.25)).norm(), 1e-15);
    EXPECT_LT((elbow.anchorChild - core::Vec3(0, 0, 0.25)).norm(), 1e-15);

    const core::Joint& weld = model.joints[2];
    EXPECT_EQ(weld.parent, core::cWorld);
    EXPECT_LT(weld.anchorChild.norm(), 1e-15); // default anchor: the child's centre of mass
}

TEST(YamlScene, DefaultsWhenSectionsAreAbsent)
{
    const core::Model model =
        loadSceneFromString("bodies: [{name: b, shape: {type: sphere, radius: 1}}]\n", "some/dir/ball.yaml");
    const core::SimulationSettings defaults;
    EXPECT_EQ(model.name, "ball");
    EXPECT_EQ(model.simulation.dt, defaults.dt);
    EXPECT_EQ(model.simulation.solver, core::SolverKind::Linear);
    EXPECT_TRUE(model.camera.automatic);
    EXPECT_EQ(model.bodies[0].position_W, core::Vec3::Zero());
    EXPECT_FALSE(model.bodies[0].color.has_value());
}

TEST(YamlScene, NailToStaticBodyAndAngleJoint)
{
    const core::Model model = loadSceneFromString(text(R"(
bodies:
  - {name: post, static: true, shape: {type: box, size: [0.1, 0.1, 1]}, position: [0, 0, 0.5]}
  - {name: a, shape: {type: sphere, radius: 0.1}, position: [0, 0, 1.2]}
  - {name: b, shape: {type: sphere, radius: 0.1}, position: [0, 0, 1.4]}
joints:
  - {name: pin, type: nail, parent: post, child: a, anchor: [0, 0, 1]}
  - {name: cardan, type: angle, parent: a, child: b, anchor: [0, 0, 1.3], axis: [0, 0, 1]}
)"),
                                                  "s.yaml");
    ASSERT_EQ(model.joints.size(), 2u);
    EXPECT_EQ(model.joints[0].type, core::JointType::Nail);
    EXPECT_EQ(model.joints[0].parent, 0);
    EXPECT_LT((model.joints[0].anchorParent - core::Vec3(0, 0, 0.5)).norm(), 1e-15);
    EXPECT_EQ(model.joints[1].type, core::JointType::Angle);
}

TEST(YamlScene, FlowAndBlockStylesAreEquivalent)
{
    const core::Model flow = loadSceneFromString(
        "bodies: [{name: b, mass: 2, shape: {type: box, size: [1, 2, 3]}, position: [1, 2, 3]}]\n", "s.yaml");
    const core::Model block = loadSceneFromString(text(R"(
bodies:
  - name: b
    mass: 2
    shape:
      type: box
      size:
        - 1
        - 2
        - 3
    position: [1, 2, 3]
)"),
                                                  "s.yaml");
    EXPECT_EQ(flow.bodies[0].inertia_B, block.bodies[0].inertia_B);
    EXPECT_EQ(flow.bodies[0].position_W, block.bodies[0].position_W);
}

} // namespace
} // namespace frontier::io::test
