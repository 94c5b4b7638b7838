// render/camera.h: view and projection matrices (Eigen, column-major) and automatic framing.
#pragma once

#include "core/model.h"

#include <Eigen/Core>
#include <vector>

namespace frontier::render
{

using Mat4 = Eigen::Matrix4d;

// An up direction usable with a view along `forward`: `preferredUp` unless it is (nearly) parallel
// to `forward` (e.g. looking straight down), then the world axis most perpendicular to `forward`.
core::Vec3 robustUp(const core::Vec3& forward, const core::Vec3& preferredUp);

// World to camera (OpenGL convention: the camera looks along -z, y up).
Mat4 lookAt(const core::Vec3& eye, const core::Vec3& target, const core::Vec3& preferredUp);
// OpenGL clip matrices; fovy in degrees.
Mat4 perspective(double fovyDegrees, double aspect, double zNear, double zFar);
Mat4 orthographic(double left, double right, double bottom, double top, double zNear, double zFar);

struct View
{
    core::Vec3 eye = core::Vec3(3, -3, 2);
    core::Vec3 target = core::Vec3::Zero();
    core::Vec3 up = core::Vec3::UnitZ(); // preferred up, made robust by lookAt
    double fovyDegrees = 45.0;
};

// The tightest camera looking from the usual three-quarter direction (azimuth -45 deg, elevation
// 25 deg relative to `up`) that keeps every point inside the central `fill` fraction of the image
// in both directions, centred on the points' extent (so the points touch the margin on the
// limiting axis and are centred on the other). The camera is never closer to the points' bounding
// box centre than `minRadius` (m) over the sine of the smaller half field of view, so a tiny scene
// is not magnified without limit. Closed form: with the camera axes s (right), u (up), f (forward)
// fixed, "|s.(p - e)| <= k f.(p - e)" for every point p is two linear bounds on (s.e, f.e), and the
// largest f.e meeting the bounds of both axes is the closest eye.
// `topFill` (when positive and below `fill`) keeps the points below that fraction of the upper
// half instead, leaving room for a caption.
View framePoints(const std::vector<core::Vec3>& points, const core::Vec3& up, double fovyDegrees,
                 double aspect, double fill = 0.9, double minRadius = 0.25, double topFill = 0.0);

// framePoints of the eight corners of the axis-aligned box [lo, hi].
View frameBox(const core::Vec3& lo, const core::Vec3& hi, const core::Vec3& up, double fovyDegrees,
              double aspect);

} // namespace frontier::render
