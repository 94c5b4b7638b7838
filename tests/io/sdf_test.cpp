// tests/io/sdf_test.cpp: SDF models and worlds (io/sdf_model.cpp): Debian's dart-doc SDF files, and
// small files written here for each rule (pendulum period, resting box, welding, limits, universal
// joint, model:// includes, bad files).
#include "core/state.h"
#include "io/scene.h"
#include "io/sdf_model.h"
#include "io_test_util.h"
#include "run/simulation.h"
#include "tests/decompressed_copy.h"

#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::io::test
{
namespace
{

const std::string cDartSdf = "/usr/share/doc/dart/data/sdf";

#define SKIP_WITHOUT_SDF()                                                                                   \
    if (!detail::sdfSupported())                                                                             \
    {                                                                                                        \
        GTEST_SKIP() << "built without libsdformat";                                                         \
    }

// The InputError of loading `path` (fails the test when it loads).
InputError sdfLoadError(const std::string& path, const UrdfOptions& options = {})
{
    try
    {
        loadScene(path, options);
    }
    catch (const InputError& e)
    {
        return e;
    }
    ADD_FAILURE() << path << " loaded";
    return InputError(path, 0, 0, "");
}

int sdfBody(const core::Model& model, const std::string& name)
{
    const int index = model.findBody(name);
    EXPECT_GE(index, 0) << "no body " << name;
    return index;
}

// Runs `seconds`; every state finite, the joints held to 1e-6 m, and (passive models) the energy
// never above its start by more than energyTolerance of its scale.
void runChecked(const core::Model& model, double seconds, double energyTolerance, const std::string& what)
{
    run::Simulation simulation(model);
    const double e0 = core::totalEnergy(model, simulation.state());
    const bool passive = model.actuators.empty() && model.loads.empty();
    const long steps = std::lround(seconds / model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulation.step();
        for (const core::BodyState& b : simulation.state().bodies)
        {
            ASSERT_TRUE(b.position_W.allFinite() && b.velocity_W.allFinite() &&
                        b.angularVelocity_W.allFinite())
                << what << " at step " << k;
        }
        ASSERT_LE(simulation.simulator().jointErrors(simulation.state()).first, 1e-6)
            << what << " at step " << k;
        if (passive)
        {
            ASSERT_LE(core::totalEnergy(model, simulation.state()),
                      e0 + energyTolerance * std::max(1.0, std::abs(e0)))
                << what << " at step " << k;
        }
    }
}

TEST(SdfDartDoc, EveryFileRunsOrIsRefusedNamingWhatAndWhere)
{
    SKIP_WITHOUT_SDF();
    if (!std::filesystem::exists(cDartSdf))
    {
        GTEST_SKIP() << cDartSdf << " is missing (Debian's dart-doc)";
    }
    const TempDir dir;
    int loaded = 0;
    int refused = 0;
    for (const std::string& file : copyDecompressed(cDartSdf, dir.path()))
    {
        const std::string ext = std::filesystem::path(file).extension().string();
        if (ext != ".sdf" && ext != ".world" && ext != ".model")
        {
            continue;
        }
        const std::string path = dir.file(file);
        SCOPED_TRACE(path);
        try
        {
            core::Model model = loadScene(path);
            ++loaded;
            // RATTLE steps: Euler's (the default) let a passive pendulum's energy swing a few 1e-4
            // of itself about its start (docs/method.md §11).
            model.simulation.integrator = core::IntegratorKind::Rattle;
            runChecked(model, 2.0, 1e-6, path);
        }
        catch (const InputError& e)
        {
            ++refused;
            EXPECT_GT(e.line(), 0) << e.what();
            EXPECT_NE(e.message().find("does not support"), std::string::npos) << e.what();
        }
    }
    EXPECT_GE(loaded, 15);
    EXPECT_LE(refused, 1);
}

// A rod of mass m and length 2l hanging from a revolute joint at its top end, released at angle a0:
// the exact period of the physical pendulum, 4 sqrt(I/(m g d)) K(sin(a0/2)), d = l, I = m (2l)^2/3.
TEST(SdfFile, RevolutePendulumSwingsWithTheExactPeriod)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    const double a0 = 0.5;
    const std::string path = dir.write("pendulum.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="pendulum">
    <link name="rod">
      <pose>0 0 2 0 0 0</pose>
      <inertial><pose>0 0 -0.5 0 0 0</pose><mass>2</mass>
        <inertia><ixx>0.16666666666666666</ixx><iyy>0.16666666666666666</iyy><izz>1e-3</izz></inertia>
      </inertial>
    </link>
    <joint name="hinge" type="revolute">
      <parent>world</parent><child>rod</child>
      <pose>0 0 0 0 0 0</pose>
      <axis><xyz>1 0 0</xyz></axis>
    </joint>
  </model>
</sdf>
)"));
    core::Model model = loadScene(path);
    ASSERT_EQ(model.joints.size(), 1u);
    const int rod = sdfBody(model, "rod");
    EXPECT_NEAR(model.bodies[static_cast<std::size_t>(rod)].position_W.z(), 1.5, 1e-12);
    // Start at a0: the rod turned about the hinge at (0, 0, 2).
    core::Body& body = model.bodies[static_cast<std::size_t>(rod)];
    const core::Quat turn(Eigen::AngleAxisd(a0, core::Vec3::UnitX()));
    body.position_W = core::Vec3(0, 0, 2) + turn * (body.position_W - core::Vec3(0, 0, 2));
    body.orientation_WB = turn * body.orientation_WB;
    model.simulation.dt = 1e-4;
    model.simulation.integrator = core::IntegratorKind::Rattle4;
    run::Simulation simulation(model);
    // Time of the first return through the lowest point moving the same way: y crosses 0 upward
    // after the swing goes there and back (half periods at each crossing).
    double previous = simulation.state().bodies[static_cast<std::size_t>(rod)].position_W.y();
    std::vector<double> crossings;
    while (simulation.time() < 3.0 && crossings.size() < 3)
    {
        simulation.step();
        const double y = simulation.state().bodies[static_cast<std::size_t>(rod)].position_W.y();
        if ((previous < 0.0) != (y < 0.0))
        {
            crossings.push_back(simulation.time() - model.simulation.dt * y / (y - previous));
        }
        previous = y;
    }
    ASSERT_EQ(crossings.size(), 3u);
    const double g = 9.81;
    const double l = 0.5;
    const double inertiaAboutHinge = 1.0 / 6.0 + 2.0 * l * l;
    const double k = std::sin(a0 / 2.0);
    const double period = 4.0 * std::sqrt(inertiaAboutHinge / (2.0 * g * l)) * std::comp_ellint_1(k);
    EXPECT_NEAR(crossings[2] - crossings[0], period, 1e-4 * period);
}

TEST(SdfFile, BoxRestsOnTheWorldsGroundPlane)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    const std::string path = dir.write("box.world", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <world name="w">
    <gravity>0 0 -9.8</gravity>
    <model name="ground">
      <static>true</static>
      <link name="link">
        <collision name="c"><geometry><plane><normal>0 0 1</normal><size>10 10</size></plane></geometry>
          <surface><friction><ode><mu>0.8</mu></ode></friction></surface>
        </collision>
      </link>
    </model>
    <model name="box">
      <pose>0 0 0.25 0 0 0</pose>
      <link name="body">
        <inertial><mass>3</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.4 0.4 0.5</size></box></geometry></collision>
      </link>
    </model>
  </world>
</sdf>
)"));
    const core::Model model = loadScene(path);
    EXPECT_DOUBLE_EQ(model.simulation.gravity.z(), -9.8);
    const int ground = sdfBody(model, "ground::link");
    ASSERT_TRUE(model.bodies[static_cast<std::size_t>(ground)].isStatic);
    ASSERT_EQ(model.bodies[static_cast<std::size_t>(ground)].shapes.at(0).type, core::ShapeType::Plane);
    EXPECT_EQ(model.bodies[static_cast<std::size_t>(ground)].friction, 0.8);
    const int box = sdfBody(model, "box::body");
    run::Simulation simulation(model);
    simulation.step(1000);
    const core::BodyState& b = simulation.state().bodies[static_cast<std::size_t>(box)];
    EXPECT_GT(b.position_W.z(), 0.25 - 1e-4); // not into the plane
    EXPECT_LT(b.position_W.z(), 0.25 + 1e-6);
    // At rest, the vertical momentum no longer changes: over 1 s the contact impulse is m g t, so the
    // mean contact force is m g (to the contact tolerance's 3e-5 m/s x 3 kg over 1 s, 1e-4 N).
    const double vz = b.velocity_W.z();
    simulation.step(1000);
    const double force =
        3.0 * (simulation.state().bodies[static_cast<std::size_t>(box)].velocity_W.z() - vz) / 1.0 +
        3.0 * 9.8;
    EXPECT_NEAR(force, 3.0 * 9.8, 1e-3);
    EXPECT_GT(simulation.state().bodies[static_cast<std::size_t>(box)].position_W.z(), 0.25 - 1e-4);
}

TEST(SdfFile, FixedJointWeldsLinksIntoOneBodyWhoseMassesAdd)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    const std::string path = dir.write("welded.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="welded">
    <pose>0 0 1 0 0 0</pose>
    <link name="a">
      <inertial><mass>2</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
      <collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>
    </link>
    <link name="b">
      <pose>1 0 0 0 0 0</pose>
      <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
      <collision name="c"><geometry><cylinder><radius>0.1</radius><length>0.2</length></cylinder></geometry></collision>
    </link>
    <joint name="weld" type="fixed"><parent>a</parent><child>b</child></joint>
  </model>
</sdf>
)"));
    LoadReport report;
    const core::Model model = loadScene(path, {}, &report);
    ASSERT_EQ(model.bodies.size(), 2u); // the welded body and the floor
    EXPECT_EQ(model.bodies[0].name, "a");
    EXPECT_DOUBLE_EQ(model.bodies[0].mass, 3.0);
    EXPECT_NEAR(model.bodies[0].position_W.x(), 1.0 / 3.0, 1e-12);
    EXPECT_EQ(model.bodies[0].shapes.size(), 2u);
    EXPECT_TRUE(model.joints.empty());
    ASSERT_EQ(report.robots.size(), 1u);
    ASSERT_EQ(report.robots[0].welded.size(), 1u);
    EXPECT_EQ(report.robots[0].welded[0].first, "b");
    // A model alone is dropped onto a floor like a bare URDF: lowest point (the sphere) at z = 0.
    EXPECT_NEAR(model.bodies[0].position_W.z(), 0.1, 1e-12);
}

TEST(SdfFile, LimitsAreHeldAndAMissingInertialIsWarnedAbout)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    const std::string path = dir.write("limited.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="limited">
    <link name="base"/>
    <link name="arm">
      <pose>0.5 0 2 0 0 0</pose>
      <collision name="c"><geometry><box><size>1 0.1 0.1</size></box></geometry></collision>
    </link>
    <joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>
    <joint name="hinge" type="revolute">
      <parent>base</parent><child>arm</child>
      <pose>-0.5 0 0 0 0 0</pose>
      <axis><xyz>0 1 0</xyz><limit><lower>-0.3</lower><upper>0.2</upper><effort>5</effort></limit>
        <dynamics><damping>0.1</damping><friction>0.05</friction></dynamics></axis>
    </joint>
  </model>
</sdf>
)"));
    LoadReport report;
    const core::Model model = loadScene(path, {}, &report);
    ASSERT_EQ(model.joints.size(), 1u);
    const core::Joint& j = model.joints[0];
    ASSERT_TRUE(j.limits.has_value());
    EXPECT_DOUBLE_EQ((*j.limits)[0], -0.3);
    EXPECT_DOUBLE_EQ((*j.limits)[1], 0.2);
    EXPECT_DOUBLE_EQ(j.effortLimit, 5.0);
    EXPECT_DOUBLE_EQ(j.damping, 0.1);
    EXPECT_DOUBLE_EQ(j.friction, 0.05);
    EXPECT_NEAR(
        (model.bodies[static_cast<std::size_t>(j.child)].position_W + j.anchorChild - core::Vec3(0, 0, 2))
            .norm(),
        0.0, 1e-12); // anchored at the joint frame, 0.5 m from the arm's origin
    const int arm = sdfBody(model, "arm");
    EXPECT_DOUBLE_EQ(model.bodies[static_cast<std::size_t>(arm)].mass, 1.0); // SDF's default
    bool warned = false;
    for (const std::string& w : report.warnings)
    {
        warned = warned || (w.find("limited.sdf:5") != std::string::npos &&
                            w.find("no <inertial>") != std::string::npos);
    }
    EXPECT_TRUE(warned);
    // The arm falls about +y (gravity pulls its far end down: rotation +y lowers +x): the lower limit
    // holds it, at -0.3 rad, within the solver's tolerance.
    run::Simulation simulation(model);
    simulation.step(2000);
    const core::Quat q = simulation.state().bodies[static_cast<std::size_t>(arm)].orientation_WB;
    EXPECT_NEAR(Eigen::AngleAxisd(q).angle(), 0.2, 2e-3);
}

TEST(SdfFile, UniversalJointIsAnAngleJointWithItsTwoAxes)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    const std::string path = dir.write("universal.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="u">
    <link name="top"><pose>0 0 3 0 0 0</pose>
      <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial></link>
    <link name="bob"><pose>0.3 0.2 2 0 0 0</pose>
      <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial></link>
    <joint name="base" type="fixed"><parent>world</parent><child>top</child></joint>
    <joint name="cross" type="universal">
      <parent>top</parent><child>bob</child>
      <pose relative_to="top">0 0 0 0 0 0</pose>
      <axis><xyz>1 0 0</xyz></axis><axis2><xyz>0 1 0</xyz></axis2>
    </joint>
  </model>
</sdf>
)"));
    const core::Model model = loadScene(path);
    ASSERT_EQ(model.joints.size(), 1u);
    const core::Joint& j = model.joints[0];
    EXPECT_EQ(j.type, core::JointType::Angle);
    EXPECT_TRUE(j.perpParent1.isApprox(core::Vec3::UnitX()));
    EXPECT_TRUE(j.angleChildAxis.isApprox(core::Vec3::UnitY()));
    // The bob hangs off the cross: it swings about x and y but cannot spin about the link axis.
    run::Simulation simulation(model);
    simulation.step(1500);
    const core::BodyState& b = simulation.state().bodies[static_cast<std::size_t>(sdfBody(model, "bob"))];
    const core::Vec3 a1 = core::Vec3::UnitX();                 // fixed in the static top
    const core::Vec3 b2 = b.orientation_WB * j.angleChildAxis; // fixed in the bob
    EXPECT_NEAR(a1.dot(b2), 0.0, 1e-6);
    EXPECT_NEAR((b.position_W + b.orientation_WB * j.anchorChild - core::Vec3(0, 0, 3)).norm(), 0.0, 1e-6);
    EXPECT_GT(b.angularVelocity_W.norm(), 0.1); // it does swing
    runChecked(model, 1.0, 1e-3, path);
}

TEST(SdfFile, IncludesModelUrisThroughThePackagePath)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    std::filesystem::create_directories(dir.path() / "models" / "crate");
    dir.write("models/crate/model.config", text(R"(
<?xml version="1.0"?>
<model><name>crate</name><version>1.0</version><sdf version="1.7">model.sdf</sdf></model>
)"));
    dir.write("models/crate/model.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="crate">
    <link name="body"><pose>0 0 0.5 0 0 0</pose>
      <inertial><mass>4</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz></inertia></inertial>
      <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
    </link>
  </model>
</sdf>
)"));
    const std::string path = dir.write("yard.world", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <world name="yard">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://crate</uri><name>left</name><pose>-2 0 0 0 0 0</pose></include>
    <include><uri>model://crate</uri><name>right</name><pose>2 0 0 0 0 0</pose></include>
  </world>
</sdf>
)"));
    const InputError missing = sdfLoadError(path);
    EXPECT_EQ(missing.line(), 5) << missing.what();
    EXPECT_NE(missing.message().find("model://crate"), std::string::npos) << missing.what();
    EXPECT_NE(missing.message().find("--package-path"), std::string::npos) << missing.what();

    UrdfOptions options;
    options.packagePaths = {(dir.path() / "models").string()};
    LoadReport report;
    const core::Model model = loadScene(path, options, &report);
    const int left = sdfBody(model, "left::body");
    const int right = sdfBody(model, "right::body");
    EXPECT_TRUE(model.bodies[static_cast<std::size_t>(left)].position_W.isApprox(core::Vec3(-2, 0, 0.5)));
    EXPECT_TRUE(model.bodies[static_cast<std::size_t>(right)].position_W.isApprox(core::Vec3(2, 0, 0.5)));
    // Gazebo's ground_plane is not on the path: taken as Gazebo defines it, with a warning.
    const int ground = sdfBody(model, "ground_plane");
    EXPECT_TRUE(model.bodies[static_cast<std::size_t>(ground)].isStatic);
    EXPECT_EQ(model.bodies[static_cast<std::size_t>(ground)].shapes.at(0).type, core::ShapeType::Plane);
    ASSERT_FALSE(report.warnings.empty());
    EXPECT_NE(report.warnings[0].find("yard.world:4"), std::string::npos) << report.warnings[0];
    // The included file is among the run's inputs.
    bool recorded = false;
    for (const InputFile& f : report.inputFiles)
    {
        recorded = recorded || f.path.find("crate/model.sdf") != std::string::npos;
    }
    EXPECT_TRUE(recorded);
}

TEST(SdfFile, BadFilesAreInputErrorsWithFileAndLine)
{
    SKIP_WITHOUT_SDF();
    const TempDir dir;
    const InputError missing = sdfLoadError(dir.file("nothing.sdf"));
    EXPECT_NE(std::string(missing.what()).find("nothing.sdf"), std::string::npos) << missing.what();

    const std::string screw = dir.write("screw.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="m">
    <link name="a"><inertial><mass>1</mass></inertial></link>
    <link name="b"><inertial><mass>1</mass></inertial></link>
    <joint name="s" type="screw"><parent>a</parent><child>b</child><axis><xyz>0 0 1</xyz></axis></joint>
  </model>
</sdf>
)"));
    const InputError unsupported = sdfLoadError(screw);
    EXPECT_EQ(unsupported.file(), screw);
    EXPECT_EQ(unsupported.line(), 6) << unsupported.what();
    EXPECT_NE(unsupported.message().find("type screw"), std::string::npos) << unsupported.what();

    const std::string unknown = dir.write("unknown.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="m">
    <link name="a"><inertial><mass>1</mass></inertial></link>
    <link name="b"><inertial><mass>1</mass></inertial></link>
    <joint name="s" type="hinge"><parent>a</parent><child>b</child></joint>
  </model>
</sdf>
)"));
    const InputError typo = sdfLoadError(unknown);
    EXPECT_EQ(typo.line(), 6) << typo.what();

    const std::string malformed = dir.write("malformed.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="m">
    <link name="a">
  </model>
</sdf>
)"));
    const InputError xml = sdfLoadError(malformed);
    EXPECT_EQ(xml.file(), malformed);
    EXPECT_GT(xml.line(), 0) << xml.what();

    const std::string empty =
        dir.write("empty.world", "<?xml version=\"1.0\"?>\n<sdf version=\"1.7\"><world name=\"w\"/></sdf>\n");
    EXPECT_NE(sdfLoadError(empty).message().find("no links"), std::string::npos);

    const std::string moving = dir.write("plane.sdf", text(R"(
<?xml version="1.0"?>
<sdf version="1.7">
  <model name="m">
    <link name="a"><inertial><mass>1</mass></inertial>
      <collision name="c"><geometry><plane><normal>0 0 1</normal></plane></geometry></collision>
    </link>
  </model>
</sdf>
)"));
    const InputError plane = sdfLoadError(moving);
    EXPECT_EQ(plane.line(), 5) << plane.what();
    EXPECT_NE(plane.message().find("static"), std::string::npos) << plane.what();
}

TEST(SdfFile, WithoutLibsdformatTheErrorNamesThePackage)
{
    if (detail::sdfSupported())
    {
        GTEST_SKIP() << "built with libsdformat";
    }
    const TempDir dir;
    const std::string path = dir.write("m.sdf", "<sdf version=\"1.7\"><model name=\"m\"/></sdf>\n");
    const InputError e = sdfLoadError(path);
    EXPECT_NE(e.message().find("no SDF support"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("libsdformat-dev"), std::string::npos) << e.what();
}

} // namespace
} // namespace frontier::io::test
