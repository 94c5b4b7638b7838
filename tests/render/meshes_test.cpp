// tests/render/meshes_test.cpp: tessellated shapes are closed, outward-facing and the right size.
#include "render/meshes.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace frontier::render
{
namespace
{

// Signed volume by the divergence theorem: positive when the triangles face outwards.
double signedVolume(const MeshData& m)
{
    double v = 0.0;
    for (int t = 0; t + 2 < m.vertexCount(); t += 3)
    {
        auto p = [&](int k)
        {
            const float* f = &m.vertices[static_cast<std::size_t>(6 * (t + k))];
            return core::Vec3(f[0], f[1], f[2]);
        };
        v += p(0).dot(p(1).cross(p(2))) / 6.0;
    }
    return v;
}

void expectUnitNormals(const MeshData& m)
{
    for (int i = 0; i < m.vertexCount(); ++i)
    {
        const float* f = &m.vertices[static_cast<std::size_t>(6 * i + 3)];
        ASSERT_NEAR(std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]), 1.0, 1e-5);
    }
}

TEST(Meshes, VolumesMatchTheShapes)
{
    const double pi = std::numbers::pi;
    const MeshData box = boxMesh(core::Vec3(1, 2, 3));
    EXPECT_EQ(box.vertexCount(), 36);
    EXPECT_NEAR(signedVolume(box), 6.0, 1e-5);

    const MeshData sphere = sphereMesh(0.5, 32, 16);
    EXPECT_NEAR(signedVolume(sphere), 4.0 / 3.0 * pi * 0.125, 0.02 * 0.52);

    const MeshData cylinder = cylinderMesh(0.3, 1.0, 32);
    EXPECT_NEAR(signedVolume(cylinder), pi * 0.09 * 1.0, 0.02 * 0.28);

    const MeshData capsule = capsuleMesh(0.2, 0.6, 32, 8);
    EXPECT_NEAR(signedVolume(capsule), pi * 0.04 * 0.6 + 4.0 / 3.0 * pi * 0.008, 0.02 * 0.11);

    for (const MeshData* m : {&box, &sphere, &cylinder, &capsule})
    {
        expectUnitNormals(*m);
    }
}

TEST(Meshes, TriangleMeshIsFlatShadedAndSkipsBadTriangles)
{
    const std::vector<core::Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<std::array<int, 3>> t = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2},
                                               {1, 2, 3}, {0, 0, 1}, {0, 1, 9}};
    const MeshData m = triangleMesh(v, t);
    EXPECT_EQ(m.vertexCount(), 12);
    EXPECT_NEAR(signedVolume(m), 1.0 / 6.0, 1e-6);
    expectUnitNormals(m);
    // The first triangle lies in z = 0 and faces -z.
    EXPECT_FLOAT_EQ(m.vertices[5], -1.0f);
}

} // namespace
} // namespace frontier::render
