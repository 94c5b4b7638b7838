// tests/collision/hull_test.cpp: convex hulls of meshes (collision/convex_hull.cpp) and moving
// meshes colliding as them. Oracles: the cube's own corners, faces and volume (the divergence
// theorem over the hull's faces); FCL's dedicated box-box algorithm for cubes given as meshes;
// the notch of an L, which only the hull fills.
#include "collision/convex_hull.h"
#include "collision/internal.h"
#include "test_models.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>
#include <limits>
#include <memory>
#include <numbers>
#include <tuple>

namespace frontier::collision::test
{
namespace
{

using std::numbers::pi;

// Volume (m^3) enclosed by the faces, each a fan of triangles: sum of a . (b x c) / 6. Positive
// only when every face is counter-clockwise seen from outside.
double enclosedVolume(const ConvexHull& h)
{
    double volume = 0.0;
    for (const int start : h.faceStart)
    {
        const auto corner = [&](int i)
        { return h.vertices[static_cast<std::size_t>(h.faces[static_cast<std::size_t>(start + 1 + i)])]; };
        const int n = h.faces[static_cast<std::size_t>(start)];
        for (int i = 1; i + 1 < n; ++i)
            volume += corner(0).dot(corner(i).cross(corner(i + 1))) / 6.0;
    }
    return volume;
}

// The unit cube's corners, each twice, with its face centres, edge midpoints and points inside.
std::vector<Vec3> cubeCloud()
{
    std::vector<Vec3> points;
    for (int repeat = 0; repeat < 2; ++repeat)
        for (int k = 0; k < 8; ++k)
            points.push_back(cubeMesh(1.0).vertices[static_cast<std::size_t>(k)]);
    for (int axis = 0; axis < 3; ++axis)
        for (const double side : {-0.5, 0.5})
            points.push_back(side * Vec3::Unit(axis));
    for (int axis = 0; axis < 3; ++axis)
        for (const double s1 : {-0.5, 0.5})
            for (const double s2 : {-0.5, 0.5})
            {
                Vec3 p = Vec3::Zero();
                p[(axis + 1) % 3] = s1;
                p[(axis + 2) % 3] = s2;
                points.push_back(p);
            }
    for (int k = 0; k < 30; ++k)
        points.emplace_back(0.45 * std::sin(1.3 * k), 0.45 * std::cos(2.1 * k),
                            0.45 * std::sin(0.7 * k + 1.0));
    return points;
}

TEST(ConvexHull, CubeWithInteriorAndDuplicatePointsIsTheCube)
{
    ConvexHull hull;
    std::string reason;
    ASSERT_TRUE(computeConvexHull(cubeCloud(), hull, reason)) << reason;
    ASSERT_EQ(hull.vertices.size(), 8u);
    for (const Vec3& v : hull.vertices)
        EXPECT_EQ(v.cwiseAbs(), Vec3::Constant(0.5)) << v.transpose();
    ASSERT_EQ(hull.normals.size(), 6u);
    ASSERT_EQ(hull.faceStart.size(), 6u);
    ASSERT_EQ(hull.offsets.size(), 6u);
    ASSERT_EQ(hull.faces.size(), 6u * 5u); // six quads: [4, i0, i1, i2, i3]
    for (std::size_t k = 0; k < 6; ++k)
    {
        const Vec3& n = hull.normals[k];
        EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0, 1e-12) << "face " << k << " is not axis-aligned";
        EXPECT_NEAR(hull.offsets[k], 0.5, 1e-12);
        const auto start = static_cast<std::size_t>(hull.faceStart[k]);
        ASSERT_EQ(hull.faces[start], 4);
        for (std::size_t i = 1; i <= 4; ++i)
            EXPECT_NEAR(n.dot(hull.vertices[static_cast<std::size_t>(hull.faces[start + i])]), 0.5, 1e-12);
    }
    EXPECT_NEAR(enclosedVolume(hull), 1.0, 1e-12);
}

TEST(ConvexHull, RockHullEnclosesEveryVertexAndIsConvex)
{
    // A jittered sphere: non-convex, so some vertices fall inside the hull.
    const core::Shape rock = rockMesh(0.1, 8, 12, 0.25, 7);
    ConvexHull hull;
    std::string reason;
    ASSERT_TRUE(computeConvexHull(rock.vertices, hull, reason)) << reason;
    EXPECT_LT(hull.vertices.size(), rock.vertices.size());
    for (std::size_t k = 0; k < hull.normals.size(); ++k)
    {
        EXPECT_NEAR(hull.normals[k].norm(), 1.0, 1e-12);
        for (const Vec3& v : rock.vertices)
            EXPECT_LE(hull.normals[k].dot(v), hull.offsets[k] + 1e-12);
    }
    // The hull holds more than the rock (its notches filled), and Euler's formula holds for a
    // closed polytope: V - E + F = 2.
    EXPECT_GT(enclosedVolume(hull), core::shapeVolume(rock));
    long edges = 0;
    for (const int start : hull.faceStart)
        edges += hull.faces[static_cast<std::size_t>(start)];
    EXPECT_EQ(static_cast<long>(hull.vertices.size()) - edges / 2 + static_cast<long>(hull.normals.size()),
              2);
}

TEST(ConvexHull, HillClimbFindsTheFurthestCornerInEveryDirection)
{
    // Brute force over every corner is the oracle; 2000 directions spread over the sphere.
    const detail::ShapeInstance s = detail::makeShapeInstance(rockMesh(0.1, 16, 24, 0.25, 3), 0, true);
    ASSERT_TRUE(s.convexHull);
    for (int k = 0; k < 2000; ++k)
    {
        const double z = 1.0 - (k + 0.5) / 1000.0;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const Vec3 u(r * std::cos(2.39996 * k), r * std::sin(2.39996 * k), z);
        double best = -std::numeric_limits<double>::infinity();
        for (const Vec3& v : s.meshVertices())
            best = std::max(best, u.dot(v));
        EXPECT_EQ(u.dot(s.meshVertices()[static_cast<std::size_t>(detail::hullExtremeCorner(s, u))]), best)
            << k;
    }
}

// The distance (m) from p to the hull h by FCL's GJK (a point as a sphere of radius 1e-12 against
// fcl::Convex): an oracle independent of hullSignedDistance; 0 inside.
double fclDistance(const ConvexHull& h, const Vec3& p)
{
    const fcl::Convexd convex(std::make_shared<const std::vector<Vec3>>(h.vertices),
                              static_cast<int>(h.normals.size()),
                              std::make_shared<const std::vector<int>>(h.faces));
    const fcl::Sphered point(1e-12);
    fcl::Transform3d at = fcl::Transform3d::Identity();
    at.translation() = p;
    fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    return std::max(0.0, fcl::distance(&convex, fcl::Transform3d::Identity(), &point, at, request, result));
}

// A hull capped at K corners keeps K of the full hull's corners (so it lies inside it), reaches
// every corner left out within the distance hullDeviation states (checked against FCL), and
// grows towards the full hull as K grows; a hull of few corners is kept as it is.
TEST(ConvexHull, CappedHullKeepsItsCornersWithinTheStatedDistance)
{
    ConvexHull full;
    std::string reason;
    ASSERT_TRUE(computeConvexHull(rockMesh(0.1, 32, 48, 0.25, 3).vertices, full, reason)) << reason;
    ASSERT_GT(full.vertices.size(), 100u);
    const double fullVolume = enclosedVolume(full);
    double lastDeviation = std::numeric_limits<double>::infinity();
    double lastVolume = 0.0;
    for (const int k : {8, 16, 32, 64, 128})
    {
        ConvexHull capped;
        ASSERT_TRUE(capConvexHull(full, k, capped, reason)) << reason;
        EXPECT_LE(capped.vertices.size(), static_cast<std::size_t>(k));
        EXPECT_GE(capped.vertices.size(), static_cast<std::size_t>(k) - 2) << "qhull stopped early";
        for (const Vec3& v : capped.vertices)
            EXPECT_NE(std::find(full.vertices.begin(), full.vertices.end(), v), full.vertices.end())
                << "K = " << k << ": " << v.transpose() << " is not a corner of the full hull";
        const double deviation = hullDeviation(full, capped);
        double farthest = 0.0;
        for (const Vec3& v : full.vertices)
        {
            const double d = fclDistance(capped, v);
            EXPECT_LE(d, deviation + 1e-6) << "K = " << k;
            farthest = std::max(farthest, d);
        }
        EXPECT_NEAR(farthest, deviation, 1e-6) << "K = " << k;
        const double volume = enclosedVolume(capped);
        EXPECT_LE(volume, fullVolume * (1.0 + 1e-12));
        EXPECT_LE(deviation, lastDeviation) << "K = " << k;
        EXPECT_GE(volume, lastVolume) << "K = " << k;
        std::printf("K = %d: %zu of %zu corners, %.2f mm from the full hull, %.1f %% of its volume\n", k,
                    capped.vertices.size(), full.vertices.size(), 1e3 * deviation,
                    100.0 * volume / fullVolume);
        lastDeviation = deviation;
        lastVolume = volume;
        if (k == cHullCorners)
        {
            // The detector's cap on a rough 10 cm rock (radii +-25 %): within 8 mm, 95 % of its
            // volume.
            EXPECT_LT(deviation, 0.008);
            EXPECT_GT(volume, 0.95 * fullVolume);
        }
    }
    ConvexHull same;
    ASSERT_TRUE(capConvexHull(full, static_cast<int>(full.vertices.size()), same, reason));
    EXPECT_EQ(same.vertices, full.vertices);
    EXPECT_EQ(same.faces, full.faces);
    EXPECT_EQ(hullDeviation(full, same), 0.0);
    EXPECT_FALSE(capConvexHull(full, 3, same, reason));
}

// The detector's meshes keep at most cHullCorners corners unless asked for the full hull: the
// instance says how many the full hull had and how far it reaches beyond the capped one, and a
// rock sunk into the floor touches it with the capped hull's corners, no deeper than the full
// hull's and at most that distance shallower.
TEST(HullContacts, LargeHullsAreCappedUnlessAskedForTheFull)
{
    const core::Shape rock = rockMesh(0.1, 32, 48, 0.25, 3);
    const detail::ShapeInstance capped = detail::makeShapeInstance(rock, 0, true, nullptr, cHullCorners);
    const detail::ShapeInstance full = detail::makeShapeInstance(rock, 0, true, nullptr, 0);
    ASSERT_TRUE(capped.convexHull);
    EXPECT_LE(capped.hull().vertices.size(), static_cast<std::size_t>(cHullCorners));
    EXPECT_EQ(capped.meshVertices(), capped.hull().vertices);
    EXPECT_EQ(capped.geometry->fullHullCorners, static_cast<int>(full.hull().vertices.size()));
    EXPECT_EQ(capped.geometry->hullDeviation, hullDeviation(full.hull(), capped.hull()));
    EXPECT_GT(capped.geometry->hullDeviation, 0.0);
    EXPECT_EQ(full.geometry->hullDeviation, 0.0);

    for (int k = 0; k < 8; ++k)
    {
        core::Model model;
        model.bodies.push_back(floorBody());
        model.bodies.push_back(
            movingMesh("rock", rock, Vec3(0, 0, 0.09), 1000.0, rotation(0.8 * k, Vec3(1, 0.3 * k, 2))));
        ContactDetector cappedDetector(model, 2e-3);
        ContactDetector fullDetector(model, 2e-3, MovingMeshes::FullConvexHulls);
        std::vector<Contact> a, b;
        cappedDetector.detect(core::initialState(model), a);
        fullDetector.detect(core::initialState(model), b);
        ASSERT_FALSE(a.empty());
        ASSERT_FALSE(b.empty());
        double deepestA = -1.0, deepestB = -1.0;
        for (const Contact& c : a)
            deepestA = std::max(deepestA, c.depth);
        for (const Contact& c : b)
            deepestB = std::max(deepestB, c.depth);
        EXPECT_LE(deepestA, deepestB + 1e-12) << k;
        EXPECT_GE(deepestA, deepestB - capped.geometry->hullDeviation - 1e-12) << k;
    }
}

TEST(ShapeInstance, EqualShapesShareOneGeometryAndAMeshKeepsItsOwn)
{
    core::Shape box;
    box.type = core::ShapeType::Box;
    box.size = Vec3(0.08, 0.02, 0.03);
    const detail::ShapeInstance first = detail::makeShapeInstance(box, 0, true);
    const detail::ShapeInstance second = detail::makeShapeInstance(box, 1, true, first.geometry);
    EXPECT_EQ(second.geometry, first.geometry);
    // What the second would have built alone: the same polytope, corner for corner.
    const detail::ShapeInstance alone = detail::makeShapeInstance(box, 1, true);
    ASSERT_EQ(alone.hull().vertices.size(), 8u);
    EXPECT_EQ(alone.hull().vertices, second.hull().vertices);
    EXPECT_EQ(alone.hull().faces, second.hull().faces);
    EXPECT_EQ(alone.hull().normals, second.hull().normals);
    // A mesh offered a box's geometry builds its own hull.
    const core::Shape rock = rockMesh(0.1, 16, 24, 0.25, 3);
    const detail::ShapeInstance mesh = detail::makeShapeInstance(rock, 2, true, first.geometry);
    ASSERT_TRUE(mesh.convexHull);
    EXPECT_NE(mesh.geometry, first.geometry);
    EXPECT_GT(mesh.hull().vertices.size(), 8u);
}

TEST(ConvexHull, DegenerateInputIsRefusedQuietly)
{
    std::vector<std::pair<std::string, std::vector<Vec3>>> cases;
    cases.push_back({"empty", {}});
    cases.push_back({"three points", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}});
    cases.push_back({"one point four times", {Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3)}});
    std::vector<Vec3> flat, line;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            flat.emplace_back(0.1 * i, 0.1 * j + 0.01 * i, 0.3);
    for (int i = 0; i < 6; ++i)
        line.emplace_back(0.1 * i, 0.2 * i, -0.1 * i);
    cases.push_back({"flat", flat});
    cases.push_back({"collinear", line});
    cases.push_back({"not finite",
                     {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                      Vec3(0, 0, std::numeric_limits<double>::quiet_NaN())}});
    for (const auto& [name, points] : cases)
    {
        ConvexHull hull;
        std::string reason;
        testing::internal::CaptureStderr();
        const bool built = computeConvexHull(points, hull, reason);
        const std::string printed = testing::internal::GetCapturedStderr();
        EXPECT_FALSE(built) << name;
        EXPECT_FALSE(reason.empty()) << name;
        EXPECT_TRUE(printed.empty()) << name << " printed: " << printed;
        EXPECT_TRUE(hull.vertices.empty() && hull.faces.empty()) << name;
    }
}

TEST(ConvexHull, SmallestHullIsATetrahedron)
{
    ConvexHull hull;
    std::string reason;
    ASSERT_TRUE(
        computeConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, hull, reason));
    EXPECT_EQ(hull.vertices.size(), 4u);
    EXPECT_EQ(hull.normals.size(), 4u);
    EXPECT_NEAR(enclosedVolume(hull), 1.0 / 6.0, 1e-15);
}

// A flat mesh (a square plate of two triangles) has no 3-d hull: it keeps its triangles and
// still rests on the floor and on a box on its four corners.
TEST(HullContacts, FlatMovingMeshKeepsItsTriangles)
{
    core::Shape plate;
    plate.type = core::ShapeType::Mesh;
    plate.vertices = {Vec3(-0.1, -0.1, 0), Vec3(0.1, -0.1, 0), Vec3(0.1, 0.1, 0), Vec3(-0.1, 0.1, 0)};
    plate.triangles = {{0, 1, 2}, {0, 2, 3}};
    core::Model model;
    model.bodies.push_back(floorBody());
    model.bodies.push_back(moving("plate", plate, Vec3(0, 0, -0.001)));
    model.bodies.push_back(moving("onBox", plate, Vec3(2, 0, 0.199)));
    model.bodies.push_back(fixed("table", box(1, 1, 0.2), Vec3(2, 0, 0.1)));
    const auto contacts = detectAll(model);
    int onFloor = 0, onTable = 0;
    for (const Contact& c : contacts)
    {
        EXPECT_NEAR(c.depth, 0.001, 1e-9);
        EXPECT_NEAR(std::abs(c.normal_W.z()), 1.0, 1e-9);
        onFloor += c.bodyA == 1 ? 1 : 0;
        onTable += c.bodyA == 2 ? 1 : 0;
    }
    EXPECT_EQ(onFloor, 4);
    EXPECT_EQ(onTable, 4);
}

// Cubes given as meshes collide as their hulls, the cubes themselves; FCL's dedicated box-box
// algorithm (exact, up to 4 points) on the same poses is the oracle: the same normals, depths
// and points, mesh against mesh and mesh against box.
struct CubePose
{
    const char* name;
    double lowerSide, upperSide; // m
    Vec3 upperCentre;            // m; the lower cube is at the origin
    Quat upperOrientation;
    // m: FCL's speculative box-box points (a box grown by the margin) sit half the margin (here
    // 0.5 mm) above the middle of the gap, where the clipped faces put theirs.
    double pointTolerance = 1e-6;
};

std::vector<Contact> cubeContacts(const CubePose& pose, bool lowerMesh, bool upperMesh)
{
    core::Model model;
    const auto shape = [](double side, bool mesh) { return mesh ? cubeMesh(side) : box(side, side, side); };
    model.bodies.push_back(moving("lower", shape(pose.lowerSide, lowerMesh), Vec3::Zero()));
    model.bodies.push_back(
        moving("upper", shape(pose.upperSide, upperMesh), pose.upperCentre, pose.upperOrientation));
    return detectAll(model);
}

TEST(HullContacts, CubeMeshesGiveTheContactsOfBoxes)
{
    const Quat tilt = rotation(0.3, Vec3::UnitX());
    const Quat corner = rotation(std::atan(std::sqrt(2.0)), Vec3(1, -1, 0)); // a corner points down
    const std::vector<CubePose> poses = {
        {"small on large, off centre", 0.4, 0.2, Vec3(0.05, -0.03, 0.3 - 0.002), Quat::Identity()},
        {"equal, shifted", 0.2, 0.2, Vec3(0.05, 0.03, 0.2 - 0.001), Quat::Identity()},
        {"turned 45 degrees", 0.4, 0.2, Vec3(0, 0, 0.3 - 0.001), rotation(pi / 4, Vec3::UnitZ())},
        {"edge down", 0.4, 0.2, Vec3(0.02, 0, 0.2 + 0.1 * (std::cos(0.3) + std::sin(0.3)) - 0.002), tilt},
        {"corner down", 0.4, 0.2, Vec3(0.01, 0.02, 0.2 + 0.1 * std::sqrt(3.0) - 0.002), corner},
        {"apart by half the margin", 0.4, 0.2, Vec3(0.05, -0.03, 0.3 + 0.0005), Quat::Identity(),
         0.5e-3 + 1e-6},
    };
    for (const CubePose& pose : poses)
    {
        const auto boxes = cubeContacts(pose, false, false);
        ASSERT_FALSE(boxes.empty()) << pose.name;
        for (const auto& [lowerMesh, upperMesh] : {std::pair{true, true}, {true, false}, {false, true}})
        {
            const auto meshes = cubeContacts(pose, lowerMesh, upperMesh);
            const std::string what = std::string(pose.name) + (lowerMesh ? ", mesh" : ", box") + " under a" +
                                     (upperMesh ? " mesh" : " box");
            ASSERT_EQ(meshes.size(), boxes.size()) << what;
            for (const Contact& b : boxes)
            {
                const auto same =
                    std::find_if(meshes.begin(), meshes.end(),
                                 [&](const Contact& m)
                                 {
                                     return (m.normal_W - b.normal_W).norm() < 1e-6 &&
                                            std::abs(m.depth - b.depth) < 1e-6 &&
                                            (m.point_W - b.point_W).norm() < pose.pointTolerance;
                                 });
                EXPECT_NE(same, meshes.end())
                    << what << ": no contact like the boxes' at " << b.point_W.transpose() << ", normal "
                    << b.normal_W.transpose() << ", depth " << b.depth;
            }
        }
    }
}

// Spheres, capsules and cylinders on a hull get the contacts they get on the same box: the
// hull's exact signed distance for their features, its corners against theirs, and a capsule's
// axis clipped to the hull face (a capsule across a narrow beam is held at the beam's edges).
TEST(HullContacts, RoundShapesOnAHullAsOnABox)
{
    const core::Shape beamMesh = prismMesh({{-0.1, -0.5}, {0.1, -0.5}, {0.1, 0.5}, {-0.1, 0.5}}, 0.2);
    const Quat alongX = rotation(pi / 2, Vec3::UnitY());
    const std::vector<std::tuple<const char*, core::Shape, Vec3, Quat>> cases = {
        {"sphere", sphere(0.05), Vec3(0.03, 0.1, 0.15 - 0.001), Quat::Identity()},
        {"capsule across", capsule(0.05, 0.6), Vec3(0, 0, 0.15 - 0.001), alongX},
        {"capsule along", capsule(0.05, 0.3), Vec3(0.02, 0, 0.15 - 0.002), rotation(pi / 2, Vec3::UnitX())},
        {"cylinder across", cylinder(0.05, 0.6), Vec3(0, 0, 0.15 - 0.001),
         alongX * rotation(0.2, Vec3::UnitZ())},
        {"cylinder standing", cylinder(0.05, 0.2), Vec3(0.01, 0.2, 0.2 - 0.001), Quat::Identity()},
    };
    for (const auto& [name, shape, centre, orientation] : cases)
    {
        std::vector<Contact> onHull, onBox;
        for (const bool hull : {true, false})
        {
            core::Model model;
            model.bodies.push_back(moving("beam", hull ? beamMesh : box(0.2, 1.0, 0.2), Vec3::Zero()));
            model.bodies.push_back(moving(name, shape, centre, orientation));
            (hull ? onHull : onBox) = detectAll(model);
        }
        ASSERT_FALSE(onBox.empty()) << name;
        ASSERT_EQ(onHull.size(), onBox.size()) << name;
        // A lying cylinder's points on an edge take the pair's normal from libccd, which differs
        // between a box and a hull to its tolerance (~1e-8 here); everything else is exact.
        for (std::size_t k = 0; k < onBox.size(); ++k)
        {
            EXPECT_LT((onHull[k].normal_W - onBox[k].normal_W).norm(), 1e-6) << name;
            EXPECT_NEAR(onHull[k].depth, onBox[k].depth, 1e-6) << name;
            EXPECT_LT((onHull[k].point_W - onBox[k].point_W).norm(), 1e-6) << name;
        }
    }
}

// A static triangle mesh (terrain, fixtures) stays triangles. A moving hull or box on it is
// clipped against each touching triangle: the same four corners as on a static box. Every
// shape is pushed out of the mesh, not into it (FCL 0.7 reports a shape against a mesh with
// the normal from the mesh, whichever comes first, and the sphere's depth negated).
TEST(HullContacts, ShapesOnAStaticTriangleMesh)
{
    const core::Shape slabMesh = prismMesh({{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, 0.2);
    const std::vector<std::pair<const char*, core::Shape>> shapes = {
        {"hull", cubeMesh(0.2)},        {"box", box(0.2, 0.2, 0.2)},      {"sphere", sphere(0.1)},
        {"capsule", capsule(0.1, 0.2)}, {"cylinder", cylinder(0.1, 0.2)},
    };
    for (const auto& [name, shape] : shapes)
    {
        // Resting 1 mm deep on the slab's top face (z = 0.2), lying (capsule and cylinder axes along x).
        const bool lying = shape.type == core::ShapeType::Capsule || shape.type == core::ShapeType::Cylinder;
        const Quat orientation = lying ? rotation(pi / 2, Vec3::UnitY()) : Quat::Identity();
        const Vec3 centre(0.1, 0.05, 0.3 - 0.001);
        std::vector<Contact> onMesh, onBox;
        for (const bool meshSlab : {true, false})
        {
            core::Model model;
            model.bodies.push_back(moving(name, shape, centre, orientation));
            model.bodies.push_back(fixed("slab", meshSlab ? slabMesh : box(1, 1, 0.2), Vec3(0, 0, 0.1)));
            (meshSlab ? onMesh : onBox) = detectAll(model);
        }
        ASSERT_FALSE(onMesh.empty()) << name;
        // Capsules and cylinders get FCL's per-triangle GJK/MPR points (iterative, to ~1e-7 m
        // here); the clipped faces and the sphere are exact.
        const double tolerance = lying ? 1e-6 : 1e-9;
        for (const Contact& c : onMesh)
        {
            EXPECT_NEAR(c.normal_W.z(), -1.0, tolerance) << name << ": from the shape down into the slab";
            EXPECT_NEAR(c.depth, 0.001, tolerance) << name;
        }
        if (shape.type == core::ShapeType::Box || shape.type == core::ShapeType::Mesh)
        {
            ASSERT_EQ(onMesh.size(), 4u) << name;
            ASSERT_EQ(onBox.size(), 4u) << name;
            for (std::size_t k = 0; k < 4; ++k)
                EXPECT_LT((onMesh[k].point_W - onBox[k].point_W).norm(), 1e-9) << name;
        }
    }
}

// A non-convex mesh collides as its hull: a box in the notch of an L, a centimetre clear of the
// L's inner faces, touches the hull (which fills the notch up to the diagonal x + y = 0.3) but
// not the L's triangles.
TEST(HullContacts, LShapeCollidesAsItsHull)
{
    core::Model model;
    model.bodies.push_back(moving("L", lShapeMesh(0.1, 0.1), Vec3::Zero()));
    model.bodies.push_back(moving("block", box(0.08, 0.08, 0.08), Vec3(0.15, 0.15, 0)));
    const auto asHull = detectAll(model);
    ASSERT_FALSE(asHull.empty());
    double deepest = 0.0;
    for (const Contact& c : asHull)
    {
        EXPECT_EQ(c.bodyA, 0);
        deepest = std::max(deepest, c.depth);
    }
    // The block's corner (0.11, 0.11) is (0.3 - 0.22) / sqrt(2) inside the diagonal face.
    EXPECT_NEAR(deepest, 0.08 / std::sqrt(2.0), 1e-9);

    ContactDetector triangles(model, 1e-3, MovingMeshes::Triangles);
    std::vector<Contact> asTriangles;
    triangles.detect(core::initialState(model), asTriangles);
    EXPECT_TRUE(asTriangles.empty());
}

// Contacts of hull pairs in a pile of overlapping rocks: the same state gives the same
// contacts, bit for bit, from one detector called twice and from a second detector.
TEST(HullContacts, SameStateSameContacts)
{
    core::Model model;
    model.bodies.push_back(floorBody());
    for (int k = 0; k < 12; ++k)
    {
        const Vec3 p(0.15 * (k % 4), 0.15 * ((k / 4) % 2), 0.08 + 0.1 * (k / 8));
        model.bodies.push_back(movingMesh("rock" + std::to_string(k),
                                          rockMesh(0.09, 6, 10, 0.2, static_cast<unsigned>(k)), p, 1000.0,
                                          rotation(0.4 * k, Vec3(1, 0.2 * k, 0.5))));
    }
    const core::State state = core::initialState(model);
    ContactDetector first(model, 2e-3);
    ContactDetector second(model, 2e-3);
    std::vector<Contact> a, b, c;
    first.detect(state, a);
    first.detect(state, b);
    second.detect(state, c);
    ASSERT_GT(a.size(), 12u);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    for (std::size_t k = 0; k < a.size(); ++k)
    {
        for (const Contact* other : {&b[k], &c[k]})
        {
            EXPECT_EQ(a[k].bodyA, other->bodyA);
            EXPECT_EQ(a[k].bodyB, other->bodyB);
            EXPECT_EQ(a[k].point_W, other->point_W);
            EXPECT_EQ(a[k].normal_W, other->normal_W);
            EXPECT_EQ(a[k].depth, other->depth);
        }
    }
}

} // namespace
} // namespace frontier::collision::test
