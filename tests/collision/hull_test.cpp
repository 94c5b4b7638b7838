// tests/collision/hull_test.cpp: convex hulls of meshes (collision/convex_hull.cpp). Oracles:
// the cube's own corners, faces and volume (the divergence theorem over the hull's faces).
#include "collision/convex_hull.h"
#include "test_models.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
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

} // namespace
} // namespace frontier::collision::test
