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
// The URDF's fixed joint welds the tip into the slider; `weldedBySceneJoint` keeps them two bodies
// joined by a YAML fixed joint instead, `weldedByHand` writes the welded body out (below).
// A .urdf loaded alone also gets the static floor plane, so the YAML has it too.
std::string yamlScene(const std::string& sliderAndTip)
{
    return R"(
bodies:
  - name: upper
    mass: 1.5
    inertia: [0.002, 0.03, 0.031]
    position: [0.2, 0, 1.5]
)" + sliderAndTip +
           R"(
  - name: floor
    static: true
    shape: {type: plane, normal: [0, 0, 1]}
joints:
  - {name: shoulder, type: revolute, parent: world, child: upper, anchor: [0, 0, 1.5], axis: [0, 1, 0]}
  - {name: slide, type: prismatic, parent: upper, child: slider, anchor: [0.4, 0, 1.5], axis: [1, 0, 1], limits: [-5, 5]}
)";
}

std::string number(double value)
{
    std::ostringstream out;
    out.precision(17);
    out << value;
    return out.str();
}

std::string weldedBySceneJoint()
{
    return yamlScene(R"(  - name: slider
    mass: 0.5
    inertia: [0.001, 0.002, 0.0025]
    position: [0.4, 0, 1.45]
  - name: tip
    mass: 0.3
    inertia: [0.0004, 0.0006, 0.0008, 0.00005, 0, 0]
    position: [0.55, 0.02, 1.4]
    orientation: [)" +
                     number(std::cos(0.25)) + ", 0, 0, " + number(std::sin(0.25)) + R"(]
)") + "  - {name: weld, type: fixed, parent: slider, child: tip, anchor: [0.5, 0, 1.4]}\n";
}

// Slider and tip as one body by the parallel-axis theorem: mass 0.8 kg, centre of mass
// (0.5 (0.4, 0, 1.45) + 0.3 (0.55, 0.02, 1.4)) / 0.8, axes of the slider's inertial frame (the
// world's), the tip's inertia turned by Rz(0.5) into them.
std::string weldedByHand()
{
    const core::Vec3 c1(0.4, 0, 1.45), c2(0.55, 0.02, 1.4);
    const core::Vec3 com = (0.5 * c1 + 0.3 * c2) / 0.8;
    core::Mat3 tip;
    tip << 0.0004, 0.00005, 0, 0.00005, 0.0006, 0, 0, 0, 0.0008;
    const core::Mat3 R = Eigen::AngleAxisd(0.5, core::Vec3::UnitZ()).toRotationMatrix();
    auto shifted = [&](double m, const core::Vec3& c)
    {
        const core::Vec3 d = c - com;
        return core::Mat3(m * (d.squaredNorm() * core::Mat3::Identity() - d * d.transpose()));
    };
    const core::Mat3 I = core::Vec3(0.001, 0.002, 0.0025).asDiagonal().toDenseMatrix() + shifted(0.5, c1) +
                         R * tip * R.transpose() + shifted(0.3, c2);
    return yamlScene("  - name: slider\n    mass: 0.8\n    inertia: [" + number(I(0, 0)) + ", " +
                     number(I(1, 1)) + ", " + number(I(2, 2)) + ", " + number(I(0, 1)) + ", " +
                     number(I(0, 2)) + ", " + number(I(1, 2)) + "]\n    position: [" + number(com.x()) +
                     ", " + number(com.y()) + ", " + number(com.z()) + "]\n");
}

// Largest centre-of-mass distance between the URDF run and a YAML run over 1 s; the YAML body
// `slider` (and `tip`, when it is a body of its own) stand for the welded slider.
double largestDifference(const core::Model& fromUrdf, const core::Model& fromYaml, double limit)
{
    core::Simulator urdfSim(fromUrdf);
    core::Simulator yamlSim(fromYaml);
    core::State a = core::initialState(fromUrdf);
    core::State b = core::initialState(fromYaml);
    const std::size_t upperU = static_cast<std::size_t>(fromUrdf.findBody("upper"));
    const std::size_t sliderU = static_cast<std::size_t>(fromUrdf.findBody("slider"));
    const std::size_t upperY = static_cast<std::size_t>(fromYaml.findBody("upper"));
    const std::size_t sliderY = static_cast<std::size_t>(fromYaml.findBody("slider"));
    const int tipY = fromYaml.findBody("tip");
    double worst = 0.0;
    const long steps = stepsFor(1.0, fromYaml.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        urdfSim.step(a);
        yamlSim.step(b);
        core::Vec3 slider = b.bodies[sliderY].position_W;
        if (tipY >= 0)
        {
            slider = (0.5 * slider + 0.3 * b.bodies[static_cast<std::size_t>(tipY)].position_W) / 0.8;
        }
        worst = std::max({worst, (a.bodies[upperU].position_W - b.bodies[upperY].position_W).norm(),
                          (a.bodies[sliderU].position_W - slider).norm()});
        if (!(worst < limit))
        {
            ADD_FAILURE() << "difference " << worst << " m at step " << a.step;
            break;
        }
    }
    // The model moved: the arm swung down and the slider slid along it.
    EXPECT_GT((a.bodies[upperU].position_W - core::Vec3(0.2, 0, 1.5)).norm(), 0.1);
    return worst;
}

TEST(UrdfTrajectory, WeldedLinksMoveAsTheSameBodyWrittenByHand)
{
    const TestDir dir;
    const core::Model fromUrdf = io::loadScene(dir.write("arm.urdf", cUrdf));
    const core::Model fromYaml = io::loadSceneFromString(weldedByHand(), (dir.path() / "arm.yaml").string());
    ASSERT_EQ(fromUrdf.bodies.size(), 3u); // upper, slider (with the tip welded in), floor
    ASSERT_EQ(fromUrdf.joints.size(), 2u);
    const core::Body& u = fromUrdf.bodies[static_cast<std::size_t>(fromUrdf.findBody("slider"))];
    const core::Body& y = fromYaml.bodies[static_cast<std::size_t>(fromYaml.findBody("slider"))];
    EXPECT_LT((u.position_W - y.position_W).norm(), 1e-15);
    EXPECT_LT((u.inertia_B - y.inertia_B).norm(), 1e-17);
    const double worst = largestDifference(fromUrdf, fromYaml, 1e-9);
    RecordProperty("max_com_difference", sci(worst));
}

TEST(UrdfTrajectory, WeldingMovesLikeAFixedJoint)
{
    // A fixed joint holds its two bodies together to the drift tolerance (1e-10 m per step), so the
    // welded body and the jointed pair agree to that, not to round-off.
    const TestDir dir;
    const core::Model fromUrdf = io::loadScene(dir.write("arm.urdf", cUrdf));
    const core::Model fromYaml =
        io::loadSceneFromString(weldedBySceneJoint(), (dir.path() / "arm.yaml").string());
    ASSERT_EQ(fromYaml.bodies.size(), 4u);
    const double worst = largestDifference(fromUrdf, fromYaml, 1e-6);
    RecordProperty("max_com_difference", sci(worst));
}

} // namespace
} // namespace frontier::sim::test
