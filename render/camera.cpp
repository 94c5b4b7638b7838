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

View frameBox(const core::Vec3& lo, const core::Vec3& hi, const core::Vec3& up, double fovyDegrees,
              double aspect)
{
    const core::Vec3 u = up.norm() > 0.0 ? up.normalized() : core::Vec3::UnitZ();
    // Horizontal basis (a, b) so that for z-up a = x, b = y.
    const core::Vec3 ref =
        std::abs(u.dot(core::Vec3::UnitX())) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY();
    const core::Vec3 a = (ref - ref.dot(u) * u).normalized();
    const core::Vec3 b = u.cross(a);

    const core::Vec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * (hi - lo).norm(), 0.25);
    const double elevation = 25.0 * std::numbers::pi / 180.0;
    const core::Vec3 horizontal = (a - b).normalized(); // from the centre towards the camera (+x, -y)
    const core::Vec3 dir = std::cos(elevation) * horizontal + std::sin(elevation) * u;

    const double halfFovY = 0.5 * fovyDegrees * std::numbers::pi / 180.0;
    const double tanY = std::tan(halfFovY);
    const double tanX = tanY * aspect;
    // The smallest distance at which all eight corners lie inside 90 % of the view.
    auto fits = [&](double distance)
    {
        const Mat4 view = lookAt(centre + distance * dir, centre, u);
        for (int i = 0; i < 8; ++i)
        {
            const Eigen::Vector4d corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                                         (i & 4) ? hi.z() : lo.z(), 1.0);
            const Eigen::Vector4d p = view * corner;
            const double depth = -p.z();
            if (depth < 0.1 * distance || std::abs(p.x()) > 0.9 * depth * tanX ||
                std::abs(p.y()) > 0.9 * depth * tanY)
            {
                return false;
            }
        }
        return true;
    };
    double far = radius / std::sin(std::atan(std::min(tanX, tanY)));
    for (int i = 0; i < 60 && !fits(far); ++i)
    {
        far *= 1.25;
    }
    double near = 0.0;
    for (int i = 0; i < 40; ++i)
    {
        const double mid = 0.5 * (near + far);
        (fits(mid) ? far : near) = mid;
    }
    const double distance = far;

    View view;
    view.target = centre;
    view.eye = centre + distance * dir;
    view.up = u;
    view.fovyDegrees = fovyDegrees;
    return view;
}

} // namespace frontier::render
