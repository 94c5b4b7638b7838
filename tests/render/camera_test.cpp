// tests/render/camera_test.cpp: view matrices, robust up vector, automatic framing.
#include "render/camera.h"

#include <gtest/gtest.h>

namespace frontier::render
{
namespace
{

TEST(Camera, LookingStraightDownUsesPlusYAsUp)
{
    const Mat4 view = lookAt(core::Vec3(0, 0, 3), core::Vec3(0, 0, 0), core::Vec3::UnitZ());
    ASSERT_TRUE(view.allFinite());
    // World +x is screen right, world +y is screen up, the target is 3 m in front.
    EXPECT_NEAR(view(0, 0), 1.0, 1e-12);
    EXPECT_NEAR(view(1, 1), 1.0, 1e-12);
    const Eigen::Vector4d target = view * Eigen::Vector4d(0, 0, 0, 1);
    EXPECT_NEAR(target.z(), -3.0, 1e-12);
    const Eigen::Matrix3d r = view.block<3, 3>(0, 0);
    EXPECT_TRUE((r * r.transpose()).isIdentity(1e-12));
}

TEST(Camera, RobustUpKeepsPreferredUpWhenPossible)
{
    EXPECT_TRUE(robustUp(core::Vec3(1, 1, -0.5), core::Vec3::UnitZ()).isApprox(core::Vec3::UnitZ()));
    EXPECT_LT(std::abs(robustUp(core::Vec3(0, 0, 1), core::Vec3::UnitZ()).z()), 1e-12);
    EXPECT_LT(std::abs(robustUp(core::Vec3(0, 1, 0), core::Vec3::UnitY()).y()), 1e-12);
}

TEST(Camera, FrameBoxSeesEveryCorner)
{
    const core::Vec3 lo(-1.0, -0.5, 0.0);
    const core::Vec3 hi(2.0, 0.5, 1.5);
    const double aspect = 4.0 / 3.0;
    const View v = frameBox(lo, hi, core::Vec3::UnitZ(), 45.0, aspect);
    const Mat4 vp = perspective(v.fovyDegrees, aspect, 0.01, 100.0) * lookAt(v.eye, v.target, v.up);
    for (int i = 0; i < 8; ++i)
    {
        const Eigen::Vector4d corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                                     (i & 4) ? hi.z() : lo.z(), 1.0);
        const Eigen::Vector4d clip = vp * corner;
        ASSERT_GT(clip.w(), 0.0);
        EXPECT_LT(std::abs(clip.x() / clip.w()), 1.0) << "corner " << i;
        EXPECT_LT(std::abs(clip.y() / clip.w()), 1.0) << "corner " << i;
    }
    EXPECT_GT(v.eye.z(), hi.z()); // looking down on the scene
}

TEST(Camera, PerspectiveMapsNearAndFarToClipRange)
{
    const Mat4 p = perspective(60.0, 1.5, 0.1, 50.0);
    const Eigen::Vector4d n = p * Eigen::Vector4d(0, 0, -0.1, 1);
    const Eigen::Vector4d f = p * Eigen::Vector4d(0, 0, -50.0, 1);
    EXPECT_NEAR(n.z() / n.w(), -1.0, 1e-9);
    EXPECT_NEAR(f.z() / f.w(), 1.0, 1e-9);
}

} // namespace
} // namespace frontier::render
