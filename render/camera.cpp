// render/camera.cpp: view and projection matrices and automatic framing.
#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace frontier::render
{

core::Vec3 robustUp(const core::Vec3& forward, const core::Vec3& preferredUp)
{
    const core::Vec3 f = forward.normalized();
    core::Vec3 up = preferredUp.norm() > 0.0 ? preferredUp.normalized() : core::Vec3::UnitZ();
    if (std::abs(f.dot(up)) < 0.999)
    {
        return up;
    }
    // Looking along the up axis: take the world axis least aligned with the view, ties broken
    // towards y (so a camera looking straight down at a z-up world shows +y upwards).
    const core::Vec3 candidates[3] = {core::Vec3::UnitY(), core::Vec3::UnitX(), core::Vec3::UnitZ()};
    core::Vec3 best = candidates[0];
    double bestDot = 2.0;
    for (const core::Vec3& c : candidates)
    {
        const double d = std::abs(f.dot(c));
        if (d < bestDot - 1e-9)
        {
            best = c;
            bestDot = d;
        }
    }
    return best;
}

Mat4 lookAt(const core::Vec3& eye, const core::Vec3& target, const core::Vec3& preferredUp)
{
    core::Vec3 f = target - eye;
    if (f.norm() < 1e-12)
    {
        f = -core::Vec3::UnitZ();
    }
    f.normalize();
    const core::Vec3 s = f.cross(robustUp(f, preferredUp)).normalized();
    const core::Vec3 u = s.cross(f);
    Mat4 m = Mat4::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(eye);
    m(1, 3) = -u.dot(eye);
    m(2, 3) = f.dot(eye);
    return m;
}

Mat4 perspective(double fovyDegrees, double aspect, double zNear, double zFar)
{
    const double t = 1.0 / std::tan(0.5 * fovyDegrees * std::numbers::pi / 180.0);
    Mat4 m = Mat4::Zero();
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = (zFar + zNear) / (zNear - zFar);
    m(2, 3) = 2.0 * zFar * zNear / (zNear - zFar);
    m(3, 2) = -1.0;
    return m;
}

Mat4 orthographic(double left, double right, double bottom, double top, double zNear, double zFar)
{
    Mat4 m = Mat4::Identity();
    m(0, 0) = 2.0 / (right - left);
    m(1, 1) = 2.0 / (top - bottom);
    m(2, 2) = -2.0 / (zFar - zNear);
    m(0, 3) = -(right + left) / (right - left);
    m(1, 3) = -(top + bottom) / (top - bottom);
    m(2, 3) = -(zFar + zNear) / (zFar - zNear);
    return m;
}

namespace
{
// The automatic camera's axes as lookAt builds them: forward f (25 degrees down, from +x -y for
// z-up), sideways s, upwards v; u the unit up.
struct CameraAxes
{
    core::Vec3 u, f, s, v;
};

CameraAxes automaticAxes(const core::Vec3& up)
{
    const core::Vec3 u = up.norm() > 0.0 ? up.normalized() : core::Vec3::UnitZ();
    // Horizontal basis (a, b) so that for z-up a = x, b = y.
    const core::Vec3 ref =
        std::abs(u.dot(core::Vec3::UnitX())) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY();
    const core::Vec3 a = (ref - ref.dot(u) * u).normalized();
    const core::Vec3 b = u.cross(a);
    const double elevation = 25.0 * std::numbers::pi / 180.0;
    const core::Vec3 horizontal = (a - b).normalized(); // from the scene towards the camera (+x, -y)
    const core::Vec3 towardsEye = std::cos(elevation) * horizontal + std::sin(elevation) * u;

    // Camera axes as lookAt builds them.
    const core::Vec3 f = -towardsEye;
    const core::Vec3 s = f.cross(robustUp(f, u)).normalized();
    const core::Vec3 v = s.cross(f);
    return {u, f, s, v};
}
} // namespace

View framePoints(const std::vector<core::Vec3>& points, const core::Vec3& up, double fovyDegrees,
                 double aspect, double fill, double minRadius, double topFill)
{
    const auto [u, f, s, v] = automaticAxes(up);

    const double tanY = std::tan(0.5 * std::clamp(fovyDegrees, 1.0, 170.0) * std::numbers::pi / 180.0);
    const double tanX = tanY * aspect;
    const double kx = fill * tanX;
    const double ky = fill * tanY;
    const double kTop = (topFill > 0.0 ? std::min(topFill, fill) : fill) * tanY;

    core::Vec3 lo = core::Vec3::Constant(1e300);
    core::Vec3 hi = core::Vec3::Constant(-1e300);
    // For axis w and slopes k+ (top or right) and k-: w.e - k+ f.e >= max(w.p - k+ f.p) = plus and
    // -w.e - k- f.e >= max(-w.p - k- f.p) = minus; so f.e <= -(plus + minus) / (k+ + k-), and w.e
    // in the middle of [plus + k+ f.e, -minus - k- f.e] centres the points.
    double plusX = -1e300;
    double minusX = -1e300;
    double plusY = -1e300;
    double minusY = -1e300;
    for (const core::Vec3& p : points)
    {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        const double fp = f.dot(p);
        plusX = std::max(plusX, s.dot(p) - kx * fp);
        minusX = std::max(minusX, -s.dot(p) - kx * fp);
        plusY = std::max(plusY, v.dot(p) - kTop * fp);
        minusY = std::max(minusY, -v.dot(p) - ky * fp);
    }
    if (points.empty())
    {
        lo = core::Vec3::Constant(-1.0);
        hi = core::Vec3::Constant(1.0);
        return framePoints({lo, hi}, up, fovyDegrees, aspect, fill, minRadius, topFill);
    }
    double forward = std::min(-(plusX + minusX) / (2.0 * kx), -(plusY + minusY) / (kTop + ky));

    const core::Vec3 centre = 0.5 * (lo + hi);
    const double minDistance = minRadius / std::sin(std::atan(std::min(tanX, tanY)));
    forward = std::min(forward, f.dot(centre) - minDistance);
    // Centred between the bounds the chosen depth leaves on each axis.
    const double sideways = 0.5 * (plusX - minusX);
    const double upwards = 0.5 * ((plusY + kTop * forward) + (-minusY - ky * forward));

    View view;
    view.eye = sideways * s + upwards * v + forward * f;
    // Look straight ahead (along f), at the depth of the points' centre.
    view.target = view.eye + std::max(f.dot(centre) - forward, 1e-3) * f;
    view.up = u;
    view.fovyDegrees = fovyDegrees;
    return view;
}

View frameBox(const core::Vec3& lo, const core::Vec3& hi, const core::Vec3& up, double fovyDegrees,
              double aspect)
{
    std::vector<core::Vec3> corners;
    for (int i = 0; i < 8; ++i)
    {
        corners.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
    }
    return framePoints(corners, up, fovyDegrees, aspect);
}

} // namespace frontier::render
