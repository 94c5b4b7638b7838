// tests/sim/urdf_trajectory_test.cpp: a URDF model and the same model written as YAML by hand
// give the same trajectory to round-off (tests/io checks that they load into the same Model; this
// checks what the simulator makes of them).
#include "sim_test_util.h"

#include <cmath>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::sim::test
{
namespace
{

// Three links hanging from the world: an arm on a continuous (revolute) shoulder, a slider on a
// prismatic joint along a slanted axis, and a tip welded to the slider. Every inertial origin is
// offset from its link origin; the tip's is also turned by 0.5 rad about z.
const char* const cUrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="world"/>
  <link name="upper">
    <inertial>
      <origin xyz="0.2 0 0"/>
      <mass value="1.5"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.031"/>
    </inertial>
  </link>
  <link name="slider">
    <inertial>
      <origin xyz="0 0 -0.05"/>
      <mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.0025"/>
    </inertial>
  </link>
  <link name="tip">
    <inertial>
      <origin xyz="0.05 0.02 0" rpy="0 0 0.5"/>
      <mass value="0.3"/>
      <inertia ixx="0.0004" ixy="0.00005" ixz="0" iyy="0.0006" iyz="0" izz="0.0008"/>
    </inertial>
  </link>
  <joint name="shoulder" type="continuous">
    <parent link="world"/>
    <child link="upper"/>
    <origin xyz="0 0 1.5"/>
    <axis xyz="0 1 0"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="upper"/>
    <child link="slider"/>
    <origin xyz="0.4 0 0"/>
    <axis xyz="1 0 1"/>
    <limit lower="-5" upper="5" effort="1" velocity="1"/>
  </joint>
  <joint name="weld" type="fixed">
    <parent link="slider"/>
    <child link="tip"/>
    <origin xyz="0.1 0 -0.1"/>
  </joint>
</robot>
)";

// The same model in YAML, worked out by hand at the initial pose (every joint at zero, every link
// frame parallel to the world):
//   upper link frame at the shoulder (0, 0, 1.5); centre of mass + (0.2, 0, 0) = (0.2, 0, 1.5).
//   slider link frame at (0.4, 0, 1.5); centre of mass + (0, 0, -0.05) = (0.4, 0, 1.45).
//   tip link frame at (0.4, 0, 1.5) + (0.1, 0, -0.1) = (0.5, 0, 1.4); centre of mass
//   + (0.05, 0.02, 0) = (0.55, 0.02, 1.4), axes turned 0.5 rad about z:
//   q = (cos 0.25, 0, 0, sin 0.25), the inertia given in those axes.
//   Anchors: each joint at its child link's origin; axes rotated into the world (unchanged).
// A .urdf loaded alone also gets the static floor plane, so the YAML has it too.
std::string yamlScene()
{
    std::ostringstream q;
    q.precision(17);
    q << "[" << std::cos(0.25) << ", 0, 0, " << std::sin(0.25) << "]";
    return R"(
bodies:
  - name: upper
    mass: 1.5
    inertia: [0.002, 0.03, 0.031]
    position: [0.2, 0, 1.5]
  - name: slider
    mass: 0.5
    inertia: [0.001, 0.002, 0.0025]
    position: [0.4, 0, 1.45]
  - name: tip
    mass: 0.3
    inertia: [0.0004, 0.0006, 0.0008, 0.00005, 0, 0]
    position: [0.55, 0.02, 1.4]
    orientation: )" +
           q.str() + R"(
  - name: floor
    static: true
    shape: {type: plane, normal: [0, 0, 1]}
joints:
  - {name: shoulder, type: revolute, parent: world, child: upper, anchor: [0, 0, 1.5], axis: [0, 1, 0]}
  - {name: slide, type: prismatic, parent: upper, child: slider, anchor: [0.4, 0, 1.5], axis: [1, 0, 1], limits: [-5, 5]}
  - {name: weld, type: fixed, parent: slider, child: tip, anchor: [0.5, 0, 1.4]}
)";
}

TEST(UrdfTrajectory, UrdfAndYamlFormsOfOneModelMoveAlike)
{
    const TestDir dir;
    const core::Model fromUrdf = io::loadScene(dir.write("arm.urdf", cUrdf));
    const core::Model fromYaml = io::loadSceneFromString(yamlScene(), (dir.path() / "arm.yaml").string());
    ASSERT_EQ(fromUrdf.bodies.size(), 4u);
    ASSERT_EQ(fromYaml.bodies.size(), 4u);
    ASSERT_EQ(fromUrdf.joints.size(), 3u);
    ASSERT_EQ(fromYaml.joints.size(), 3u);
    // Body i of the YAML model is body map[i] of the URDF model.
    std::vector<std::size_t> map;
    for (const core::Body& body : fromYaml.bodies)
    {
        const int index = fromUrdf.findBody(body.name);
        ASSERT_GE(index, 0) << body.name;
        map.push_back(static_cast<std::size_t>(index));
        const core::Body& other = fromUrdf.bodies[static_cast<std::size_t>(index)];
        ASSERT_EQ(other.isStatic, body.isStatic) << body.name;
        if (!body.isStatic)
        {
            EXPECT_LT((other.position_W - body.position_W).norm(), 1e-12) << body.name;
        }
    }

    core::Simulator urdfSim(fromUrdf);
    core::Simulator yamlSim(fromYaml);
    core::State a = core::initialState(fromUrdf);
    core::State b = core::initialState(fromYaml);
    double worst = 0.0;
    const long steps = stepsFor(1.0, fromYaml.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        urdfSim.step(a);
        yamlSim.step(b);
        core::State mapped = b;
        for (std::size_t i = 0; i < map.size(); ++i)
        {
            mapped.bodies[map[i]] = b.bodies[i];
        }
        worst = std::max(worst, stateDifference(a, mapped));
        ASSERT_LT(worst, 1e-9) << "at step " << a.step;
    }
    RecordProperty("max_state_difference", sci(worst));
    // The model moved: the arm swung down and the slider slid along it.
    const std::size_t slider = map[1];
    EXPECT_GT((a.bodies[map[0]].position_W - core::Vec3(0.2, 0, 1.5)).norm(), 0.1);
    const core::Vec3 along = (a.bodies[slider].position_W - a.bodies[map[0]].position_W);
    EXPECT_GT(std::abs(along.norm() - (core::Vec3(0.4, 0, 1.45) - core::Vec3(0.2, 0, 1.5)).norm()), 1e-3);
}

} // namespace
} // namespace frontier::sim::test
