// tests/io/urdf_test.cpp: URDF models: errors with URDF line numbers, the link/inertial/joint
// mapping, and equality with the equivalent YAML scene.
#include "io/scene.h"
#include "io_test_util.h"

#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <numbers>
#include <sys/stat.h>

namespace frontier::io::test
{
namespace
{

// Three links: a floating base, an upper arm on a revolute joint, a lower arm on a prismatic
// joint whose origin is turned 90 degrees about z. Inertial frames are offset (and turned, for
// the upper arm), so the centre of mass is not the link origin.
const char* const cArmUrdf = R"(
<?xml version="1.0"?>
<robot name="arm">
  <material name="grey"><color rgba="0.5 0.25 0.75 1"/></material>
  <link name="base">
    <inertial>
      <origin xyz="0 0 0.05"/>
      <mass value="2"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/>
    </inertial>
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry><material name="grey"/></visual>
  </link>
  <link name="upper">
    <inertial>
      <origin xyz="0 0 0.2" rpy="0 0 1.5707963267948966"/>
      <mass value="1"/>
      <inertia ixx="0.01" ixy="0.001" ixz="0" iyy="0.012" iyz="0" izz="0.003"/>
    </inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.03" length="0.4"/></geometry></collision>
  </link>
  <link name="lower">
    <inertial>
      <origin xyz="0.15 0 0"/>
      <mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.004" iyz="0" izz="0.004"/>
    </inertial>
    <collision><origin xyz="0.15 0 0" rpy="0 1.5707963267948966 0"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <joint name="elbow" type="prismatic">
    <parent link="upper"/>
    <child link="lower"/>
    <origin xyz="0 0 0.4" rpy="0 0 1.5707963267948966"/>
    <axis xyz="2 0 0"/>
    <limit lower="0" upper="0.1" effort="10" velocity="1"/>
  </joint>
</robot>
)";

// The same model written as a YAML scene, placed like `models: [{urdf: arm.urdf, position:
// [0, 0, 1], prefix: a_}]`, worked out by hand.
const char* const cArmYaml = R"(
bodies:
  - name: a_base
    mass: 2
    inertia: [0.02, 0.03, 0.04]
    position: [0, 0, 1.05]
    color: [0.5, 0.25, 0.75]
    shape: {type: box, size: [0.2, 0.2, 0.1]}
  - name: a_upper
    mass: 1
    inertia: [0.01, 0.012, 0.003, 0.001, 0, 0]
    position: [0, 0, 1.3]
    orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]
    shape: {type: cylinder, radius: 0.03, length: 0.4, orientation: [0.7071067811865476, 0, 0, -0.7071067811865476]}
  - name: a_lower
    mass: 0.5
    inertia: [0.001, 0.004, 0.004]
    position: [0, 0.15, 1.5]
    orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]
    shape: {type: sphere, radius: 0.05, orientation: [0.7071067811865476, 0, 0.7071067811865476, 0]}
joints:
  - {name: a_shoulder, type: revolute, parent: a_base, child: a_upper, anchor: [0, 0, 1.1], axis: [0, 1, 0], limits: [-1, 1]}
  - {name: a_elbow, type: prismatic, parent: a_upper, child: a_lower, anchor: [0, 0, 1.5], axis: [0, 1, 0], limits: [0, 0.1]}
)";

constexpr double cTol = 1e-12;

void expectNear(const core::Vec3& a, const core::Vec3& b, const std::string& what)
{
    EXPECT_LT((a - b).norm(), cTol) << what << ": " << a.transpose() << " vs " << b.transpose();
}

void expectSameRotation(const core::Quat& a, const core::Quat& b, const std::string& what)
{
    EXPECT_LT(std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm()), cTol) << what;
}

InputError urdfError(const TempDir& dir, const std::string& urdf)
{
    const std::string path = dir.write("robot.urdf", urdf);
    return captureInputError([&] { loadScene(path); });
}

// A one-link robot with the given body inside <robot>; `link` starts at line 2.
std::string robot(const std::string& inner)
{
    return "<robot name=\"r\">\n" + inner + "</robot>\n";
}

const std::string cGoodInertial = "<inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" "
                                  "iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>";

TEST(Urdf, MasslessLinkMovedByAJointNamesTheJointLine)
{
    TempDir dir;
    const InputError e = urdfError(dir, robot("  <link name=\"a\">\n    " + cGoodInertial + "\n  </link>\n" +
                                              "  <link name=\"b\"/>\n" +
                                              "  <joint name=\"j\" type=\"continuous\">\n"
                                              "    <parent link=\"a\"/><child link=\"b\"/>\n  </joint>\n"));
    EXPECT_INPUT_ERROR_AT(
        e, dir.file("robot.urdf"), 6, 3,
        "link 'b' has no mass (no <inertial> with a positive mass) but continuous joint 'j' "
        "moves it");
}

TEST(Urdf, MassThatIsNotANumberIsFatal)
{
    TempDir dir;
    // urdfdom logs an error and keeps the link with mass 0: we stop at the <mass> line.
    const InputError e =
        urdfError(dir, robot("  <link name=\"a\">\n    <inertial>\n      <mass value=\"heavy\"/>\n"
                             "      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" "
                             "izz=\"1\"/>\n    </inertial>\n  </link>\n"));
    EXPECT_EQ(e.file(), dir.file("robot.urdf"));
    EXPECT_EQ(e.line(), 4) << e.what();
    EXPECT_NE(std::string(e.what()).find("mass [heavy] is not a float"), std::string::npos) << e.what();
}

TEST(Urdf, MasslessFreeRootIsAnErrorThatSuggestsFixedBase)
{
    TempDir dir;
    const InputError e =
        urdfError(dir, robot("  <link name=\"a\">\n    <inertial>\n      <mass value=\"0\"/>\n"
                             "      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" "
                             "izz=\"1\"/>\n    </inertial>\n  </link>\n"));
    EXPECT_INPUT_ERROR_AT(e, dir.file("robot.urdf"), 2, 3, "link 'a' has no mass");
    EXPECT_NE(std::string(e.what()).find("floats freely"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--fixed-base"), std::string::npos) << e.what();
}

TEST(Urdf, NegativeMassIsAnError)
{
    TempDir dir;
    const InputError e =
        urdfError(dir, robot("  <link name=\"a\">\n    <inertial>\n      <mass value=\"-2\"/>\n"
                             "      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" "
                             "izz=\"1\"/>\n    </inertial>\n  </link>\n"));
    EXPECT_INPUT_ERROR_AT(e, dir.file("robot.urdf"), 4, 7,
                          "link 'a' has mass -2; expected a non-negative <mass value> (kg)");
}

TEST(Urdf, ImpossibleInertiaIsReplacedByThatOfTheShapesWithAWarning)
{
    TempDir dir;
    // izz = 0: not positive-definite. The link's collision box (0.2 x 0.4 x 0.6 m) at its mass 3 kg
    // gives m/12 (b^2 + c^2), ... about the box centre.
    const std::string path = dir.write(
        "robot.urdf", robot("  <link name=\"a\">\n    <inertial>\n      <mass value=\"3\"/>\n"
                            "      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"0\"/>\n"
                            "    </inertial>\n    <collision><geometry><box size=\"0.2 0.4 0.6\"/></geometry>"
                            "</collision>\n  </link>\n"));
    LoadReport report;
    const core::Model model = loadScene(path, {}, &report);
    const core::Body& body = model.bodies.at(0);
    EXPECT_DOUBLE_EQ(body.mass, 3.0);
    const core::Vec3 expected = 3.0 / 12.0 * core::Vec3(0.16 + 0.36, 0.04 + 0.36, 0.04 + 0.16);
    EXPECT_LT((body.inertia_B.diagonal() - expected).norm(), 1e-12) << body.inertia_B;
    EXPECT_LT((body.inertia_B - core::Mat3(body.inertia_B.diagonal().asDiagonal())).norm(), 1e-15);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find(dir.file("robot.urdf") +
                                      ":5:7: warning: link 'a': the inertia is not positive-definite"),
              std::string::npos)
        << report.warnings[0];
    ASSERT_EQ(report.robots.size(), 1u);
    ASSERT_EQ(report.robots[0].repaired.size(), 1u);
    EXPECT_NE(report.robots[0].repaired[0].find("link 'a'"), std::string::npos);
}

TEST(Urdf, TinyOrTriangleBreakingInertiaIsRepairedEvenWithoutShapes)
{
    TempDir dir;
    // No shapes at all: a ball of water (1000 kg/m^3) of the link's mass, I = 2/5 m r^2.
    for (const char* inertia : {"ixx=\"1e-12\" ixy=\"0\" ixz=\"0\" iyy=\"1e-12\" iyz=\"0\" izz=\"1e-12\"",
                                "ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"3\""})
    {
        SCOPED_TRACE(inertia);
        const std::string path = dir.write(
            "robot.urdf", robot(std::string("  <link name=\"a\"><inertial><mass value=\"0.5\"/><inertia ") +
                                inertia + "/></inertial></link>\n"));
        LoadReport report;
        const core::Model model = loadScene(path, {}, &report);
        const double r = std::cbrt(3.0 * 0.5 / (4.0 * std::numbers::pi * 1000.0));
        EXPECT_LT((model.bodies.at(0).inertia_B - 0.4 * 0.5 * r * r * core::Mat3::Identity()).norm(), 1e-15);
        // One warning for the inertia, one that nothing holds the robot up (it has no shapes).
        ASSERT_EQ(report.warnings.size(), 2u);
        EXPECT_NE(report.warnings[0].find("link 'a': the inertia "), std::string::npos) << report.warnings[0];
        EXPECT_NE(report.warnings[1].find("no collision shapes"), std::string::npos) << report.warnings[1];
    }
}

TEST(Urdf, MissingParentLink)
{
    TempDir dir;
    const InputError e =
        urdfError(dir, robot("  <link name=\"a\">" + cGoodInertial + "</link>\n" +
                             "  <joint name=\"j\" type=\"fixed\">\n"
                             "    <parent link=\"nope\"/>\n    <child link=\"a\"/>\n  </joint>\n"));
    EXPECT_EQ(e.file(), dir.file("robot.urdf"));
    EXPECT_EQ(e.line(), 4) << e.what();
    EXPECT_NE(std::string(e.what()).find("parent link [nope] of joint [j] not found"), std::string::npos)
        << e.what();
}

// A planar joint moves its child in the plane normal to its axis (docs/method.md §2): anchored at
// the child link's origin, the axis rotated into the world; it takes no limits and no dynamics.
TEST(Urdf, PlanarJointMovesTheChildInThePlaneNormalToItsAxis)
{
    TempDir dir;
    const std::string path =
        dir.write("robot.urdf",
                  robot("  <link name=\"a\">" + cGoodInertial + "</link>\n" + "  <link name=\"b\">" +
                        cGoodInertial + "</link>\n" +
                        "  <joint name=\"slide\" type=\"planar\">\n"
                        "    <parent link=\"a\"/><child link=\"b\"/>\n"
                        "    <origin xyz=\"1 0 0\" rpy=\"1.5707963267948966 0 0\"/><axis xyz=\"0 0 1\"/>\n"
                        "    <limit lower=\"-1\" upper=\"1\" effort=\"5\" velocity=\"1\"/>\n"
                        "    <dynamics damping=\"0.5\"/>\n  </joint>\n"));
    LoadReport report;
    const core::Model model = loadScene(path, {}, &report);
    ASSERT_EQ(model.joints.size(), 1u);
    const core::Joint& joint = model.joints[0];
    EXPECT_EQ(joint.type, core::JointType::Planar);
    EXPECT_EQ(core::jointRowCount(joint.type), 3);
    EXPECT_FALSE(joint.limits);
    EXPECT_EQ(joint.damping, 0.0) << "a planar joint's <dynamics> is ignored";
    EXPECT_TRUE(std::isinf(joint.effortLimit)) << "nor does its <limit effort> bound anything";
    // (and the robot has no collision shapes: a third warning)
    ASSERT_EQ(report.warnings.size(), 3u);
    EXPECT_NE(
        report.warnings[0].find("robot.urdf:7:5: warning: joint 'slide': <limit> of a planar joint is not "
                                "supported and is ignored"),
        std::string::npos)
        << report.warnings[0];
    EXPECT_NE(
        report.warnings[1].find("robot.urdf:8:5: warning: joint 'slide': <dynamics> of a planar joint is not "
                                "supported and is ignored"),
        std::string::npos)
        << report.warnings[1];
    expectNear(joint.anchorParent, core::Vec3(1, 0, 0), "anchor at the child link's origin, in a");
    expectNear(joint.axisParent, core::Vec3(0, -1, 0), "the axis turned by the joint's origin, in a");

    // It has no coordinate to start away from: a start position for it is refused, naming its type.
    UrdfOptions start;
    start.jointPositions = {{"slide", 0.1}};
    try
    {
        loadScene(path, start);
        ADD_FAILURE() << "a start position for a planar joint was taken";
    }
    catch (const InputError& e)
    {
        EXPECT_NE(
            std::string(e.what()).find("--joint-position slide: joint 'slide' has no position to start from "
                                       "(it is planar; revolute"),
            std::string::npos)
            << e.what();
    }
}

TEST(Urdf, ZeroAxis)
{
    TempDir dir;
    const InputError e = urdfError(dir, robot("  <link name=\"a\">" + cGoodInertial + "</link>\n" +
                                              "  <link name=\"b\">" + cGoodInertial + "</link>\n" +
                                              "  <joint name=\"hinge\" type=\"continuous\">\n"
                                              "    <parent link=\"a\"/><child link=\"b\"/>\n"
                                              "    <axis xyz=\"0 0 0\"/>\n  </joint>\n"));
    EXPECT_INPUT_ERROR_AT(e, dir.file("robot.urdf"), 6, 5, "joint 'hinge' has a zero <axis>");
}

// A collision box, so that the robot stands on the floor without a warning.
const std::string cNamelessBox = "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>";

TEST(Urdf, NamelessRobotIsNamedAfterItsFileWithAWarning)
{
    TempDir dir;
    const std::string links = "  <link name=\"a\">" + cGoodInertial + cNamelessBox + "</link>\n" +
                              "  <link name=\"b\">" + cGoodInertial + cNamelessBox + "</link>\n" +
                              "  <joint name=\"hinge\" type=\"continuous\">\n"
                              "    <parent link=\"a\"/><child link=\"b\"/>\n";
    const std::string arm =
        dir.write("my_arm.urdf", "<?xml version=\"1.0\"?>\n<robot\n    xmlns:xacro=\"x\">\n" + links +
                                     "    <axis xyz=\"0 0 1\"/>\n  </joint>\n</robot>\n");
    LoadReport report;
    const core::Model model = loadScene(arm, {}, &report);
    EXPECT_EQ(model.name, "my_arm");
    ASSERT_EQ(report.robots.size(), 1u);
    EXPECT_EQ(report.robots[0].name, "my_arm");
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find(arm + ":2:1: warning: the <robot> has no name"), std::string::npos)
        << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("'my_arm'"), std::string::npos) << report.warnings[0];

    // The name goes in without moving a line: a later mistake is reported where it is.
    const std::string bad =
        dir.write("bad.urdf", "<?xml version=\"1.0\"?>\n<robot\n    xmlns:xacro=\"x\">\n" + links +
                                  "    <axis xyz=\"0 0 0\"/>\n  </joint>\n</robot>\n");
    const InputError e = captureInputError([&] { loadScene(bad); });
    EXPECT_INPUT_ERROR_AT(e, bad, 8, 5, "joint 'hinge' has a zero <axis>");
}

TEST(Urdf, BadXmlReportsRowAndColumn)
{
    TempDir dir;
    const InputError e = urdfError(dir, "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n");
    EXPECT_EQ(e.file(), dir.file("robot.urdf"));
    EXPECT_GT(e.line(), 0) << e.what();
    EXPECT_NE(std::string(e.what()).find("invalid XML"), std::string::npos) << e.what();
}

TEST(Urdf, DroppedCollisionIsFatal)
{
    TempDir dir;
    // urdfdom drops a collision with an unreadable origin and only logs it.
    const InputError e =
        urdfError(dir, robot("  <link name=\"a\">\n    " + cGoodInertial +
                             "\n    <collision><origin xyz=\"0 zero 0\"/><geometry><box size=\"1 1 "
                             "1\"/></geometry></collision>\n  </link>\n"));
    EXPECT_EQ(e.line(), 2) << e.what();
    EXPECT_NE(std::string(e.what()).find("Could not parse collision element for Link [a]"), std::string::npos)
        << e.what();
}

TEST(Urdf, CapsuleIsNotUrdf)
{
    TempDir dir;
    const InputError e = urdfError(dir, robot("  <link name=\"a\">\n    " + cGoodInertial +
                                              "\n    <collision><geometry><capsule radius=\"1\" "
                                              "length=\"1\"/></geometry></collision>\n  </link>\n"));
    EXPECT_EQ(e.line(), 4) << e.what();
    EXPECT_NE(std::string(e.what()).find("Unknown geometry type 'capsule'"), std::string::npos) << e.what();
}

TEST(Urdf, InertialOffsetPutsTheBodyAtTheCentreOfMass)
{
    TempDir dir;
    // Link frame of `b` at (1, 0, 0) turned 90 degrees about z; inertial origin (0.2, 0, 0) in it.
    const std::string path = dir.write(
        "robot.urdf",
        robot("  <link name=\"a\">" + cGoodInertial + "</link>\n" +
              "  <link name=\"b\"><inertial><origin xyz=\"0.2 0 0\" rpy=\"0 0 0\"/><mass value=\"3\"/>"
              "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"3\"/></inertial></link>\n"
              "  <joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
              "<origin xyz=\"1 0 0\" rpy=\"0 0 1.5707963267948966\"/></joint>\n"));
    const core::Model model = loadScene(path);
    const int b = model.findBody("b");
    ASSERT_GE(b, 0);
    const core::Body& body = model.bodies[static_cast<std::size_t>(b)];
    expectNear(body.position_W, core::Vec3(1, 0.2, 0), "COM = link origin + R_link * inertial origin");
    expectSameRotation(body.orientation_WB, core::Quat(std::sqrt(0.5), 0, 0, std::sqrt(0.5)), "orientation");
    EXPECT_EQ(body.mass, 3.0);
    EXPECT_EQ(body.inertia_B.diagonal(), core::Vec3(1, 2, 3));
    ASSERT_EQ(model.joints.size(), 1u);
    EXPECT_EQ(model.joints[0].type, core::JointType::Revolute);
    // A URDF alone gets a static floor plane.
    ASSERT_EQ(model.bodies.size(), 3u);
    EXPECT_TRUE(model.bodies[2].isStatic);
    EXPECT_EQ(model.bodies[2].name, "floor");
    EXPECT_EQ(model.bodies[2].shapes.at(0).type, core::ShapeType::Plane);
}

TEST(Urdf, SameModelAsTheEquivalentYaml)
{
    TempDir dir;
    dir.write("arm.urdf", text(cArmUrdf));
    const std::string scene =
        dir.write("scene.yaml", "models:\n  - {urdf: arm.urdf, position: [0, 0, 1], prefix: a_}\n");
    const core::Model fromUrdf = loadScene(scene);
    const core::Model fromYaml = loadSceneFromString(text(cArmYaml), "arm.yaml");
    ASSERT_EQ(fromUrdf.bodies.size(), 3u);
    ASSERT_EQ(fromYaml.bodies.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i)
    {
        const core::Body& u = fromUrdf.bodies[i];
        const core::Body& y = fromYaml.bodies[i];
        SCOPED_TRACE(y.name);
        EXPECT_EQ(u.name, y.name);
        EXPECT_NEAR(u.mass, y.mass, cTol);
        EXPECT_LT((u.inertia_B - y.inertia_B).norm(), cTol);
        expectNear(u.position_W, y.position_W, "position");
        expectSameRotation(u.orientation_WB, y.orientation_WB, "orientation");
        ASSERT_EQ(u.shapes.size(), 1u);
        ASSERT_EQ(y.shapes.size(), 1u);
        EXPECT_EQ(u.shapes[0].type, y.shapes[0].type);
        EXPECT_EQ(u.shapes[0].size, y.shapes[0].size);
        EXPECT_EQ(u.shapes[0].radius, y.shapes[0].radius);
        EXPECT_EQ(u.shapes[0].length, y.shapes[0].length);
        expectNear(u.shapes[0].position_BS, y.shapes[0].position_BS, "shape position");
        expectSameRotation(u.shapes[0].rotation_BS, y.shapes[0].rotation_BS, "shape rotation");
    }
    ASSERT_TRUE(fromUrdf.bodies[0].color.has_value());
    EXPECT_LT((*fromUrdf.bodies[0].color - *fromYaml.bodies[0].color).norm(),
              1e-7); // urdfdom colours are floats
    ASSERT_EQ(fromUrdf.joints.size(), 2u);
    ASSERT_EQ(fromYaml.joints.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i)
    {
        const core::Joint& u = fromUrdf.joints[i];
        const core::Joint& y = fromYaml.joints[i];
        SCOPED_TRACE(y.name);
        EXPECT_EQ(u.name, y.name);
        EXPECT_EQ(u.type, y.type);
        EXPECT_EQ(u.parent, y.parent);
        EXPECT_EQ(u.child, y.child);
        expectNear(u.anchorParent, y.anchorParent, "anchorParent");
        expectNear(u.anchorChild, y.anchorChild, "anchorChild");
        expectNear(u.axisParent, y.axisParent, "axisParent");
        expectNear(u.axisChild, y.axisChild, "axisChild");
        expectNear(u.perpParent1, y.perpParent1, "perpParent1");
        expectNear(u.perpParent2, y.perpParent2, "perpParent2");
        expectNear(u.perpChild1, y.perpChild1, "perpChild1");
        expectSameRotation(u.restRotation_AB, y.restRotation_AB, "restRotation");
        ASSERT_TRUE(u.limits.has_value());
        EXPECT_EQ(*u.limits, *y.limits);
        EXPECT_FALSE(u.collideConnected);
    }
}

TEST(Urdf, InstancedTwiceWithPrefixesGroupsAndFixedRoot)
{
    TempDir dir;
    dir.write("arm.urdf", text(cArmUrdf));
    const std::string scene = dir.write("scene.yaml", text(R"(
models:
  - {urdf: arm.urdf, prefix: a_, self_collision: false}
  - {urdf: arm.urdf, prefix: b_, position: [1, 0, 0], fixed: true, angular_velocity: [1, 0, 0]}
)"));
    const core::Model model = loadScene(scene);
    ASSERT_EQ(model.bodies.size(), 6u);
    ASSERT_EQ(model.joints.size(), 4u);
    EXPECT_EQ(model.bodies[0].group, "a_");
    EXPECT_EQ(model.bodies[2].group, "a_");
    EXPECT_EQ(model.bodies[3].group, "");
    EXPECT_FALSE(model.bodies[0].isStatic);
    // b_base is static, at its link frame (the inertial is ignored); b_shoulder keeps it as parent.
    const int bBase = model.findBody("b_base");
    ASSERT_EQ(bBase, 3);
    EXPECT_TRUE(model.bodies[3].isStatic);
    expectNear(model.bodies[3].position_W, core::Vec3(1, 0, 0), "static root at its link frame");
    expectNear(model.bodies[3].shapes.at(0).position_BS, core::Vec3(0, 0, 0.05), "shape in the link frame");
    EXPECT_EQ(model.joints[2].name, "b_shoulder");
    EXPECT_EQ(model.joints[2].parent, 3);
    EXPECT_EQ(model.joints[2].child, 4);
    // Rigid rotation about the root link origin (1, 0, 0): b_upper's COM is at (1, 0, 0.3).
    expectNear(model.bodies[4].velocity_W, core::Vec3(1, 0, 0).cross(core::Vec3(0, 0, 0.3)), "velocity");
    expectNear(model.bodies[3].velocity_W, core::Vec3::Zero(), "static body does not move");
}

TEST(Urdf, SamePrefixTwiceIsAnError)
{
    TempDir dir;
    dir.write("arm.urdf", text(cArmUrdf));
    const std::string scene = dir.write("scene.yaml", text(R"(
models:
  - {urdf: arm.urdf, prefix: a_}
  - {urdf: arm.urdf, prefix: a_}
)"));
    const InputError e = captureInputError([&] { loadScene(scene); });
    EXPECT_INPUT_ERROR_AT(e, scene, 3, 5, "adds body 'a_base', but a body of that name exists already");
}

TEST(Urdf, YamlJointCanAttachToAUrdfLink)
{
    TempDir dir;
    dir.write("arm.urdf", text(cArmUrdf));
    const std::string scene = dir.write("scene.yaml", text(R"(
models:
  - {urdf: arm.urdf, prefix: a_}
joints:
  - {name: pin, type: ball, parent: world, child: a_base, anchor: [0, 0, 0]}
)"));
    const core::Model model = loadScene(scene);
    ASSERT_EQ(model.joints.size(), 3u);
    EXPECT_EQ(model.joints[2].name, "pin");
    EXPECT_EQ(model.joints[2].child, 0);
}

TEST(Urdf, ErrorInAModelNamesTheUrdfFile)
{
    TempDir dir;
    const std::string urdf = dir.write("bad.urdf", robot("  <link name=\"a\"/>\n"));
    const std::string scene = dir.write("scene.yaml", "models: [{urdf: bad.urdf}]\n");
    const InputError e = captureInputError([&] { loadScene(scene); });
    EXPECT_INPUT_ERROR_AT(e, urdf, 2, 3, "link 'a' has no mass");
}

// The joints must form a tree; a joint from a link to itself or a loop of joints (which once sent
// the pose walk round forever) is refused at the joint's line before anything else reads the file.
std::string revolute(const std::string& name, const std::string& parent, const std::string& child)
{
    return "  <joint name=\"" + name + "\" type=\"revolute\"><parent link=\"" + parent +
           "\"/><child link=\"" + child +
           "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\"/></joint>\n";
}

std::string massiveLink(const std::string& name)
{
    return "  <link name=\"" + name + "\">" + cGoodInertial + "</link>\n";
}

TEST(Urdf, JointsThatDoNotFormATreeAreRefusedAtTheJoint)
{
    TempDir dir;
    const std::string file = dir.file("robot.urdf");
    // Lines: 2 a, 3 b, 4 c, then the joints from line 5.
    const std::string links = massiveLink("a") + massiveLink("b") + massiveLink("c");
    EXPECT_INPUT_ERROR_AT(urdfError(dir, robot(links + revolute("j1", "a", "b") + revolute("j2", "b", "b"))),
                          file, 6, 3, "joint 'j2' joins link 'b' to itself");
    EXPECT_INPUT_ERROR_AT(urdfError(dir, robot(links + revolute("j1", "a", "b") + revolute("j2", "b", "c") +
                                               revolute("j3", "c", "b"))),
                          file, 7, 3, "link 'b' is the child of joint 'j1' and of joint 'j3'");
    // A loop that leaves no link without a parent: urdfdom would say only "failed to find root link".
    EXPECT_INPUT_ERROR_AT(urdfError(dir, robot(links + revolute("j1", "a", "b") + revolute("j2", "b", "a"))),
                          file, 6, 3, "closes a loop of joints through link");
}

// TinyXML recurses once per level: 40 000 nested elements overflowed the stack, 30 000 took 16 s.
// A linear scan refuses them (and names where the limit was passed) before any parser runs.
TEST(Urdf, DeeplyNestedElementsAreRefusedBeforeParsing)
{
    TempDir dir;
    const int depth = 40000;
    std::string nested;
    for (int i = 0; i < depth; ++i)
    {
        nested += "<x>";
    }
    for (int i = 0; i < depth; ++i)
    {
        nested += "</x>";
    }
    const InputError e = urdfError(dir, robot(massiveLink("a") + nested + "\n"));
    // <robot> is level 1, so the 1000th <x> (column 3 * 999 + 1) is level 1001.
    EXPECT_INPUT_ERROR_AT(e, dir.file("robot.urdf"), 3, 2998, "elements nested more than 1000 levels deep");
    // Comments, CDATA, processing instructions, quoted '>' and self-closing tags open no level.
    std::string flat = "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n" + massiveLink("a");
    for (int i = 0; i < 2000; ++i)
    {
        flat += "<!-- <x> --><![CDATA[<x>]]><y a=\">\"/>";
    }
    flat += "\n</robot>\n";
    const std::string path = dir.write("flat.urdf", flat);
    EXPECT_NO_THROW(loadScene(path));
}

TEST(Urdf, DoctypeAndUnclosedCommentsAreLocated)
{
    TempDir dir;
    const std::string file = dir.file("robot.urdf");
    EXPECT_INPUT_ERROR_AT(urdfError(dir, "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [ <!ENTITY m \"1\"> ]>\n" +
                                             robot(massiveLink("a"))),
                          file, 2, 1,
                          "a <!DOCTYPE> declaration (and the entities it may define) is not supported");
    EXPECT_INPUT_ERROR_AT(
        urdfError(dir, "<robot name=\"r\">\n" + massiveLink("a") + "  <!-- open\n</robot>\n"), file, 3, 3,
        "the comment '<!--' is never closed; expected '-->'");
    EXPECT_INPUT_ERROR_AT(urdfError(dir, "\n<robot name=\"r\">\n</robot>\n"), file, 2, 1,
                          "No link elements found");
    EXPECT_INPUT_ERROR_AT(urdfError(dir, ""), file, 1, 1, "Error document empty");
}

// A FIFO would block the open, /dev/zero never ends: both are refused at once, as a URDF file and
// as a mesh named by a file:// URI.
TEST(Urdf, OnlyRegularFilesAreRead)
{
    TempDir dir;
    const std::string fifo = dir.file("pipe.urdf");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_INPUT_ERROR_AT(captureInputError([&] { loadScene(fifo); }), fifo, 0, 0,
                          "is not a regular file (a FIFO), expected a URDF file");
    const std::string zero = dir.file("zero.urdf");
    std::filesystem::create_symlink("/dev/zero", zero);
    EXPECT_INPUT_ERROR_AT(captureInputError([&] { loadScene(zero); }), zero, 0, 0,
                          "is not a regular file (a device), expected a URDF file");
    const InputError mesh = urdfError(
        dir, robot("  <link name=\"a\">" + cGoodInertial +
                   "\n    <collision><geometry><mesh filename=\"file:///dev/zero\"/></geometry></collision>\n"
                   "  </link>\n"));
    EXPECT_INPUT_ERROR_AT(mesh, dir.file("robot.urdf"), 3, 26,
                          "/dev/zero: error: is not a regular file (a device)");
}

} // namespace
} // namespace frontier::io::test

namespace frontier::io::test
{
namespace
{
const std::string cMaterialBox = "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>";

// PyBullet's <contact> block and Gazebo's <mu1> give a link's friction and restitution; a link's
// own <contact> wins over <gazebo>, a link without either takes the scene's.
TEST(UrdfMaterials, ContactBlockAndGazeboMu1GiveTheLinksMaterial)
{
    TempDir dir;
    const std::string urdf = robot(
        "  <link name=\"foot\">" + cGoodInertial + cMaterialBox +
        "<contact><lateral_friction value=\"1.1\"/><restitution value=\"0.3\"/></contact></link>\n"
        "  <link name=\"shin\">" +
        cGoodInertial + cMaterialBox + "</link>\n" + "  <link name=\"hand\">" + cGoodInertial + cMaterialBox +
        "</link>\n"
        "  <joint name=\"a\" type=\"continuous\"><parent link=\"foot\"/><child link=\"shin\"/></joint>\n"
        "  <joint name=\"b\" type=\"continuous\"><parent link=\"shin\"/><child link=\"hand\"/></joint>\n"
        "  <gazebo reference=\"shin\"><mu1>0.7</mu1></gazebo>\n"
        "  <gazebo reference=\"foot\"><mu1>0.2</mu1></gazebo>\n");
    const core::Model model = loadScene(dir.write("robot.urdf", urdf));
    const core::Body& foot = model.bodies[static_cast<std::size_t>(model.findBody("foot"))];
    const core::Body& shin = model.bodies[static_cast<std::size_t>(model.findBody("shin"))];
    const core::Body& hand = model.bodies[static_cast<std::size_t>(model.findBody("hand"))];
    EXPECT_EQ(foot.friction, 1.1);
    EXPECT_EQ(foot.restitution, 0.3);
    EXPECT_EQ(shin.friction, 0.7);
    EXPECT_FALSE(shin.restitution);
    EXPECT_FALSE(hand.friction);
    EXPECT_FALSE(hand.restitution);
}

TEST(UrdfMaterials, AnImpossibleValueIsAnErrorAtItsLine)
{
    TempDir dir;
    const InputError e =
        urdfError(dir, robot("  <link name=\"foot\">" + cGoodInertial + cMaterialBox +
                             "\n    <contact><restitution value=\"1.5\"/></contact></link>\n"));
    EXPECT_INPUT_ERROR_AT(e, dir.file("robot.urdf"), 3, 14,
                          "expected a restitution in [0, 1] for link 'foot', got '1.5'");
}
} // namespace
} // namespace frontier::io::test
