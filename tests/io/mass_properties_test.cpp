// tests/io/mass_properties_test.cpp: mass properties of YAML bodies against closed forms
// computed here (not with core's formulas).
#include "io/scene.h"
#include "io_test_util.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::io::test
{
namespace
{

constexpr double pi = std::numbers::pi;

const core::Body& onlyBody(const core::Model& model)
{
    EXPECT_EQ(model.bodies.size(), 1u);
    return model.bodies.at(0);
}

void expectDiagonal(const core::Mat3& m, double xx, double yy, double zz, double tol)
{
    EXPECT_NEAR(m(0, 0), xx, tol);
    EXPECT_NEAR(m(1, 1), yy, tol);
    EXPECT_NEAR(m(2, 2), zz, tol);
    EXPECT_NEAR(m(0, 1), 0.0, tol);
    EXPECT_NEAR(m(0, 2), 0.0, tol);
    EXPECT_NEAR(m(1, 2), 0.0, tol);
    EXPECT_NEAR((m - m.transpose()).norm(), 0.0, tol);
}

TEST(MassProperties, BoxFromDensity)
{
    const core::Model model = loadSceneFromString(
        "bodies: [{name: b, density: 500, shape: {type: box, size: [0.3, 0.2, 0.1]}}]\n", "s.yaml");
    const core::Body& b = onlyBody(model);
    const double m = 500 * 0.3 * 0.2 * 0.1;
    EXPECT_NEAR(b.mass, m, 1e-12);
    expectDiagonal(b.inertia_B, m * (0.04 + 0.01) / 12, m * (0.09 + 0.01) / 12, m * (0.09 + 0.04) / 12,
                   1e-15);
}

TEST(MassProperties, DefaultDensityIsWater)
{
    const core::Model model =
        loadSceneFromString("bodies: [{name: s, shape: {type: sphere, radius: 0.1}}]\n", "s.yaml");
    const double m = 1000 * 4.0 / 3.0 * pi * 0.001;
    EXPECT_NEAR(onlyBody(model).mass, m, 1e-12);
    expectDiagonal(onlyBody(model).inertia_B, 0.4 * m * 0.01, 0.4 * m * 0.01, 0.4 * m * 0.01, 1e-15);
}

TEST(MassProperties, MassOnlyScalesTheShapeInertia)
{
    const core::Model model = loadSceneFromString(
        "bodies: [{name: c, mass: 3, shape: {type: cylinder, radius: 0.05, length: 0.4}}]\n", "s.yaml");
    const double m = 3, r = 0.05, h = 0.4;
    EXPECT_EQ(onlyBody(model).mass, 3.0);
    expectDiagonal(onlyBody(model).inertia_B, m * (3 * r * r + h * h) / 12, m * (3 * r * r + h * h) / 12,
                   m * r * r / 2, 1e-14);
}

TEST(MassProperties, CapsuleAsCylinderPlusTwoHemispheres)
{
    const double rho = 800, r = 0.04, h = 0.2;
    const core::Model model = loadSceneFromString(
        "bodies: [{name: c, density: 800, shape: {type: capsule, radius: 0.04, length: 0.2}}]\n", "s.yaml");
    const double mc = rho * pi * r * r * h;
    const double ms = rho * 4.0 / 3.0 * pi * r * r * r; // both hemispheres = one sphere
    const double mh = ms / 2;
    // A hemisphere's inertia about a transverse axis through the sphere centre is 2/5 mh r^2; its
    // centre of mass is 3r/8 from the flat face. Move that axis to the hemisphere's own centre of
    // mass, then out to the capsule centre (h/2 + 3r/8 away).
    const double c = 3 * r / 8;
    const double hemiCentre = 0.4 * mh * r * r - mh * c * c;
    const double ixx = mc * (3 * r * r + h * h) / 12 + 2 * (hemiCentre + mh * std::pow(h / 2 + c, 2));
    const double izz = mc * r * r / 2 + 0.4 * ms * r * r;
    EXPECT_NEAR(onlyBody(model).mass, mc + ms, 1e-12);
    expectDiagonal(onlyBody(model).inertia_B, ixx, ixx, izz, 1e-14);
}

TEST(MassProperties, ExplicitInertiaForms)
{
    const core::Model model = loadSceneFromString(text(R"(
bodies:
  - {name: a, mass: 2, inertia: [0.1, 0.2, 0.25]}
  - {name: b, mass: 2, inertia: [0.1, 0.2, 0.25, 0.01, 0.02, 0.03]}
  - {name: c, mass: 2, inertia: [[0.1, 0.01, 0.02], [0.01, 0.2, 0.03], [0.02, 0.03, 0.25]]}
)"),
                                                  "s.yaml");
    ASSERT_EQ(model.bodies.size(), 3u);
    expectDiagonal(model.bodies[0].inertia_B, 0.1, 0.2, 0.25, 0.0);
    const core::Mat3 expected =
        (core::Mat3() << 0.1, 0.01, 0.02, 0.01, 0.2, 0.03, 0.02, 0.03, 0.25).finished();
    EXPECT_EQ(model.bodies[1].inertia_B, expected);
    EXPECT_EQ(model.bodies[2].inertia_B, expected);
}

TEST(MassProperties, TwoSpheresCompositeShiftsTheCentreOfMass)
{
    // Spheres of radius 0.1 at x = 0 and x = 0.3 (same density): the centre of mass is at x = 0.15
    // of the body frame, so the body moves there and its shapes move back.
    const core::Model model = loadSceneFromString(text(R"(
bodies:
  - name: dumbbell
    position: [1, 2, 3]
    shapes:
      - {type: sphere, radius: 0.1}
      - {type: sphere, radius: 0.1, position: [0.3, 0, 0]}
)"),
                                                  "s.yaml");
    const core::Body& b = onlyBody(model);
    const double ms = 1000 * 4.0 / 3.0 * pi * 0.001;
    EXPECT_NEAR(b.mass, 2 * ms, 1e-12);
    EXPECT_NEAR((b.position_W - core::Vec3(1.15, 2, 3)).norm(), 0.0, 1e-15);
    ASSERT_EQ(b.shapes.size(), 2u);
    EXPECT_NEAR((b.shapes[0].position_BS - core::Vec3(-0.15, 0, 0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((b.shapes[1].position_BS - core::Vec3(0.15, 0, 0)).norm(), 0.0, 1e-15);
    const double own = 0.4 * ms * 0.01;
    expectDiagonal(b.inertia_B, 2 * own, 2 * own + 2 * ms * 0.15 * 0.15, 2 * own + 2 * ms * 0.15 * 0.15,
                   1e-15);
}

TEST(MassProperties, RotatedShapeRotatesItsInertia)
{
    // A cylinder along z, turned 90 degrees about y in the body: its long axis is body x.
    const core::Model model = loadSceneFromString(text(R"(
bodies:
  - name: rod
    mass: 2
    shape: {type: cylinder, radius: 0.01, length: 1.0, orientation: [0.7071067811865476, 0, 0.7071067811865476, 0]}
)"),
                                                  "s.yaml");
    const double m = 2, r = 0.01, h = 1.0;
    expectDiagonal(onlyBody(model).inertia_B, m * r * r / 2, m * (3 * r * r + h * h) / 12,
                   m * (3 * r * r + h * h) / 12, 1e-14);
}

TEST(MassProperties, MeshCubeFromObjShiftsToItsCentre)
{
    TempDir dir;
    // Unit cube with corners (1,1,1)..(2,2,2), faces counter-clockwise seen from outside (quads).
    dir.write("cube.obj", text(R"(
# a unit cube away from its origin
v 1 1 1
v 2 1 1
v 2 2 1
v 1 2 1
v 1 1 2
v 2 1 2
v 2 2 2
v 1 2 2
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)"));
    const std::string scene = dir.write("scene.yaml", text(R"(
bodies:
  - name: cube
    density: 2
    position: [0, 0, 10]
    shape: {type: mesh, file: cube.obj, scale: 0.5}
)"));
    const core::Model model = loadScene(scene);
    const core::Body& b = onlyBody(model);
    // Scaled by 0.5: a 0.5 m cube from (0.5,0.5,0.5) to (1,1,1); centre (0.75, 0.75, 0.75).
    const double m = 2 * 0.125;
    EXPECT_NEAR(b.mass, m, 1e-14);
    EXPECT_NEAR((b.position_W - core::Vec3(0.75, 0.75, 10.75)).norm(), 0.0, 1e-14);
    ASSERT_EQ(b.shapes.size(), 1u);
    EXPECT_NEAR((b.shapes[0].position_BS - core::Vec3(-0.75, -0.75, -0.75)).norm(), 0.0, 1e-14);
    EXPECT_EQ(b.shapes[0].vertices.size(), 8u);
    EXPECT_EQ(b.shapes[0].triangles.size(), 12u);
    // Vertices stay in the file's frame, scaled: the corner (2,2,2) is at (1,1,1) (the shift to
    // the centre of mass is in position_BS).
    EXPECT_NE(std::find(b.shapes[0].vertices.begin(), b.shapes[0].vertices.end(), core::Vec3(1, 1, 1)),
              b.shapes[0].vertices.end());
    expectDiagonal(b.inertia_B, m * 0.25 / 6, m * 0.25 / 6, m * 0.25 / 6, 1e-15);
}

} // namespace
} // namespace frontier::io::test
