// tests/io/mjcf_test.cpp: MJCF files (MuJoCo's format) read as MuJoCo means them. Each test writes
// a small model, loads it as every command does, and checks the bodies, joints and actuators
// against values worked out by hand here (textbook formulas, rotations written out): defaults and
// classes, includes, angle units, fromto, inertia from geoms, welded bodies, actuators, joint
// springs, keyframes, contact filters, autolimits, unsupported elements, and three runs (boxes that
// stack or pass through each other by their contact bits, a sphere resting on a plane, a hinge
// pendulum's period). Bad files are InputErrors naming the file and line.
#include "core/state.h"
#include "io_test_util.h"
#include "run/names.h"
#include "run/run_loop.h"
#include "run/scene_loading.h"
#include "run/simulation.h"
#include "tests/decompressed_copy.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace frontier::io::test
{
namespace
{

using core::Mat3;
using core::Vec3;

constexpr double cPi = std::numbers::pi;

// Mass (kg) and central moments of inertia (kg m^2) of solids of density rho (kg/m^3).
double sphereMass(double rho, double r)
{
    return rho * 4.0 / 3.0 * cPi * r * r * r;
}
double sphereMoment(double mass, double r)
{
    return 0.4 * mass * r * r;
}
// A box of full sides a, b, c: mass and the diagonal of its inertia about its centre.
double boxMass(double rho, double a, double b, double c)
{
    return rho * a * b * c;
}
Vec3 boxMoments(double mass, double a, double b, double c)
{
    return mass / 12.0 * Vec3(b * b + c * c, a * a + c * c, a * a + b * b);
}

// Rotation by `angle` (rad) about z and about y, written out.
Mat3 rotationZ(double angle)
{
    Mat3 r;
    r << std::cos(angle), -std::sin(angle), 0.0, std::sin(angle), std::cos(angle), 0.0, 0.0, 0.0, 1.0;
    return r;
}

struct MjcfLoad
{
    core::Model model;
    LoadReport report;
};

// Writes `text` as NAME in the test's folder and loads it as `frontier run NAME` does.
MjcfLoad mjcfLoad(const TempDir& dir, const std::string& name, const std::string& text,
                  const UrdfOptions& options = {})
{
    MjcfLoad loaded;
    loaded.model = loadScene(dir.write(name, text), options, &loaded.report);
    return loaded;
}

const core::Body& mjcfBody(const core::Model& model, const std::string& name)
{
    const int index = model.findBody(name);
    if (index < 0)
    {
        ADD_FAILURE() << "no body '" << name << "'";
        static const core::Body none;
        return none;
    }
    return model.bodies[static_cast<std::size_t>(index)];
}

const core::Joint& mjcfJoint(const core::Model& model, const std::string& name)
{
    return model.joints[static_cast<std::size_t>(run::jointIndex(model, name))];
}

// A body's inertia about its centre of mass in world axes (independent of the body frame chosen).
Mat3 worldInertia(const core::Body& body)
{
    const Mat3 r = body.orientation_WB.toRotationMatrix();
    return r * body.inertia_B * r.transpose();
}

// A shape's pose in the world at the model's initial pose.
Vec3 shapePosition_W(const core::Body& body, const core::Shape& shape)
{
    return body.position_W + body.orientation_WB * shape.position_BS;
}
Mat3 shapeRotation_W(const core::Body& body, const core::Shape& shape)
{
    return (body.orientation_WB * shape.rotation_BS).toRotationMatrix();
}

bool hasWarning(const LoadReport& report, const std::string& needle)
{
    return std::any_of(report.warnings.begin(), report.warnings.end(),
                       [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

std::string allWarnings(const LoadReport& report)
{
    std::string all;
    for (const std::string& w : report.warnings)
    {
        all += w + "\n";
    }
    return all;
}

bool ignoresPair(const core::Model& model, const std::string& a, const std::string& b)
{
    const int i = model.findBody(a);
    const int j = model.findBody(b);
    EXPECT_GE(i, 0) << a;
    EXPECT_GE(j, 0) << b;
    return std::any_of(model.contact.ignore.begin(), model.contact.ignore.end(),
                       [&](const std::array<int, 2>& p)
                       { return (p[0] == i && p[1] == j) || (p[0] == j && p[1] == i); });
}

#define EXPECT_VEC_NEAR(actual, expected, tolerance)                                                         \
    EXPECT_LE(((actual) - (expected)).norm(), (tolerance))                                                   \
        << "actual " << (actual).transpose() << "\nexpected " << (expected).transpose()
#define EXPECT_MAT_NEAR(actual, expected, tolerance)                                                         \
    EXPECT_LE(((actual) - (expected)).norm(), (tolerance)) << "actual\n"                                     \
                                                           << (actual) << "\nexpected\n"                     \
                                                           << (expected)

// ---------------------------------------------------------------------------------------------
// What the compiler makes of the file

TEST(Mjcf, DefaultClassesChildclassAndNestedDefaults)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "classes.xml", R"(<mujoco>
  <default>
    <geom type="sphere" size="0.1" density="1000"/>
    <default class="big">
      <geom size="0.2"/>
      <default class="slab">
        <geom type="box" size="0.1 0.2 0.3"/>
      </default>
    </default>
    <default class="stiff">
      <joint damping="7"/>
    </default>
  </default>
  <worldbody>
    <body name="plain" pos="0 0 1">
      <freejoint/>
      <geom/>
    </body>
    <body name="bigball" pos="1 0 1" childclass="big">
      <freejoint/>
      <geom/>
      <body name="slab" pos="0 0 -0.6">
        <joint name="damped" type="hinge" axis="0 1 0" class="stiff"/>
        <geom class="slab"/>
        <body name="inner" pos="0 0 -0.6">
          <joint name="free_swing" type="hinge" axis="0 1 0"/>
          <geom/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Model& model = loaded.model;
    // The main default: a sphere of 0.1 m.
    const core::Body& plain = mjcfBody(model, "plain");
    ASSERT_EQ(plain.shapes.size(), 1u);
    EXPECT_EQ(plain.shapes[0].type, core::ShapeType::Sphere);
    EXPECT_DOUBLE_EQ(plain.shapes[0].radius, 0.1);
    EXPECT_NEAR(plain.mass, sphereMass(1000.0, 0.1), 1e-9);
    // childclass "big": its size, the main default's type and density.
    const core::Body& big = mjcfBody(model, "bigball");
    ASSERT_EQ(big.shapes.size(), 1u);
    EXPECT_EQ(big.shapes[0].type, core::ShapeType::Sphere);
    EXPECT_DOUBLE_EQ(big.shapes[0].radius, 0.2);
    EXPECT_NEAR(big.mass, sphereMass(1000.0, 0.2), 1e-9);
    // class "slab", nested in "big": a box of half sizes 0.1 0.2 0.3, density inherited from the top.
    const core::Body& slab = mjcfBody(model, "slab");
    ASSERT_EQ(slab.shapes.size(), 1u);
    EXPECT_EQ(slab.shapes[0].type, core::ShapeType::Box);
    EXPECT_VEC_NEAR(slab.shapes[0].size, Vec3(0.2, 0.4, 0.6), 1e-12);
    EXPECT_NEAR(slab.mass, boxMass(1000.0, 0.2, 0.4, 0.6), 1e-9);
    // The joint's own class wins over the body's childclass; a joint of the childclass ("big",
    // which says nothing of joints) has the main default's damping, 0.
    EXPECT_DOUBLE_EQ(mjcfJoint(model, "damped").damping, 7.0);
    EXPECT_DOUBLE_EQ(mjcfJoint(model, "free_swing").damping, 0.0);
    // The childclass reaches the nested body's geom: a 0.2 m sphere.
    const core::Body& inner = mjcfBody(model, "inner");
    ASSERT_EQ(inner.shapes.size(), 1u);
    EXPECT_DOUBLE_EQ(inner.shapes[0].radius, 0.2);
}

TEST(Mjcf, IncludedFilesBringTheirDefaultsAndBodies)
{
    const TempDir dir;
    std::filesystem::create_directories(dir.path() / "parts");
    dir.write("parts/looks.xml", R"(<mujoco>
  <default>
    <default class="heavy">
      <geom type="box" size="0.05 0.05 0.05" density="8000"/>
    </default>
  </default>
</mujoco>
)");
    dir.write("parts/arm.xml", R"(<mujoco>
  <body name="weight" pos="0 0 1">
    <joint name="hook" type="slide" axis="0 0 1"/>
    <geom class="heavy"/>
  </body>
</mujoco>
)");
    const MjcfLoad loaded = mjcfLoad(dir, "main.xml", R"(<mujoco>
  <include file="parts/looks.xml"/>
  <worldbody>
    <include file="parts/arm.xml"/>
  </worldbody>
</mujoco>
)");
    const core::Body& weight = mjcfBody(loaded.model, "weight");
    ASSERT_EQ(weight.shapes.size(), 1u);
    EXPECT_EQ(weight.shapes[0].type, core::ShapeType::Box);
    EXPECT_VEC_NEAR(weight.shapes[0].size, Vec3(0.1, 0.1, 0.1), 1e-12);
    EXPECT_NEAR(weight.mass, 8000.0 * 0.001, 1e-9);
    EXPECT_VEC_NEAR(weight.position_W, Vec3(0.0, 0.0, 1.0), 1e-12);
    EXPECT_EQ(mjcfJoint(loaded.model, "hook").type, core::JointType::Prismatic);
}

// The same arm in degrees (MuJoCo's default) and in radians: a hinge's range and the body's euler
// angles, the body turned about z and its box 0.5 m out along the body's x.
TEST(Mjcf, AnglesAreDegreesByDefaultAndRadiansWhenAsked)
{
    const auto arm = [](const std::string& compiler, const std::string& euler, const std::string& range)
    {
        return "<mujoco>\n  " + compiler + "\n  <worldbody>\n    <body name=\"arm\" pos=\"0 0 1\" euler=\"" +
               euler + "\">\n      <joint name=\"j\" type=\"hinge\" axis=\"0 1 0\" range=\"" + range +
               "\"/>\n      <geom type=\"box\" size=\"0.1 0.2 0.3\" pos=\"0.5 0 0\"/>\n    </body>\n  "
               "</worldbody>\n</mujoco>\n";
    };
    const TempDir dir;
    struct Case
    {
        std::string file;
        double turn; // rad about z
        double low;  // rad
        double high; // rad
    };
    const std::vector<std::pair<Case, std::string>> cases = {
        {{"degrees.xml", cPi / 2.0, -cPi / 2.0, cPi / 4.0}, arm("", "0 0 90", "-90 45")},
        {{"degrees_said.xml", cPi / 2.0, -cPi / 2.0, cPi / 4.0},
         arm("<compiler angle=\"degree\"/>", "0 0 90", "-90 45")},
        {{"radians.xml", 0.5, -1.0, 0.5}, arm("<compiler angle=\"radian\"/>", "0 0 0.5", "-1 0.5")},
    };
    for (const auto& [c, text] : cases)
    {
        SCOPED_TRACE(c.file);
        const MjcfLoad loaded = mjcfLoad(dir, c.file, text);
        const core::Body& body = mjcfBody(loaded.model, "arm");
        ASSERT_EQ(body.shapes.size(), 1u);
        const Mat3 turn = rotationZ(c.turn);
        EXPECT_MAT_NEAR(shapeRotation_W(body, body.shapes[0]), turn, 1e-9);
        EXPECT_VEC_NEAR(shapePosition_W(body, body.shapes[0]),
                        Vec3(0.5 * std::cos(c.turn), 0.5 * std::sin(c.turn), 1.0), 1e-9);
        const core::Joint& joint = mjcfJoint(loaded.model, "j");
        // The hinge axis, body y, turned with the body.
        EXPECT_VEC_NEAR(joint.axisParent, turn * Vec3::UnitY(), 1e-9);
        ASSERT_TRUE(joint.limits.has_value());
        EXPECT_NEAR((*joint.limits)[0], c.low, 1e-9);
        EXPECT_NEAR((*joint.limits)[1], c.high, 1e-9);
    }
}

TEST(Mjcf, FromtoCapsuleHasItsRadiusLengthAndPose)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "capsule.xml", R"(<mujoco>
  <worldbody>
    <body name="rod" pos="0 0 1">
      <freejoint/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0.4" size="0.05"/>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Body& rod = mjcfBody(loaded.model, "rod");
    ASSERT_EQ(rod.shapes.size(), 1u);
    const core::Shape& capsule = rod.shapes[0];
    EXPECT_EQ(capsule.type, core::ShapeType::Capsule);
    EXPECT_DOUBLE_EQ(capsule.radius, 0.05);
    EXPECT_NEAR(capsule.length, 0.5, 1e-12); // |(0.3, 0, 0.4)|
    EXPECT_VEC_NEAR(shapePosition_W(rod, capsule), Vec3(0.15, 0.0, 1.2), 1e-12);
    // The capsule's axis (its local z) along the segment, either way.
    const Vec3 axis = shapeRotation_W(rod, capsule).col(2);
    EXPECT_NEAR(std::abs(axis.dot(Vec3(0.6, 0.0, 0.8))), 1.0, 1e-12) << axis.transpose();
    // MuJoCo's default density, 1000 kg/m^3: a cylinder and two half spheres.
    const double volume = cPi * 0.05 * 0.05 * 0.5 + 4.0 / 3.0 * cPi * 0.05 * 0.05 * 0.05;
    EXPECT_NEAR(rod.mass, 1000.0 * volume, 1e-9);
    EXPECT_VEC_NEAR(rod.position_W, Vec3(0.15, 0.0, 1.2), 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Mass and inertia

TEST(Mjcf, InertiaFromGeomsIsDensityTimesVolumeAndTheTextbookMoments)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "solids.xml", R"(<mujoco>
  <worldbody>
    <body name="box" pos="0 0 1">
      <freejoint/>
      <geom type="box" size="0.1 0.2 0.3" density="500"/>
    </body>
    <body name="ball" pos="1 0 1">
      <freejoint/>
      <geom type="sphere" size="0.1" density="2000"/>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Body& box = mjcfBody(loaded.model, "box");
    const double boxM = boxMass(500.0, 0.2, 0.4, 0.6); // 24 kg
    EXPECT_NEAR(box.mass, boxM, 1e-9);
    EXPECT_MAT_NEAR(worldInertia(box), Mat3(boxMoments(boxM, 0.2, 0.4, 0.6).asDiagonal()), 1e-9);
    EXPECT_VEC_NEAR(box.position_W, Vec3(0.0, 0.0, 1.0), 1e-12);
    const core::Body& ball = mjcfBody(loaded.model, "ball");
    const double ballM = sphereMass(2000.0, 0.1);
    EXPECT_NEAR(ball.mass, ballM, 1e-9);
    EXPECT_MAT_NEAR(worldInertia(ball), sphereMoment(ballM, 0.1) * Mat3::Identity(), 1e-9);
}

TEST(Mjcf, TwoGeomsInOneBodyAddByTheParallelAxisTheorem)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "dumbbell.xml", R"(<mujoco>
  <worldbody>
    <body name="dumbbell" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.1" density="1000"/>
      <geom type="box" size="0.1 0.1 0.1" pos="0.5 0 0" density="1000"/>
    </body>
  </worldbody>
</mujoco>
)");
    const double m1 = sphereMass(1000.0, 0.1);
    const double i1 = sphereMoment(m1, 0.1);
    const double m2 = boxMass(1000.0, 0.2, 0.2, 0.2); // 8 kg
    const double i2 = boxMoments(m2, 0.2, 0.2, 0.2).x();
    const double m = m1 + m2;
    const double c = m2 * 0.5 / m; // m along x from the sphere
    const double across = i1 + m1 * c * c + i2 + m2 * (0.5 - c) * (0.5 - c);
    const core::Body& body = mjcfBody(loaded.model, "dumbbell");
    EXPECT_NEAR(body.mass, m, 1e-9);
    EXPECT_VEC_NEAR(body.position_W, Vec3(c, 0.0, 1.0), 1e-12);
    EXPECT_MAT_NEAR(worldInertia(body), Mat3(Vec3(i1 + i2, across, across).asDiagonal()), 1e-9);
}

TEST(Mjcf, ExplicitInertialWinsOverTheGeoms)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "inertial.xml", R"(<mujoco>
  <worldbody>
    <body name="given" pos="0 0 1">
      <freejoint/>
      <inertial pos="0 0 0.1" mass="3" diaginertia="0.1 0.2 0.3"/>
      <geom type="box" size="0.1 0.2 0.3" density="500"/>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Body& body = mjcfBody(loaded.model, "given");
    EXPECT_DOUBLE_EQ(body.mass, 3.0);
    EXPECT_VEC_NEAR(body.position_W, Vec3(0.0, 0.0, 1.1), 1e-12);
    EXPECT_MAT_NEAR(worldInertia(body), Mat3(Vec3(0.1, 0.2, 0.3).asDiagonal()), 1e-12);
}

// MuJoCo adds a joint's armature to its joint-space inertia; Frontier gives the body it moves a thin
// disc spinning on the axis: the armature about the axis, half of it about every axis across.
TEST(Mjcf, HingeArmatureIsADiscSpinningOnTheAxis)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "rotor.xml", R"(<mujoco>
  <worldbody>
    <body name="link" pos="0 0 1">
      <joint name="spin" type="hinge" axis="0 0 1" armature="0.5"/>
      <inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.01"/>
      <geom type="sphere" size="0.1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>
)");
    EXPECT_MAT_NEAR(worldInertia(mjcfBody(loaded.model, "link")), Mat3(Vec3(0.26, 0.26, 0.51).asDiagonal()),
                    1e-12);
}

// ---------------------------------------------------------------------------------------------
// Bodies and joints

TEST(Mjcf, BodyWithoutJointIsWeldedIntoItsParent)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "welded.xml", R"(<mujoco>
  <worldbody>
    <body name="upper" pos="0 0 1">
      <joint name="swing" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.1" density="1000"/>
      <body name="lower" pos="0 0 -0.5">
        <geom type="sphere" size="0.1" density="2000"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Model& model = loaded.model;
    EXPECT_LT(model.findBody("lower"), 0);
    const double m1 = sphereMass(1000.0, 0.1);
    const double m2 = sphereMass(2000.0, 0.1);
    const core::Body& upper = mjcfBody(model, "upper");
    EXPECT_NEAR(upper.mass, m1 + m2, 1e-9);
    EXPECT_VEC_NEAR(upper.position_W, Vec3(0.0, 0.0, (m1 * 1.0 + m2 * 0.5) / (m1 + m2)), 1e-12);
    EXPECT_EQ(upper.shapes.size(), 2u);
    ASSERT_EQ(loaded.report.robots.size(), 1u);
    const auto& welded = loaded.report.robots[0].welded;
    ASSERT_EQ(welded.size(), 1u);
    EXPECT_EQ(welded[0].first, "lower");
    EXPECT_EQ(welded[0].second, "upper");
}

TEST(Mjcf, BodyWithoutJointUnderTheWorldIsPartOfTheStaticBody)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "table.xml", R"(<mujoco>
  <worldbody>
    <body name="table" pos="0 0 0.5">
      <geom type="box" size="0.5 0.5 0.05"/>
    </body>
    <body name="ball" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.1"/>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Model& model = loaded.model;
    EXPECT_LT(model.findBody("table"), 0);
    const core::Body& world = mjcfBody(model, "world");
    EXPECT_TRUE(world.isStatic);
    ASSERT_EQ(world.shapes.size(), 1u);
    EXPECT_EQ(world.shapes[0].type, core::ShapeType::Box);
    EXPECT_VEC_NEAR(shapePosition_W(world, world.shapes[0]), Vec3(0.0, 0.0, 0.5), 1e-12);
    EXPECT_FALSE(mjcfBody(model, "ball").isStatic);
    ASSERT_EQ(loaded.report.robots.size(), 1u);
    const auto& welded = loaded.report.robots[0].welded;
    ASSERT_EQ(welded.size(), 1u);
    EXPECT_EQ(welded[0].first, "table");
    EXPECT_EQ(welded[0].second, "world");
}

TEST(Mjcf, TwoHingesInOneBodyBecomeAChainOfFramesCarryingTheBodysMass)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "gimbal.xml", R"(<mujoco>
  <worldbody>
    <body name="head" pos="0 0 1">
      <joint name="pan" type="hinge" axis="0 0 1"/>
      <joint name="tilt" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.1" pos="0.2 0 0" density="1000"/>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Model& model = loaded.model;
    double mass = 0.0;
    for (const core::Body& body : model.bodies)
    {
        mass += body.isStatic ? 0.0 : body.mass;
    }
    EXPECT_NEAR(mass, sphereMass(1000.0, 0.1), 1e-12);
    ASSERT_EQ(model.joints.size(), 2u);
    const core::Joint& pan = mjcfJoint(model, "pan");
    const core::Joint& tilt = mjcfJoint(model, "tilt");
    EXPECT_EQ(pan.parent, core::cWorld);
    EXPECT_EQ(tilt.parent, pan.child);
    EXPECT_EQ(tilt.child, model.findBody("head"));
    EXPECT_NE(pan.child, tilt.child);
    // Both about the body's origin, on their axes.
    EXPECT_VEC_NEAR(pan.anchorParent, Vec3(0.0, 0.0, 1.0), 1e-12);
    EXPECT_VEC_NEAR(pan.axisParent, Vec3::UnitZ(), 1e-12);
}

TEST(Mjcf, RangeWithoutLimitedIsALimitAsInCurrentMuJoCo)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "autolimits.xml", R"(<mujoco>
  <compiler angle="radian"/>
  <worldbody>
    <body name="a" pos="0 0 1">
      <joint name="ranged" type="hinge" axis="0 1 0" range="-1 0.5"/>
      <geom type="sphere" size="0.1"/>
      <body name="b" pos="0.5 0 0">
        <joint name="unlimited" type="hinge" axis="0 1 0" range="-1 0.5" limited="false"/>
        <geom type="sphere" size="0.1"/>
        <body name="c" pos="0.5 0 0">
          <joint name="slide" type="slide" axis="1 0 0" range="-0.2 0.3"/>
          <geom type="sphere" size="0.1"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Joint& ranged = mjcfJoint(loaded.model, "ranged");
    ASSERT_TRUE(ranged.limits.has_value());
    EXPECT_DOUBLE_EQ((*ranged.limits)[0], -1.0);
    EXPECT_DOUBLE_EQ((*ranged.limits)[1], 0.5);
    EXPECT_FALSE(mjcfJoint(loaded.model, "unlimited").limits.has_value());
    const core::Joint& slide = mjcfJoint(loaded.model, "slide");
    ASSERT_TRUE(slide.limits.has_value());
    EXPECT_DOUBLE_EQ((*slide.limits)[0], -0.2);
    EXPECT_DOUBLE_EQ((*slide.limits)[1], 0.3);
}

// ---------------------------------------------------------------------------------------------
// Actuators and springs

const char* const cDrivenArm = R"(<mujoco>
  <compiler angle="radian"/>
  <worldbody>
    <body name="a" pos="0 0 1">
      <joint name="shoulder" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.1"/>
      <body name="b" pos="0.5 0 0">
        <joint name="elbow" type="hinge" axis="0 1 0"/>
        <geom type="sphere" size="0.1"/>
        <body name="c" pos="0.5 0 0">
          <joint name="extend" type="slide" axis="1 0 0"/>
          <geom type="sphere" size="0.1"/>
          <body name="d" pos="0.5 0 0">
            <joint name="wrist" type="hinge" axis="0 1 0"/>
            <geom type="sphere" size="0.1"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor joint="shoulder" gear="50" ctrlrange="-1 1"/>
    <position joint="elbow" kp="10" gear="2"/>
    <velocity joint="extend" kv="3" gear="2"/>
    <motor joint="wrist" gear="50" ctrlrange="-1 1" forcerange="-2 2"/>
  </actuator>
  <keyframe>
    <key name="moving" ctrl="0.5 0.6 0.8 0.1"/>
  </keyframe>
</mujoco>
)";

const core::Actuator& actuatorOn(const core::Model& model, const std::string& joint)
{
    return model.actuators[static_cast<std::size_t>(run::actuatorIndex(model, joint))];
}

TEST(Mjcf, ActuatorsBecomeEffortActuatorsAndServosWithTheGearFoldedIn)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "driven.xml", cDrivenArm);
    const core::Model& model = loaded.model;
    ASSERT_EQ(model.actuators.size(), 4u);
    // motor, gear 50, ctrlrange [-1, 1]: a torque of 50 ctrl, at most 50 N m.
    const core::Actuator& motor = actuatorOn(model, "shoulder");
    EXPECT_EQ(motor.kind, core::ActuatorKind::Effort);
    EXPECT_DOUBLE_EQ(motor.effortLimit, 50.0);
    EXPECT_DOUBLE_EQ(motor.target.constant, 0.0);
    // position, kp 10, gear 2: the force kp (ctrl - 2 q) on a gear of 2 is a servo of 4 kp to ctrl / 2.
    const core::Actuator& servo = actuatorOn(model, "elbow");
    EXPECT_EQ(servo.kind, core::ActuatorKind::Position);
    EXPECT_DOUBLE_EQ(servo.kp, 40.0);
    // velocity, kv 3, gear 2: damping 4 kv towards ctrl / 2.
    const core::Actuator& velocity = actuatorOn(model, "extend");
    EXPECT_EQ(velocity.kind, core::ActuatorKind::Velocity);
    EXPECT_EQ(velocity.coordinate, core::JointCoordinate::Slide);
    EXPECT_DOUBLE_EQ(velocity.kd, 12.0);
    // forcerange [-2, 2] on a gear of 50 limits the torque to 100 N m, ctrlrange to 50: 50 holds.
    EXPECT_DOUBLE_EQ(actuatorOn(model, "wrist").effortLimit, 50.0);

    // A keyframe's ctrl: the targets in joint units.
    UrdfOptions options;
    options.keyframe = "moving";
    const MjcfLoad moving = mjcfLoad(dir, "driven.xml", cDrivenArm, options);
    EXPECT_DOUBLE_EQ(actuatorOn(moving.model, "shoulder").target.constant, 25.0); // N m
    EXPECT_DOUBLE_EQ(actuatorOn(moving.model, "elbow").target.constant, 0.3);     // rad
    EXPECT_DOUBLE_EQ(actuatorOn(moving.model, "extend").target.constant, 0.4);    // m/s
    EXPECT_DOUBLE_EQ(actuatorOn(moving.model, "wrist").target.constant, 5.0);     // N m
}

TEST(Mjcf, JointStiffnessIsAServoTowardsSpringref)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "springs.xml", R"(<mujoco>
  <worldbody>
    <body name="a" pos="0 0 1">
      <joint name="twist" type="hinge" axis="0 0 1" stiffness="20" springref="30"/>
      <geom type="sphere" size="0.1"/>
      <body name="b" pos="0.5 0 0">
        <joint name="plunger" type="slide" axis="1 0 0" stiffness="100" springref="0.2"/>
        <geom type="sphere" size="0.1"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Model& model = loaded.model;
    ASSERT_EQ(model.actuators.size(), 2u);
    const core::Actuator& twist = actuatorOn(model, "twist");
    EXPECT_EQ(twist.kind, core::ActuatorKind::Position);
    EXPECT_DOUBLE_EQ(twist.kp, 20.0);
    EXPECT_NEAR(twist.target.constant, cPi / 6.0, 1e-12); // springref in degrees, as the file's angles
    const core::Actuator& plunger = actuatorOn(model, "plunger");
    EXPECT_EQ(plunger.kind, core::ActuatorKind::Position);
    EXPECT_EQ(plunger.coordinate, core::JointCoordinate::Slide);
    EXPECT_DOUBLE_EQ(plunger.kp, 100.0);
    EXPECT_DOUBLE_EQ(plunger.target.constant, 0.2);
}

// ---------------------------------------------------------------------------------------------
// Keyframes

const char* const cKeyedPendulum = R"(<mujoco>
  <compiler angle="radian"/>
  <worldbody>
    <body name="arm" pos="0 0 1">
      <joint name="pivot" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.05" pos="0.5 0 0"/>
    </body>
  </worldbody>
  <keyframe>
    <key name="home" qpos="0"/>
    <key name="tilted" qpos="0.5"/>
  </keyframe>
</mujoco>
)";

TEST(Mjcf, KeyframeQposIsTheStartingPose)
{
    const TempDir dir;
    UrdfOptions options;
    options.keyframe = "tilted";
    const MjcfLoad loaded = mjcfLoad(dir, "keyed.xml", cKeyedPendulum, options);
    const core::Model& model = loaded.model;
    // A rotation of 0.5 rad about y takes (0.5, 0, 0) to (0.5 cos 0.5, 0, -0.5 sin 0.5).
    EXPECT_VEC_NEAR(mjcfBody(model, "arm").position_W,
                    Vec3(0.5 * std::cos(0.5), 0.0, 1.0 - 0.5 * std::sin(0.5)), 1e-12);
    EXPECT_DOUBLE_EQ(mjcfJoint(model, "pivot").initialPosition, 0.5);
    EXPECT_NEAR(run::jointPosition(model, core::initialState(model), "pivot"), 0.5, 1e-12);
    // Without a keyframe: MuJoCo's reference pose.
    const MjcfLoad home = mjcfLoad(dir, "keyed.xml", cKeyedPendulum);
    EXPECT_VEC_NEAR(mjcfBody(home.model, "arm").position_W, Vec3(0.5, 0.0, 1.0), 1e-12);
}

TEST(Mjcf, UnknownKeyframeIsAnInputErrorNamingTheKnownOnes)
{
    const TempDir dir;
    const std::string path = dir.write("keyed.xml", cKeyedPendulum);
    UrdfOptions options;
    options.keyframe = "standing";
    const InputError e = captureInputError([&] { loadScene(path, options); });
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.message().find("no keyframe 'standing'"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("home"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("tilted"), std::string::npos) << e.what();
}

TEST(Mjcf, FreeBodyKeyframeQvelIsItsStartingVelocity)
{
    const TempDir dir;
    // Turned 90 degrees about z, its centre of mass 0.1 m along its own x (world y).
    UrdfOptions options;
    options.keyframe = "thrown";
    const MjcfLoad loaded = mjcfLoad(dir, "thrown.xml", R"(<mujoco>
  <worldbody>
    <body name="stone" pos="0 0 1" euler="0 0 90">
      <freejoint/>
      <geom type="sphere" size="0.05" pos="0.1 0 0"/>
    </body>
  </worldbody>
  <keyframe>
    <key name="thrown" qpos="0 0 1 0.7071067811865476 0 0 0.7071067811865476" qvel="1 2 3 4 0 5"/>
  </keyframe>
</mujoco>
)",
                                     options);
    const core::Body& stone = mjcfBody(loaded.model, "stone");
    // qvel of a free joint: the body origin's velocity (world axes), then the angular velocity in
    // the body's axes: (4, 0, 5) turned 90 degrees about z is (0, 4, 5).
    const Vec3 omega(0.0, 4.0, 5.0);
    const Vec3 offset(0.0, 0.1, 0.0); // centre of mass from the body origin, world axes
    EXPECT_VEC_NEAR(stone.position_W, Vec3(0.0, 0.1, 1.0), 1e-12);
    EXPECT_VEC_NEAR(stone.angularVelocity_W, omega, 1e-12);
    EXPECT_VEC_NEAR(stone.velocity_W, Vec3(1.0, 2.0, 3.0) + omega.cross(offset), 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Contacts

const char* const cContactBits = R"(<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1" contype="3" conaffinity="3"/>
    <body name="a" pos="0 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" contype="1" conaffinity="1"/>
    </body>
    <body name="b" pos="0 0 0.305">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" contype="2" conaffinity="2"/>
    </body>
    <body name="c" pos="1 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1"/>
    </body>
    <body name="d" pos="1 0 0.305">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1"/>
    </body>
    <body name="e" pos="2 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1"/>
    </body>
    <body name="f" pos="2 0 0.305">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1"/>
    </body>
  </worldbody>
  <contact>
    <exclude body1="e" body2="f"/>
  </contact>
</mujoco>
)";

TEST(Mjcf, ContactBitsAndExcludesBecomePairsThatNeverCollide)
{
    const TempDir dir;
    const MjcfLoad loaded = mjcfLoad(dir, "bits.xml", cContactBits);
    const core::Model& model = loaded.model;
    EXPECT_TRUE(ignoresPair(model, "a", "b"));  // 1 & 2 == 0 both ways
    EXPECT_TRUE(ignoresPair(model, "e", "f"));  // <exclude>
    EXPECT_FALSE(ignoresPair(model, "c", "d")); // the defaults: 1 and 1
    EXPECT_FALSE(ignoresPair(model, "a", "c"));
    EXPECT_FALSE(ignoresPair(model, "world", "b")); // 2 & 3
}

// Dropped 5 mm, the boxes whose bits do not match (a, b) and the excluded ones (e, f) pass
// through each other onto the floor; the matching ones (c, d) stack, without sinking.
TEST(Mjcf, BoxesWithMatchingBitsStackAndTheOthersPassThrough)
{
    const TempDir dir;
    const run::LoadedScene scene = run::loadScene(dir.write("bits.xml", cContactBits));
    run::RunSettings settings;
    settings.steps = run::stepsFor(1.0, scene.model.simulation.dt);
    core::State last;
    const run::RunSummary summary = run::runSimulation(
        scene.model, settings, [&](const core::State& s, const core::Simulator*) { last = s; });
    ASSERT_TRUE(summary.completed) << summary.failure;
    const auto z = [&](const std::string& name)
    { return last.bodies[static_cast<std::size_t>(scene.model.findBody(name))].position_W.z(); };
    EXPECT_NEAR(z("a"), 0.1, 1e-3);
    EXPECT_NEAR(z("b"), 0.1, 1e-3);
    EXPECT_NEAR(z("c"), 0.1, 1e-3);
    EXPECT_NEAR(z("d"), 0.3, 1e-4);
    EXPECT_NEAR(z("e"), 0.1, 1e-3);
    EXPECT_NEAR(z("f"), 0.1, 1e-3);
    EXPECT_LE(summary.maxPenetrationM, 1e-4);
}

TEST(Mjcf, SphereRestsOnAWorldbodyPlaneHeldUpByItsWeight)
{
    const TempDir dir;
    const run::LoadedScene scene = run::loadScene(dir.write("rest.xml", R"(<mujoco>
  <option timestep="0.001"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1"/>
    <body name="ball" pos="0 0 0.1">
      <freejoint/>
      <geom type="sphere" size="0.1" density="1000"/>
    </body>
  </worldbody>
</mujoco>
)"));
    const core::Model& model = scene.model;
    const core::Body& world = mjcfBody(model, "world");
    ASSERT_EQ(world.shapes.size(), 1u);
    EXPECT_EQ(world.shapes[0].type, core::ShapeType::Plane);
    EXPECT_VEC_NEAR(world.shapes[0].normal, Vec3::UnitZ(), 1e-12);
    EXPECT_DOUBLE_EQ(world.shapes[0].offset, 0.0);
    EXPECT_DOUBLE_EQ(model.simulation.dt, 0.001);
    EXPECT_VEC_NEAR(model.simulation.gravity, Vec3(0.0, 0.0, -9.81), 0.0);

    run::Simulation simulation(model);
    const int ball = model.findBody("ball");
    const double m = sphereMass(1000.0, 0.1);
    double normal = 0.0; // N s over the second half
    double deepest = 0.0;
    std::vector<core::ContactImpulse> contacts;
    const long steps = run::stepsFor(1.0, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulation.step();
        simulation.simulator().contactImpulses(contacts);
        for (const core::ContactImpulse& c : contacts)
        {
            normal += k >= steps / 2 ? c.normalImpulse() : 0.0;
        }
        deepest =
            std::max(deepest, 0.1 - simulation.state().bodies[static_cast<std::size_t>(ball)].position_W.z());
    }
    EXPECT_NEAR(normal / 0.5, m * 9.81, 1e-3 * m * 9.81);
    EXPECT_LE(deepest, 1e-4);
}

// A sphere on a massless rod, swinging 0.02 rad: a compound pendulum, T = 2 pi sqrt(I / (m g d)).
TEST(Mjcf, HingePendulumSwingsWithTheCompoundPendulumsPeriod)
{
    const TempDir dir;
    io::UrdfOptions options;
    options.keyframe = "start";
    const run::LoadedScene scene = run::loadScene(dir.write("pendulum.xml", R"(<mujoco>
  <compiler angle="radian"/>
  <option timestep="0.0005"/>
  <worldbody>
    <body name="bob" pos="0 0 2">
      <joint name="pivot" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.05" pos="0 0 -0.5" density="1000"/>
    </body>
  </worldbody>
  <keyframe>
    <key name="start" qpos="0.02"/>
  </keyframe>
</mujoco>
)"),
                                                  options);
    const double m = sphereMass(1000.0, 0.05);
    const double d = 0.5;
    const double inertia = sphereMoment(m, 0.05) + m * d * d; // about the pivot
    const double period = 2.0 * cPi * std::sqrt(inertia / (m * 9.81 * d));
    // Times the angle crosses 0 going up, interpolated within the step.
    std::vector<double> crossings;
    double previous = 0.02;
    double previousTime = 0.0;
    run::RunSettings settings;
    settings.steps = run::stepsFor(3.0 * period, scene.model.simulation.dt);
    const run::RunSummary summary = run::runSimulation(
        scene.model, settings,
        [&](const core::State& s, const core::Simulator*)
        {
            const double q = run::jointPosition(scene.model, s, "pivot");
            if (previous < 0.0 && q >= 0.0)
            {
                crossings.push_back(previousTime + (s.time - previousTime) * (-previous) / (q - previous));
            }
            previous = q;
            previousTime = s.time;
        });
    ASSERT_TRUE(summary.completed) << summary.failure;
    ASSERT_GE(crossings.size(), 2u);
    const double measured =
        (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    EXPECT_NEAR(measured, period, 0.005 * period) << "T = " << period << " s";
}

// ---------------------------------------------------------------------------------------------
// What Frontier does not model: warnings naming the element, its file and line

TEST(Mjcf, TendonAndEqualityAreWarningsWithFileAndLine)
{
    const TempDir dir;
    dir.write("ties.xml", R"(<mujoco>
  <equality>
    <joint joint1="left" joint2="right"/>
  </equality>
</mujoco>
)");
    const std::string path = dir.write("tied.xml", R"(<mujoco>
  <worldbody>
    <body name="a" pos="0 0 1">
      <joint name="left" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.1"/>
    </body>
    <body name="b" pos="1 0 1">
      <joint name="right" type="hinge" axis="0 1 0"/>
      <geom type="sphere" size="0.1"/>
    </body>
  </worldbody>
  <tendon>
    <fixed name="sum">
      <joint joint="left" coef="1"/>
      <joint joint="right" coef="1"/>
    </fixed>
  </tendon>
  <include file="ties.xml"/>
</mujoco>
)");
    LoadReport report;
    loadScene(path, {}, &report);
    EXPECT_TRUE(hasWarning(report, path + ":12: warning: <tendon> is not supported")) << allWarnings(report);
    EXPECT_TRUE(hasWarning(report, dir.file("ties.xml") + ":2: warning: <equality> is not supported"))
        << allWarnings(report);
}

// ---------------------------------------------------------------------------------------------
// A scene's models: {mjcf: FILE, ...}

TEST(Mjcf, SceneModelEntryPlacesNamesAndHoldsTheModel)
{
    const TempDir dir;
    dir.write("keyed.xml", cKeyedPendulum);
    LoadReport report;
    const core::Model model = loadScene(dir.write("scene.yaml", R"(simulation: {dt: 0.001}
models:
  - {mjcf: keyed.xml, keyframe: tilted, position: [1, 2, 3], orientation: [0.7071067811865476, 0, 0, 0.7071067811865476], prefix: left_, self_collision: false, hold: true}
)"),
                                        {}, &report);
    // The arm's centre as in the file's keyframe, (0.5 cos 0.5, 0, 1 - 0.5 sin 0.5), turned 90
    // degrees about z and moved by (1, 2, 3).
    const Vec3 inFile(0.5 * std::cos(0.5), 0.0, 1.0 - 0.5 * std::sin(0.5));
    EXPECT_VEC_NEAR(mjcfBody(model, "left_arm").position_W,
                    Vec3(1.0 - inFile.y(), 2.0 + inFile.x(), 3.0 + inFile.z()), 1e-12);
    const core::Joint& pivot = mjcfJoint(model, "left_pivot");
    EXPECT_VEC_NEAR(pivot.axisParent, Vec3(-1.0, 0.0, 0.0), 1e-12);
    EXPECT_DOUBLE_EQ(pivot.initialPosition, 0.5);
    // self_collision false: one group, named by the prefix and the model, which MuJoCo leaves
    // unnamed: named after its file.
    EXPECT_EQ(mjcfBody(model, "left_arm").group, "left_keyed");
    ASSERT_EQ(report.robots.size(), 1u);
    EXPECT_EQ(report.robots[0].name, "keyed");
    ASSERT_EQ(model.actuators.size(), 1u); // hold: a servo on the pivot, at its start
    EXPECT_EQ(model.actuators[0].kind, core::ActuatorKind::Position);
    EXPECT_DOUBLE_EQ(model.actuators[0].target.constant, 0.5);
}

// A scene's MJCF entry without a position keeps the file's pose and the keyframe's velocity: a
// ball the key puts 2 m up, moving at 1 m/s along x and spinning at 3 rad/s about z; a scene
// `velocity` adds to it.
TEST(Mjcf, SceneModelEntryKeepsTheKeyframesPoseAndVelocity)
{
    const TempDir dir;
    dir.write("thrown.xml", R"(<mujoco>
  <worldbody>
    <body name="ball">
      <freejoint/>
      <geom type="sphere" size="0.1"/>
    </body>
  </worldbody>
  <keyframe>
    <key name="thrown" qpos="0 0 2 1 0 0 0" qvel="1 0 0 0 0 3"/>
  </keyframe>
</mujoco>
)");
    const core::Model model = loadScene(dir.write("scene.yaml", R"(models:
  - {mjcf: thrown.xml, keyframe: thrown, velocity: [0, 0.5, 0]}
)"));
    const core::Body& ball = mjcfBody(model, "ball");
    EXPECT_VEC_NEAR(ball.position_W, Vec3(0.0, 0.0, 2.0), 1e-15);
    EXPECT_VEC_NEAR(ball.velocity_W, Vec3(1.0, 0.5, 0.0), 1e-15);
    EXPECT_VEC_NEAR(ball.angularVelocity_W, Vec3(0.0, 0.0, 3.0), 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Bad files and misuse: InputError naming the file and line

TEST(MjcfErrors, MalformedXmlNamesTheLine)
{
    const TempDir dir;
    const std::string path = dir.write("broken.xml", "<mujoco>\n  <worldbody>\n    <body name=\"a\">\n"
                                                     "      <geom type=\"sphere\" size=\"0.1\"\n  "
                                                     "</worldbody>\n</mujoco>\n");
    const InputError e = captureInputError([&] { loadScene(path); });
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), 4) << e.what();
}

// MuJoCo gives a pair of geoms the larger of their frictions: a box of 0.5 on a floor of 1.0 slides
// with 1.0 (the geometric mean would be 0.707).
TEST(Mjcf, AContactTakesTheLargerFrictionAsInMuJoCo)
{
    const TempDir dir;
    const std::string path = dir.write("friction.xml", R"(<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1" friction="1.0"/>
    <body name="box" pos="0 0 0.1">
      <freejoint/>
      <geom type="box" size="0.1 0.1 0.1" friction="0.5"/>
    </body>
  </worldbody>
</mujoco>
)");
    const core::Model model = loadScene(path);
    const int box = model.findBody("box");
    const int floor = model.findBody("world");
    ASSERT_GE(box, 0);
    ASSERT_GE(floor, 0);
    EXPECT_EQ(model.bodies[box].friction, 0.5);
    EXPECT_EQ(core::contactFriction(model, box, floor), 1.0);
}

TEST(MjcfErrors, AModelWithNothingInItIsRefused)
{
    const TempDir dir;
    const std::string path = dir.write("empty.xml", "<mujoco model=\"nothing\"><worldbody/></mujoco>\n");
    const InputError e = captureInputError([&] { loadScene(path); });
    EXPECT_INPUT_ERROR_AT(e, path, 0, 0, "the model has no bodies");
}

TEST(MjcfErrors, UnknownAttributeIsMuJoCosSchemaErrorWithTheLine)
{
    const TempDir dir;
    const std::string path = dir.write("typo.xml", R"(<mujoco>
  <worldbody>
    <body name="a" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" radius="0.1"/>
    </body>
  </worldbody>
</mujoco>
)");
    const InputError e = captureInputError([&] { loadScene(path); });
    EXPECT_INPUT_ERROR_AT(e, path, 5, 0, "radius");
}

TEST(MjcfErrors, MissingMeshFileIsNamed)
{
    const TempDir dir;
    const std::string path = dir.write("meshless.xml", R"(<mujoco>
  <asset>
    <mesh name="part" file="no_such_part.stl"/>
  </asset>
  <worldbody>
    <body name="a" pos="0 0 1">
      <freejoint/>
      <geom type="mesh" mesh="part"/>
    </body>
  </worldbody>
</mujoco>
)");
    const InputError e = captureInputError([&] { loadScene(path); });
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.message().find("no_such_part.stl"), std::string::npos) << e.what();
}

TEST(MjcfErrors, MissingIncludeIsNamedWithItsLine)
{
    const TempDir dir;
    const std::string path = dir.write("main.xml", R"(<mujoco>
  <worldbody>
    <include file="nowhere.xml"/>
  </worldbody>
</mujoco>
)");
    const InputError e = captureInputError([&] { loadScene(path); });
    EXPECT_INPUT_ERROR_AT(e, path, 3, 0, "nowhere.xml");
}

TEST(MjcfErrors, XmlWhoseRootIsNeitherMujocoNorRobotIsRefused)
{
    const TempDir dir;
    const std::string path = dir.write(
        "world.xml", "<?xml version=\"1.0\"?>\n<sdf version=\"1.6\">\n  <world name=\"w\"/>\n</sdf>\n");
    const InputError e = captureInputError([&] { loadScene(path); });
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.message().find("<mujoco>"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("<sdf>"), std::string::npos) << e.what();
}

TEST(MjcfErrors, XmlWhoseRootIsRobotLoadsAsUrdf)
{
    const TempDir dir;
    LoadReport report;
    const core::Model model = loadScene(dir.write("robot.xml", R"(<?xml version="1.0"?>
<robot name="cube">
  <link name="block">
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
</robot>
)"),
                                        {}, &report);
    EXPECT_DOUBLE_EQ(mjcfBody(model, "block").mass, 2.0);
    // A URDF has no <key> to start from.
    UrdfOptions options;
    options.keyframe = "home";
    const InputError e = captureInputError([&] { loadScene(dir.file("robot.xml"), options); });
    EXPECT_NE(e.message().find("this .xml is a URDF"), std::string::npos) << e.what();
}

TEST(MjcfErrors, KeyframeOnAYamlSceneIsRefused)
{
    const TempDir dir;
    const std::string path =
        dir.write("scene.yaml", "bodies:\n  - {name: box, mass: 1, shape: {type: box, size: [1, 1, 1]}}\n");
    UrdfOptions options;
    options.keyframe = "home";
    const InputError e = captureInputError([&] { loadScene(path, options); });
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(e.message().find("--keyframe"), std::string::npos) << e.what();
}

TEST(MjcfErrors, KeyframeOnAUrdfModelEntryIsRefused)
{
    const TempDir dir;
    const std::string urdf =
        std::string(FRONTIER_SOURCE_DIR) + "/scenes/robots/quadruped_description/urdf/quadruped.urdf";
    const InputError e = captureInputError(
        [&] {
            loadSceneFromString("models:\n  - {urdf: " + urdf + ", keyframe: home}\n",
                                dir.file("scene.yaml"));
        });
    EXPECT_EQ(e.file(), dir.file("scene.yaml"));
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(e.message().find("'keyframe' is for an 'mjcf' model"), std::string::npos) << e.what();
}

TEST(MjcfErrors, MjcfAndUrdfInOneModelEntryIsRefused)
{
    const TempDir dir;
    const InputError e = captureInputError(
        [&] { loadSceneFromString("models:\n  - {urdf: a.urdf, mjcf: a.xml}\n", dir.file("scene.yaml")); });
    EXPECT_EQ(e.file(), dir.file("scene.yaml"));
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(e.message().find("'urdf' or 'mjcf'"), std::string::npos) << e.what();
}

// ---------------------------------------------------------------------------------------------
// Debian's dart-doc MJCF files: each loads and runs 2 s holding its joints, finite, a passive one
// never gaining energy; or is refused naming what and where.

const std::filesystem::path cDartMjcf = "/usr/share/doc/dart/data/mjcf";

// The dart-doc MJCF folder copied into `to` (tests/decompressed_copy.h); the model files, relative
// to `to`.
std::vector<std::string> copyDartMjcf(const std::filesystem::path& to)
{
    std::vector<std::string> models = copyDecompressed(cDartMjcf, to);
    std::erase_if(models, [](const std::string& file) { return !file.ends_with(".xml"); });
    return models;
}

struct DartMjcf
{
    const char* name;
    std::string file;    // relative to data/mjcf, without .gz
    const char* refusal; // nullptr: loads and runs; else what the InputError says
    int line = 0;        // and the line it names
};

std::ostream& operator<<(std::ostream& out, const DartMjcf& c)
{
    return out << c.file;
}

// Nothing in the model adds energy: no loads, every actuator a zero effort or a motor to speed 0
// (joint springs are servos: their energy is not in core::totalEnergy).
bool mjcfPassive(const core::Model& model)
{
    return model.loads.empty() &&
           std::all_of(model.actuators.begin(), model.actuators.end(),
                       [](const core::Actuator& a)
                       {
                           return a.kind != core::ActuatorKind::Position &&
                                  a.target.kind == core::TimeFunction::Kind::Constant &&
                                  a.target.constant == 0.0;
                       });
}

const std::vector<DartMjcf> cDartMjcfFiles = {
    {"Ant", "openai/ant.xml", nullptr},
    {"HalfCheetah", "openai/half_cheetah.xml", nullptr},
    {"Hopper", "openai/hopper.xml", nullptr},
    {"Humanoid", "openai/humanoid.xml", nullptr},
    {"HumanoidStandup", "openai/humanoidstandup.xml", nullptr},
    {"InvertedDoublePendulum", "openai/inverted_double_pendulum.xml", nullptr},
    {"InvertedPendulum", "openai/inverted_pendulum.xml", nullptr},
    {"Point", "openai/point.xml", nullptr},
    {"Pusher", "openai/pusher.xml", nullptr},
    {"Reacher", "openai/reacher.xml", nullptr},
    {"Striker", "openai/striker.xml", nullptr},
    {"Swimmer", "openai/swimmer.xml", nullptr},
    {"Thrower", "openai/thrower.xml", nullptr},
    // pos="0.2/2 0 0.1": MuJoCo's parser refuses the number.
    {"Walker2d", "openai/walker2d.xml", "problem reading attribute 'pos'", 23},
    {"FetchPickAndPlace", "openai/robotics/fetch/pick_and_place.xml", nullptr},
    {"FetchPush", "openai/robotics/fetch/push.xml", nullptr},
    {"FetchReach", "openai/robotics/fetch/reach.xml", nullptr},
    {"FetchSlide", "openai/robotics/fetch/slide.xml", nullptr},
    // Fragments the fetch tasks include, not models.
    {"FetchRobotFragment", "openai/robotics/fetch/robot.xml", "body", 2},
    {"FetchSharedFragment", "openai/robotics/fetch/shared.xml", "could not open STL file", 18},
    {"Default", "test/default.xml", nullptr},
    // Defaults for include_main.xml, with an empty worldbody: nothing to simulate.
    {"IncludeDefault", "test/include_default.xml", "the model has no bodies", 0},
    {"IncludeMain", "test/include_main.xml", nullptr},
};

class DartDocMjcf : public ::testing::TestWithParam<DartMjcf>
{
};

TEST_P(DartDocMjcf, LoadsAndRunsOrIsRefusedNamingWhatAndWhere)
{
    if (!std::filesystem::is_directory(cDartMjcf))
    {
        GTEST_SKIP() << cDartMjcf << " is missing (Debian's dart-doc)";
    }
    const DartMjcf& c = GetParam();
    const TempDir dir;
    copyDartMjcf(dir.path() / "mjcf");
    const std::string path = (dir.path() / "mjcf" / c.file).string();
    if (c.refusal != nullptr)
    {
        const InputError e = captureInputError([&] { run::loadScene(path); });
        EXPECT_EQ(e.file(), path) << e.what();
        EXPECT_EQ(e.line(), c.line) << e.what();
        EXPECT_NE(e.message().find(c.refusal), std::string::npos) << e.what();
        std::cout << "dart-doc " << c.file << ": refused: " << e.what() << "\n";
        return;
    }
    const run::LoadedScene scene = run::loadScene(path);
    run::RunSettings settings;
    settings.steps = run::stepsFor(2.0, scene.model.simulation.dt);
    bool finite = true;
    const run::RunSummary summary = run::runSimulation(scene.model, settings,
                                                       [&](const core::State& s, const core::Simulator*)
                                                       {
                                                           for (const core::BodyState& b : s.bodies)
                                                           {
                                                               finite = finite && b.position_W.allFinite() &&
                                                                        b.velocity_W.allFinite() &&
                                                                        b.angularVelocity_W.allFinite() &&
                                                                        b.orientation_WB.coeffs().allFinite();
                                                           }
                                                       });
    ASSERT_TRUE(summary.completed) << summary.failure;
    EXPECT_TRUE(finite && summary.finite);
    EXPECT_LE(summary.maxJointErrorM, 1e-6);
    const bool passive = mjcfPassive(scene.model);
    if (passive)
    {
        EXPECT_LE(summary.energyMaxJ,
                  summary.energyInitialJ + 1e-6 * std::max(1.0, std::abs(summary.energyInitialJ)))
            << "energy rose above its start " << summary.energyInitialJ << " J";
    }
    std::cout << "dart-doc " << c.file << ": " << scene.model.bodies.size() << " bodies, "
              << scene.model.joints.size() << " joints, dt " << scene.model.simulation.dt << " s, "
              << summary.steps << " steps, joint gap " << summary.maxJointErrorM << " m, energy "
              << summary.energyInitialJ << " -> max " << summary.energyMaxJ << " J"
              << (passive ? " (passive)" : "") << ", penetration " << summary.maxPenetrationM << " m, "
              << summary.wallSeconds / static_cast<double>(summary.steps) * 1e6 << " us/step, "
              << scene.report.warnings.size() << " warnings\n";
}

INSTANTIATE_TEST_SUITE_P(Files, DartDocMjcf, ::testing::ValuesIn(cDartMjcfFiles),
                         [](const ::testing::TestParamInfo<DartMjcf>& p)
                         { return std::string(p.param.name); });

// The table above names every MJCF file the package holds.
TEST(DartDocMjcfFiles, EveryFileOfThePackageIsInTheTable)
{
    if (!std::filesystem::is_directory(cDartMjcf))
    {
        GTEST_SKIP() << cDartMjcf << " is missing (Debian's dart-doc)";
    }
    const TempDir dir;
    for (const std::string& file : copyDartMjcf(dir.path() / "mjcf"))
    {
        EXPECT_TRUE(std::any_of(cDartMjcfFiles.begin(), cDartMjcfFiles.end(),
                                [&](const DartMjcf& c) { return c.file == file; }))
            << file << " is not in the table";
    }
}

} // namespace
} // namespace frontier::io::test
