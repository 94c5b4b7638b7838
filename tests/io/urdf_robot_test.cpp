// tests/io/urdf_robot_test.cpp: what real robot files need: package:// and other mesh URIs,
// links welded by fixed joints, frame-only links, a robot placed on the floor or fixed to the world,
// joint dynamics. Expectations are worked out here by hand (parallel-axis theorem, support points).
#include "io/scene.h"
#include "io_test_util.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <numbers>
#include <pthread.h>

namespace frontier::io::test
{
namespace
{

namespace fs = std::filesystem;

// A closed unit-ish box mesh (0.1 m cube centred at its origin) as Wavefront OBJ.
const char* const cCubeObj = R"(v -0.05 -0.05 -0.05
v 0.05 -0.05 -0.05
v 0.05 0.05 -0.05
v -0.05 0.05 -0.05
v -0.05 -0.05 0.05
v 0.05 -0.05 0.05
v 0.05 0.05 0.05
v -0.05 0.05 0.05
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
)";

// A tetrahedron (0,0,0) (0.1,0,0) (0,0.2,0) (0,0,0.3) with outward faces: no mirror symmetry.
const char* const cTetraObj =
    "v 0 0 0\nv 0.1 0 0\nv 0 0.2 0\nv 0 0 0.3\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

std::string packageXml(const std::string& name)
{
    return "<?xml version=\"1.0\"?>\n<package format=\"2\">\n  <name>" + name +
           "</name>\n  <version>1.0.0</version>\n</package>\n";
}

// A one-link robot whose collision (and visual) is the mesh at `uri`.
std::string meshRobot(const std::string& collisionUri, const std::string& visualUri = "")
{
    std::string visual;
    if (!visualUri.empty())
    {
        visual = "    <visual><geometry><mesh filename=\"" + visualUri + "\"/></geometry></visual>\n";
    }
    return "<robot name=\"r\">\n  <link name=\"a\">\n    <inertial><mass value=\"1\"/><inertia ixx=\"0.01\" "
           "ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>\n" +
           visual + "    <collision><geometry><mesh filename=\"" + collisionUri +
           "\"/></geometry></collision>\n  </link>\n</robot>\n";
}

void mkdirs(const TempDir& dir, const std::string& sub)
{
    fs::create_directories(dir.path() / sub);
}

// Restores an environment variable at the end of a test.
class ScopedEnv
{
  public:
    ScopedEnv(const char* name, const std::string& value) : mName(name)
    {
        if (const char* old = std::getenv(name))
        {
            mOld = old;
        }
        ::setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv()
    {
        if (mOld)
        {
            ::setenv(mName, mOld->c_str(), 1);
        }
        else
        {
            ::unsetenv(mName);
        }
    }

  private:
    const char* mName;
    std::optional<std::string> mOld;
};

std::size_t meshVertexCount(const core::Model& model)
{
    return model.bodies.at(0).shapes.at(0).vertices.size();
}

TEST(UrdfPackages, PackagePathThatIsAPackage)
{
    TempDir dir;
    mkdirs(dir, "pkgs/my_robot/meshes");
    mkdirs(dir, "robot");
    dir.write("pkgs/my_robot/package.xml", packageXml("my_robot"));
    dir.write("pkgs/my_robot/meshes/cube.obj", cCubeObj);
    const std::string urdf = dir.write("robot/r.urdf", meshRobot("package://my_robot/meshes/cube.obj"));
    UrdfOptions options;
    options.packagePaths = {dir.file("pkgs/my_robot")};
    EXPECT_EQ(meshVertexCount(loadScene(urdf, options)), 8u);
    // A folder that holds packages, searched a few levels down.
    options.packagePaths = {dir.file("pkgs")};
    EXPECT_EQ(meshVertexCount(loadScene(urdf, options)), 8u);
    options.packagePaths = {dir.path().string()};
    EXPECT_EQ(meshVertexCount(loadScene(urdf, options)), 8u);
}

TEST(UrdfPackages, ThreeSlashesAreReadAsTwo)
{
    TempDir dir;
    mkdirs(dir, "pkgs/my_robot/meshes");
    mkdirs(dir, "robot");
    dir.write("pkgs/my_robot/package.xml", packageXml("my_robot"));
    dir.write("pkgs/my_robot/meshes/tetra.obj", cTetraObj);
    UrdfOptions options;
    options.packagePaths = {dir.file("pkgs")};
    const core::Model two =
        loadScene(dir.write("robot/two.urdf", meshRobot("package://my_robot/meshes/tetra.obj")), options);
    LoadReport report;
    const core::Model three = loadScene(
        dir.write("robot/three.urdf", meshRobot("package:///my_robot/meshes/tetra.obj")), options, &report);
    EXPECT_TRUE(report.warnings.empty());
    const core::Shape& mesh = three.bodies.at(0).shapes.at(0);
    EXPECT_EQ(mesh.meshFile, dir.file("pkgs/my_robot/meshes/tetra.obj"));
    EXPECT_EQ(mesh.meshFile, two.bodies.at(0).shapes.at(0).meshFile);
    EXPECT_EQ(mesh.vertices, two.bodies.at(0).shapes.at(0).vertices);
}

TEST(UrdfPackages, NameEqualsDirMapsAPackageWithoutManifest)
{
    TempDir dir;
    mkdirs(dir, "anything/meshes");
    mkdirs(dir, "robot");
    dir.write("anything/meshes/cube.obj", cCubeObj);
    const std::string urdf =
        dir.write("robot/r.urdf", meshRobot("package://herb_description/meshes/cube.obj"));
    UrdfOptions options;
    options.packagePaths = {"herb_description=" + dir.file("anything")};
    LoadReport report;
    EXPECT_EQ(meshVertexCount(loadScene(urdf, options, &report)), 8u);
    EXPECT_TRUE(report.warnings.empty());
}

TEST(UrdfPackages, RosPackagePathEnvironment)
{
    TempDir dir;
    mkdirs(dir, "ws/src/deep/my_robot/meshes");
    mkdirs(dir, "robot");
    dir.write("ws/src/deep/my_robot/package.xml", packageXml("my_robot"));
    dir.write("ws/src/deep/my_robot/meshes/cube.obj", cCubeObj);
    const std::string urdf = dir.write("robot/r.urdf", meshRobot("package://my_robot/meshes/cube.obj"));
    const ScopedEnv env("ROS_PACKAGE_PATH", "/nonexistent:" + dir.file("ws"));
    EXPECT_EQ(meshVertexCount(loadScene(urdf)), 8u);
}

TEST(UrdfPackages, TheUrdfsOwnPackage)
{
    TempDir dir;
    mkdirs(dir, "my_robot/urdf");
    mkdirs(dir, "my_robot/meshes");
    dir.write("my_robot/package.xml", packageXml("my_robot"));
    dir.write("my_robot/meshes/cube.obj", cCubeObj);
    const std::string urdf =
        dir.write("my_robot/urdf/r.urdf", meshRobot("package://my_robot/meshes/cube.obj"));
    LoadReport report;
    EXPECT_EQ(meshVertexCount(loadScene(urdf, {}, &report)), 8u);
    EXPECT_TRUE(report.warnings.empty());
}

TEST(UrdfPackages, FilesBesideTheUrdfAreALastResortWithAWarning)
{
    TempDir dir;
    mkdirs(dir, "robot/meshes");
    dir.write("robot/meshes/cube.obj", cCubeObj);
    const std::string urdf = dir.write("robot/r.urdf", meshRobot("package://unknown_pkg/meshes/cube.obj"));
    LoadReport report;
    EXPECT_EQ(meshVertexCount(loadScene(urdf, {}, &report)), 8u);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find(urdf + ":4:26: warning"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("package 'unknown_pkg' was not found"), std::string::npos);
    EXPECT_NE(report.warnings[0].find("beside the URDF"), std::string::npos);
}

TEST(UrdfPackages, FileAndModelUris)
{
    TempDir dir;
    mkdirs(dir, "models/crate/meshes");
    dir.write("models/crate/meshes/cube.obj", cCubeObj);
    const std::string cube = dir.write("cube.obj", cCubeObj);
    EXPECT_EQ(meshVertexCount(loadScene(dir.write("a.urdf", meshRobot("file://" + cube)))), 8u);
    // Percent-encoded, as some exporters write paths with spaces.
    const std::string spaced = dir.write("my cube.obj", cCubeObj);
    (void)spaced;
    EXPECT_EQ(
        meshVertexCount(loadScene(dir.write("b.urdf", meshRobot("file://" + dir.file("my%20cube.obj"))))),
        8u);
    const ScopedEnv env("GAZEBO_MODEL_PATH", dir.file("models"));
    EXPECT_EQ(meshVertexCount(loadScene(dir.write("c.urdf", meshRobot("model://crate/meshes/cube.obj")))),
              8u);
}

TEST(UrdfPackages, UnresolvedPackageNamesFileLinePackageAndWhereItLooked)
{
    TempDir dir;
    mkdirs(dir, "elsewhere");
    const std::string urdf = dir.write("r.urdf", meshRobot("package://missing_package/foo.stl"));
    UrdfOptions options;
    options.packagePaths = {dir.file("elsewhere")};
    const InputError e = captureInputError([&] { loadScene(urdf, options); });
    EXPECT_INPUT_ERROR_AT(e, urdf, 4, 26, "package 'missing_package' not found");
    const std::string what = e.what();
    EXPECT_NE(what.find("--package-path " + dir.file("elsewhere")), std::string::npos) << what;
    EXPECT_NE(what.find("collision mesh 'package://missing_package/foo.stl' of link 'a'"), std::string::npos)
        << what;
}

// A package:// path stays inside its package folder: '..' above it (or a package named '..') is
// refused at the mesh's line, even where the file it would reach exists.
TEST(UrdfPackages, DotDotCannotLeaveThePackage)
{
    TempDir dir;
    mkdirs(dir, "pkgs/my_robot/urdf");
    dir.write("pkgs/my_robot/package.xml", packageXml("my_robot"));
    dir.write("pkgs/secret.obj", cCubeObj);
    for (const char* uri : {"package://my_robot/../secret.obj", "package://../../secret.obj",
                            "package://my_robot/meshes/../../../secret.obj", "model://..%2f..%2fsecret.obj"})
    {
        const std::string urdf = dir.write("pkgs/my_robot/urdf/r.urdf", meshRobot(uri));
        EXPECT_INPUT_ERROR_AT(captureInputError([&] { loadScene(urdf); }), urdf, 4, 26,
                              "'" + std::string(uri) + "' leads out of its package folder");
    }
}

// A mesh scaled beyond the ranges of core/model.h is refused at its `scale` (YAML) or its <mesh>
// element (URDF): its vertices would be far beyond what the collision detection can take.
TEST(UrdfPackages, MeshScaledOutOfRangeIsRefused)
{
    TempDir dir;
    dir.write("cube.obj", cCubeObj);
    const std::string scene = dir.write(
        "scene.yaml",
        "bodies:\n  - {name: part, mass: 1, inertia: [1, 1, 1], shape: {type: mesh, file: cube.obj, scale: "
        "1.0e300}}\n");
    EXPECT_INPUT_ERROR_AT(
        captureInputError([&] { loadScene(scene); }), scene, 2, 90,
        "mesh 'cube.obj' of mesh shape of body 'part' reaches 8.66025e+298 m from its origin at "
        "this scale; expected a length in (0, 1e6] m");
    std::string robot = meshRobot("cube.obj");
    robot.replace(robot.find("cube.obj\"/>"), 11, "cube.obj\" scale=\"1 1e300 1\"/>");
    const std::string urdf = dir.write("r.urdf", robot);
    EXPECT_INPUT_ERROR_AT(
        captureInputError([&] { loadScene(urdf); }), urdf, 4, 26,
        "collision mesh 'cube.obj' of link 'a' reaches 5e+298 m from its origin at scale (1, "
        "1e+300, 1)");
}

TEST(UrdfPackages, PackageFoundButFileMissing)
{
    TempDir dir;
    mkdirs(dir, "my_robot");
    dir.write("my_robot/package.xml", packageXml("my_robot"));
    const std::string urdf = dir.write("my_robot/r.urdf", meshRobot("package://my_robot/meshes/nope.stl"));
    const InputError e = captureInputError([&] { loadScene(urdf); });
    EXPECT_INPUT_ERROR_AT(
        e, urdf, 4, 26, "package 'my_robot' is " + dir.file("my_robot") + ", which has no 'meshes/nope.stl'");
}

TEST(UrdfMeshes, MissingVisualMeshIsAWarningMissingCollisionMeshAnError)
{
    TempDir dir;
    dir.write("cube.obj", cCubeObj);
    const std::string urdf = dir.write("r.urdf", meshRobot("cube.obj", "no_such_visual.dae"));
    LoadReport report;
    const core::Model model = loadScene(urdf, {}, &report);
    const core::Body& body = model.bodies.at(0);
    ASSERT_EQ(body.visuals.size(), 1u); // drawn from its collision shapes
    EXPECT_EQ(body.visuals[0].vertices, body.shapes.at(0).vertices);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find(urdf + ":4:"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("visual mesh 'no_such_visual.dae' of link 'a' cannot be read"),
              std::string::npos)
        << report.warnings[0];

    const std::string bad = dir.write("bad.urdf", meshRobot("no_such_collision.stl", "cube.obj"));
    const InputError e = captureInputError([&] { loadScene(bad); });
    EXPECT_INPUT_ERROR_AT(e, bad, 5, 26, "collision mesh 'no_such_collision.stl' of link 'a'");
}

// A one-link robot whose visual (line 4) and collision (line 5) are the mesh `file` at `scale`.
std::string scaledMeshRobot(const std::string& file, const std::string& scale)
{
    const std::string mesh = "<geometry><mesh filename=\"" + file + "\" scale=\"" + scale + "\"/></geometry>";
    return "<robot name=\"r\">\n  <link name=\"a\">\n    <inertial><mass value=\"1\"/><inertia ixx=\"0.01\" "
           "ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>\n    <visual>" +
           mesh + "</visual>\n    <collision>" + mesh + "</collision>\n  </link>\n</robot>\n";
}

// Volume (m^3) enclosed by a mesh shape, by the divergence theorem: negative when inside out.
double urdfMeshVolume(const core::Shape& shape)
{
    double sixTimes = 0.0;
    for (const auto& t : shape.triangles)
    {
        sixTimes += shape.vertices.at(static_cast<std::size_t>(t[0]))
                        .dot(shape.vertices.at(static_cast<std::size_t>(t[1]))
                                 .cross(shape.vertices.at(static_cast<std::size_t>(t[2]))));
    }
    return sixTimes / 6.0;
}

// trunk (a visual mesh that is missing, a collision box) welded to marker (a visual sphere 0.5 m
// up): the trunk is drawn as its box even though its body has another link's visual.
const char* const cTrunkWithoutVisual = R"(<robot name="dog">
  <link name="trunk">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <visual><geometry><mesh filename="missing_trunk.dae"/></geometry></visual>
    <collision><origin xyz="0.1 0 0"/><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
  </link>
  <joint name="marker_fixed" type="fixed"><parent link="trunk"/><child link="marker"/><origin xyz="0 0 0.5"/></joint>
  <link name="marker">
    <visual><geometry><sphere radius="0.05"/></geometry></visual>
  </link>
</robot>
)";

TEST(UrdfMeshes, ALinkWhoseVisualMeshIsMissingIsDrawnFromItsCollisionShapes)
{
    TempDir dir;
    const std::string urdf = dir.write("dog.urdf", cTrunkWithoutVisual);
    LoadReport report;
    const core::Model model = loadScene(urdf, {}, &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find(urdf + ":4:"), std::string::npos) << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("the link is drawn from its collision shapes"), std::string::npos)
        << report.warnings[0];
    const core::Body& body = model.bodies.at(0);
    ASSERT_EQ(body.shapes.size(), 1u);
    ASSERT_EQ(body.visuals.size(), 2u); // the trunk's box, then the marker's sphere
    EXPECT_EQ(body.visuals[0].type, core::ShapeType::Box);
    EXPECT_EQ(body.visuals[0].size, core::Vec3(0.4, 0.2, 0.1));
    EXPECT_EQ(body.visuals[0].position_BS, body.shapes[0].position_BS);
    EXPECT_EQ(body.visuals[1].type, core::ShapeType::Sphere);
}

TEST(UrdfMeshes, NegativeScaleMirrorsCollisionAndVisualMeshes)
{
    TempDir dir;
    dir.write("tetra.obj", cTetraObj);
    const core::Model plain = loadScene(dir.write("plain.urdf", scaledMeshRobot("tetra.obj", "1 1 1")));
    LoadReport report;
    const core::Model mirrored =
        loadScene(dir.write("mirrored.urdf", scaledMeshRobot("tetra.obj", "1 -1 1")), {}, &report);
    EXPECT_TRUE(report.warnings.empty());
    const core::Body& p = plain.bodies.at(0);
    const core::Body& m = mirrored.bodies.at(0);
    ASSERT_EQ(m.shapes.size(), 1u);
    ASSERT_EQ(m.visuals.size(), 1u);
    for (const core::Shape* shape : {&m.shapes[0], &m.visuals[0]})
    {
        const core::Shape& unmirrored = shape == &m.shapes[0] ? p.shapes.at(0) : p.visuals.at(0);
        ASSERT_EQ(shape->vertices.size(), unmirrored.vertices.size());
        for (std::size_t i = 0; i < shape->vertices.size(); ++i)
        {
            EXPECT_EQ(shape->vertices[i], unmirrored.vertices[i].cwiseProduct(core::Vec3(1, -1, 1)));
        }
        EXPECT_NEAR(urdfMeshVolume(*shape), 0.001, 1e-9); // 0.1 * 0.2 * 0.3 / 6, facing outwards
    }
}

TEST(UrdfMeshes, ZeroScaleIsAnError)
{
    TempDir dir;
    dir.write("tetra.obj", cTetraObj);
    const std::string urdf = dir.write("r.urdf", scaledMeshRobot("tetra.obj", "1 0 1"));
    const InputError e = captureInputError([&] { loadScene(urdf); });
    EXPECT_INPUT_ERROR_AT(e, urdf, 5, 26, "collision mesh 'tetra.obj' of link 'a' has scale=\"1 0 1\"");
    EXPECT_NE(std::string(e.what()).find("expected three nonzero numbers"), std::string::npos) << e.what();
}

// base (2 kg box) --fixed--> plate (1 kg, 0.3 m up, turned 90 degrees about z, its own inertial offset)
// --fixed--> frame (no inertial) --revolute--> arm (1 kg). Expected body: base + plate; arm's joint
// hangs from it.
const char* const cWelded = R"(<robot name="w">
  <link name="base">
    <inertial><origin xyz="0 0 0.1"/><mass value="2"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <joint name="plate_fixed" type="fixed">
    <parent link="base"/><child link="plate"/>
    <origin xyz="0 0 0.3" rpy="0 0 1.5707963267948966"/>
  </joint>
  <link name="plate">
    <inertial><origin xyz="0.1 0 0"/><mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.0025"/></inertial>
    <collision><origin xyz="0.1 0 0"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="frame_fixed" type="fixed">
    <parent link="plate"/><child link="tool_frame"/>
    <origin xyz="0 0 0.1"/>
  </joint>
  <link name="tool_frame"/>
  <joint name="hinge" type="revolute">
    <parent link="tool_frame"/><child link="arm"/>
    <origin xyz="0 0 0.05"/>
    <axis xyz="1 0 0"/>
    <limit lower="-4.5" upper="4.5" effort="1" velocity="1"/>
    <dynamics damping="0.7" friction="0.2"/>
  </joint>
  <link name="arm">
    <inertial><origin xyz="0 0 0.2"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/></inertial>
  </link>
</robot>
)";

TEST(UrdfWelding, FixedJointsWeldLinksIntoOneBody)
{
    TempDir dir;
    // In a scene at the origin (a bare URDF would be moved onto the floor).
    dir.write("w.urdf", cWelded);
    const std::string scene = dir.write("scene.yaml", "models: [{urdf: w.urdf}]\n");
    LoadReport report;
    const core::Model model = loadScene(scene, {}, &report);
    ASSERT_EQ(model.bodies.size(), 2u);
    ASSERT_EQ(model.joints.size(), 1u); // no rows for the fixed joints
    const core::Body& body = model.bodies[0];
    EXPECT_EQ(body.name, "base");
    // Parts in the world (the initial pose): base COM (0, 0, 0.1), 2 kg; plate frame at (0, 0, 0.3)
    // turned 90 degrees about z, so its COM (0.1, 0, 0) in it is (0, 0.1, 0.3) in the world.
    const core::Vec3 c1(0, 0, 0.1), c2(0, 0.1, 0.3);
    const core::Vec3 com = (2.0 * c1 + 1.0 * c2) / 3.0;
    EXPECT_DOUBLE_EQ(body.mass, 3.0);
    EXPECT_LT((body.position_W - com).norm(), 1e-15) << body.position_W.transpose();
    // Inertia about the combined COM, body axes = base's inertial axes = world axes here:
    // I = sum (I_k + m_k (|d|^2 1 - d d^T)); the plate's inertia turned by Rz(90): ixx <-> iyy.
    auto shifted = [](double m, const core::Vec3& d)
    { return m * (d.squaredNorm() * core::Mat3::Identity() - d * d.transpose()); };
    const core::Mat3 expected =
        core::Vec3(0.02, 0.03, 0.04).asDiagonal().toDenseMatrix() + shifted(2.0, c1 - com) +
        core::Vec3(0.002, 0.001, 0.0025).asDiagonal().toDenseMatrix() + shifted(1.0, c2 - com);
    EXPECT_LT((body.inertia_B - expected).norm(), 1e-15) << body.inertia_B;
    // Both links' shapes, posed in the body frame.
    ASSERT_EQ(body.shapes.size(), 2u);
    EXPECT_LT((body.shapes[0].position_BS - (c1 - com)).norm(), 1e-15);
    EXPECT_LT((body.shapes[1].position_BS - (c2 - com)).norm(), 1e-15);
    // The revolute joint hangs from the welded body at tool_frame + 0.05 = (0, 0, 0.45); its axis
    // x in the turned frame is y in the world.
    const core::Joint& hinge = model.joints[0];
    EXPECT_EQ(hinge.parent, 0);
    EXPECT_EQ(hinge.child, 1);
    EXPECT_LT((body.position_W + body.orientation_WB * hinge.anchorParent - core::Vec3(0, 0, 0.45)).norm(),
              1e-15);
    EXPECT_LT((body.orientation_WB * hinge.axisParent - core::Vec3::UnitY()).norm(), 1e-15);
    EXPECT_EQ(*hinge.limits, (std::array<double, 2>{-4.5, 4.5}));
    EXPECT_EQ(hinge.damping, 0.7);
    EXPECT_EQ(hinge.friction, 0.2);
    ASSERT_EQ(report.robots.size(), 1u);
    const std::vector<std::pair<std::string, std::string>> welded{{"plate", "base"}, {"tool_frame", "base"}};
    EXPECT_EQ(report.robots[0].welded, welded);
}

TEST(UrdfWelding, AWeldedLinkNamesItsBodyInTheScene)
{
    TempDir dir;
    dir.write("w.urdf", cWelded);
    const std::string scene = dir.write("scene.yaml", text(R"(
models: [{urdf: w.urdf, prefix: r_}]
bodies:
  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.05}, position: [0, 0, 2]}
joints:
  - {name: tether, type: ball, parent: r_tool_frame, child: ball, anchor: [0, 0, 1]}
)"));
    const core::Model model = loadScene(scene);
    EXPECT_EQ(model.joints.back().parent, model.findBody("r_base"));
}

TEST(UrdfWelding, WorldLinkFixesTheRobotAndFreeBaseLetsItFloat)
{
    TempDir dir;
    const std::string urdf = dir.write("arm.urdf", text(R"(
<robot name="arm">
  <link name="world"/>
  <joint name="bolt" type="fixed"><parent link="world"/><child link="base"/><origin xyz="0 0 0.5"/></joint>
  <link name="base">
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/></joint>
  <link name="arm">
    <inertial><origin xyz="0 0 0.2"/><mass value="1"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.05 0.05 0.4"/></geometry></collision>
  </link>
</robot>
)"));
    LoadReport report;
    const core::Model fixed = loadScene(urdf, {}, &report);
    ASSERT_EQ(fixed.bodies.size(), 3u); // base (static, no mass needed), arm, floor
    EXPECT_TRUE(fixed.bodies[0].isStatic);
    EXPECT_LT((fixed.bodies[0].position_W - core::Vec3(0, 0, 0.5)).norm(), 1e-15); // where the URDF puts it
    EXPECT_EQ(fixed.bodies[2].shapes.at(0).offset, 0.0); // nothing below z = 0: the floor stays
    EXPECT_NE(report.robots.at(0).placement.find("fixed to the world by the URDF"), std::string::npos);
    // --free-base: the massless base would float, which is an error naming it.
    UrdfOptions free;
    free.freeBase = true;
    const InputError e = captureInputError([&] { loadScene(urdf, free); });
    EXPECT_INPUT_ERROR_AT(e, urdf, 4, 3, "link 'base' has no mass");
}

// A robot held by a floating joint from 'world' (scenes/doll.urdf) floats; --fixed-base bolts the
// joint's child, its root link, where the joint places it (1 m up), and leaves the rest moving.
TEST(UrdfPlacement, FixedBaseBoltsTheChildOfAFloatingJointFromWorld)
{
    const std::string urdf = std::string(FRONTIER_SOURCE_DIR) + "/scenes/doll.urdf";
    const core::Model free = loadScene(urdf, {});
    UrdfOptions options;
    options.fixedBase = true;
    LoadReport report;
    const core::Model fixed = loadScene(urdf, options, &report);
    ASSERT_EQ(fixed.bodies.size(), free.bodies.size());
    int statics = 0;
    for (std::size_t i = 0; i < fixed.bodies.size(); ++i)
    {
        statics += fixed.bodies[i].isStatic && !free.bodies[i].isStatic ? 1 : 0;
    }
    EXPECT_EQ(statics, 1);
    const int pelvis = fixed.findBody("pelvis");
    ASSERT_GE(pelvis, 0);
    EXPECT_TRUE(fixed.bodies[static_cast<std::size_t>(pelvis)].isStatic);
    EXPECT_NEAR(fixed.bodies[static_cast<std::size_t>(pelvis)].position_W.z(), 1.0, 0.2);
    EXPECT_NE(report.robots.at(0).placement.find("--fixed-base"), std::string::npos);
}

TEST(UrdfPlacement, FreeRobotRestsItsLowestCollisionPointOnTheFloor)
{
    TempDir dir;
    // A box turned 45 degrees about x, its link frame at z = -1: lowest point at
    // -1 - (0.1 cos 45 + 0.3 sin 45) (half-extents 0.1 along y, 0.3 along z).
    const std::string urdf = dir.write("box.urdf", text(R"(
<robot name="box">
  <link name="b">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><origin xyz="0 0 -1" rpy="0.7853981633974483 0 0"/><geometry><box size="0.4 0.2 0.6"/></geometry></collision>
  </link>
</robot>
)"));
    const double lowest = -1.0 - (0.1 + 0.3) * std::sqrt(0.5);
    for (const double height : {0.0, 0.25})
    {
        UrdfOptions options;
        if (height > 0.0)
        {
            options.dropHeight = height;
        }
        LoadReport report;
        const core::Model model = loadScene(urdf, options, &report);
        EXPECT_NEAR(model.bodies[0].position_W.z(), height - lowest, 1e-14);
        EXPECT_NE(report.robots.at(0).placement.find("free-floating"), std::string::npos);
    }
    // --fixed-base: the robot stays; the floor goes under its lowest point (below z = 0 here).
    UrdfOptions fixed;
    fixed.fixedBase = true;
    const core::Model model = loadScene(urdf, fixed);
    EXPECT_TRUE(model.bodies[0].isStatic);
    EXPECT_EQ(model.bodies[0].position_W, core::Vec3::Zero());
    EXPECT_NEAR(model.bodies[1].shapes.at(0).offset, lowest, 1e-14);
}

// A scene of one sphere and no robot, written into `dir`.
std::string sceneWithoutRobots(const TempDir& dir)
{
    return dir.write("s.yaml", "bodies: [{name: a, mass: 1, shape: {type: sphere, radius: 1}}]\n");
}

TEST(UrdfPlacement, PlacementFlagsAreForABareUrdf)
{
    TempDir dir;
    const std::string scene = sceneWithoutRobots(dir);
    UrdfOptions options;
    options.fixedBase = true;
    const InputError e = captureInputError([&] { loadScene(scene, options); });
    EXPECT_NE(std::string(e.what()).find("a scene places its models itself"), std::string::npos) << e.what();
}

// --self-collision on a scene with no URDF robot changes nothing: a warning says so and names the
// scene's own keys; a scene that places a robot takes it without one.
TEST(UrdfPlacement, SelfCollisionFlagWarnsOnASceneWithoutRobots)
{
    TempDir dir;
    const std::string scene = sceneWithoutRobots(dir);
    UrdfOptions options;
    options.selfCollision = false;
    LoadReport report;
    loadScene(scene, options, &report);
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_EQ(report.warnings[0].rfind(scene + ": warning: --self-collision applies to URDF robots", 0), 0u)
        << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("'group'"), std::string::npos) << report.warnings[0];

    LoadReport withRobot;
    loadScene(std::string(FRONTIER_SOURCE_DIR) + "/scenes/doll_urdf_scene.yaml", options, &withRobot);
    for (const std::string& warning : withRobot.warnings)
    {
        EXPECT_EQ(warning.find("--self-collision"), std::string::npos) << warning;
    }
}

TEST(UrdfJoints, LockedLimitAndMimicAreWarnings)
{
    TempDir dir;
    const std::string urdf = dir.write("r.urdf", text(R"(
<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="c"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    <limit effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="b"/><child link="c"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="j1" multiplier="2"/></joint>
</robot>
)"));
    LoadReport report;
    loadScene(urdf, {}, &report);
    std::string all;
    for (const std::string& w : report.warnings)
    {
        all += w + "\n";
    }
    EXPECT_NE(all.find(urdf + ":6:5: warning: joint 'j1' has lower = upper = 0"), std::string::npos) << all;
    EXPECT_NE(all.find(urdf + ":8:58: warning: joint 'j2': <mimic> is not supported"), std::string::npos)
        << all;
}

TEST(UrdfJoints, AJointWhoseZeroIsOutsideItsLimitsStartsAtTheNearestLimit)
{
    TempDir dir;
    // A knee about y with limits [-2.7, -0.9] rad (as quadrupeds' knees are written): the shin
    // starts turned by -0.9 rad about y, its centre of mass (0, 0, -0.1) in its link frame at
    // R_y(-0.9) (0, 0, -0.1) = (0.1 sin 0.9, 0, -0.1 cos 0.9) from the knee; limits measured from there are
    // [-1.8, 0].
    const std::string urdf = dir.write("leg.urdf", text(R"(
<robot name="leg">
  <link name="world"/>
  <joint name="mount" type="fixed"><parent link="world"/><child link="thigh"/><origin xyz="0 0 1"/></joint>
  <link name="thigh"/>
  <joint name="knee" type="revolute"><parent link="thigh"/><child link="shin"/>
    <axis xyz="0 1 0"/><limit lower="-2.7" upper="-0.9" effort="1" velocity="1"/></joint>
  <link name="shin">
    <inertial><origin xyz="0 0 -0.1"/><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.001"/></inertial>
  </link>
</robot>
)"));
    LoadReport report;
    const core::Model model = loadScene(urdf, {}, &report);
    const int shin = model.findBody("shin");
    ASSERT_GE(shin, 0);
    const core::Vec3 expected(0.1 * std::sin(0.9), 0.0, 1.0 - 0.1 * std::cos(0.9));
    EXPECT_LT((model.bodies[static_cast<std::size_t>(shin)].position_W - expected).norm(), 1e-15);
    const core::Joint& knee = model.joints.at(0);
    EXPECT_DOUBLE_EQ(knee.initialPosition, -0.9);
    EXPECT_NEAR((*knee.limits)[0], -1.8, 1e-15);
    EXPECT_EQ((*knee.limits)[1], 0.0);
    ASSERT_FALSE(report.warnings.empty());
    EXPECT_NE(report.warnings[0].find(urdf + ":6:24: warning"), std::string::npos) << report.warnings[0];
    EXPECT_NE(
        report.warnings[0].find("joint 'knee': its zero position lies outside its limits [-2.7, -0.9] rad; "
                                "it starts at -0.9"),
        std::string::npos)
        << report.warnings[0];
}

TEST(UrdfJoints, NegativeDampingIsAnError)
{
    TempDir dir;
    const std::string urdf = dir.write("r.urdf", text(R"(
<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
    <dynamics damping="-1" friction="0"/></joint>
</robot>
)"));
    const InputError e = captureInputError([&] { loadScene(urdf); });
    EXPECT_INPUT_ERROR_AT(e, urdf, 5, 5, "joint 'j' has <dynamics damping=\"-1\" friction=\"0\">");
}

} // namespace
} // namespace frontier::io::test

namespace frontier::io::test
{
namespace
{
// A chain of `n` links on joints of `type` ("revolute" or "fixed"), each 0.1 m after its parent;
// the links are written in reverse order (the joints in chain order), so that the welded links'
// document order is the reverse of the walk from the root.
std::string longChainUrdf(int n, const std::string& type)
{
    std::string text = "<robot name=\"chain\">\n";
    for (int i = n - 1; i >= 0; --i)
    {
        text += "<link name=\"l" + std::to_string(i) +
                "\"><inertial><mass value=\"0.1\"/><inertia ixx=\"1e-5\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" "
                "iyz=\"0\" izz=\"1e-4\"/></inertial><collision><geometry><box size=\"0.08 0.02 0.02\"/>"
                "</geometry></collision></link>\n";
    }
    for (int i = 1; i < n; ++i)
    {
        text += "<joint name=\"j" + std::to_string(i) + "\" type=\"" + type + "\"><parent link=\"l" +
                std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
                "\"/><origin xyz=\"0.1 0 0\"/>" +
                (type == "fixed"
                     ? ""
                     : "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>") +
                "</joint>\n";
    }
    return text + "</robot>\n";
}

// A long chain loads whole (its cost is benchmarked in bench/load_scaling.sh): 2 000 links on
// revolute joints are 2 000 bodies; on fixed joints, one body with the 1 999 welded links listed
// in document order.
TEST(UrdfWelding, LongChainsLoadWithEveryLink)
{
    constexpr int n = 2000;
    TempDir dir;
    const core::Model revolute = loadScene(dir.write("revolute.urdf", longChainUrdf(n, "revolute")));
    EXPECT_EQ(revolute.bodies.size(), static_cast<std::size_t>(n) + 1); // and the floor
    EXPECT_EQ(revolute.joints.size(), static_cast<std::size_t>(n) - 1);

    LoadReport report;
    const core::Model fixed = loadScene(dir.write("fixed.urdf", longChainUrdf(n, "fixed")), {}, &report);
    ASSERT_EQ(fixed.bodies.size(), 2u);
    EXPECT_EQ(fixed.bodies[0].name, "l0");
    EXPECT_EQ(fixed.bodies[0].shapes.size(), static_cast<std::size_t>(n));
    EXPECT_NEAR(fixed.bodies[0].mass, 0.1 * n, 1e-9);
    ASSERT_EQ(report.robots.size(), 1u);
    ASSERT_EQ(report.robots[0].welded.size(), static_cast<std::size_t>(n) - 1);
    for (int k = 0; k < n - 1; ++k)
    {
        EXPECT_EQ(report.robots[0].welded[static_cast<std::size_t>(k)].first,
                  "l" + std::to_string(n - 1 - k));
    }
}

// Releasing urdfdom's model of a long chain used one nested call per link (a chain of 300 000
// links overflowed the 8 MB stack): loaded on a thread with a 256 KiB stack, a chain of 20 000
// links must not need more.
TEST(UrdfWelding, LongChainIsReleasedWithoutDeepRecursion)
{
    TempDir dir;
    const std::string path = dir.write("fixed.urdf", longChainUrdf(20000, "fixed"));
    struct Job
    {
        std::string path;
        std::size_t bodies = 0;
    } job{path};
    pthread_attr_t attr;
    ASSERT_EQ(pthread_attr_init(&attr), 0);
    ASSERT_EQ(pthread_attr_setstacksize(&attr, 256 * 1024), 0);
    pthread_t thread;
    ASSERT_EQ(pthread_create(
                  &thread, &attr,
                  [](void* arg) -> void*
                  {
                      Job& j = *static_cast<Job*>(arg);
                      j.bodies = loadScene(j.path).bodies.size();
                      return nullptr;
                  },
                  &job),
              0);
    pthread_join(thread, nullptr);
    pthread_attr_destroy(&attr);
    EXPECT_EQ(job.bodies, 2u);
}

} // namespace
} // namespace frontier::io::test
