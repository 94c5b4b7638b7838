// core/free_rotation.cpp: principal axes and the split free rigid-body rotation.
#include "core/free_rotation.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace frontier::core
{

PrincipalAxes principalAxes(const Mat3& inertia_B)
{
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(inertia_B);
    Mat3 axes = eigen.eigenvectors(); // columns: principal axes in the body frame
    if (axes.determinant() < 0.0)
    {
        axes.col(2) = -axes.col(2); // a proper rotation
    }
    PrincipalAxes result;
    result.rotation_BP = Quat(axes).normalized();
    result.moments = eigen.eigenvalues();
    return result;
}

Quat rotateFreely(const Quat& orientation_WB, const PrincipalAxes& axes, const Vec3& angularMomentum_W,
                  double h)
{
    Quat q_WP = orientation_WB * axes.rotation_BP;
    Vec3 pi = q_WP.conjugate() * angularMomentum_W; // angular momentum in the principal frame
    const auto rotateAbout = [&](int k, double t)
    {
        // Exact flow of pi_k^2 / (2 I_k): a rotation r = (c, s e_k) about principal axis k at rate
        // pi_k / I_k. q_WP r and r^-1 pi written out for r's two nonzero components: the same
        // products and sums as the general quaternion formulas, without their terms that are zero.
        const double half = 0.5 * (t * pi(k) / axes.moments(k));
        const double c = std::cos(half);
        const double s = std::sin(half);
        const int i = (k + 1) % 3;
        const int j = (k + 2) % 3;
        Vec3 v = q_WP.vec();
        const double w = q_WP.w();
        q_WP.w() = w * c - v(k) * s;
        q_WP.vec()(k) = w * s + v(k) * c;
        q_WP.vec()(i) = v(i) * c + v(j) * s;
        q_WP.vec()(j) = v(j) * c - v(i) * s;
        // r^-1 pi = pi + 2c (a x pi) + 2 a x (a x pi), a = -s e_k, as Eigen evaluates it.
        const double ui = 2.0 * (s * pi(j));  // (a x pi)_i doubled
        const double uj = -2.0 * (s * pi(i)); // (a x pi)_j doubled
        v(i) = pi(i) + c * ui + s * uj;
        v(j) = pi(j) + c * uj - s * ui;
        pi(i) = v(i);
        pi(j) = v(j);
    };
    rotateAbout(0, 0.5 * h);
    rotateAbout(1, 0.5 * h);
    rotateAbout(2, h);
    rotateAbout(1, 0.5 * h);
    rotateAbout(0, 0.5 * h);
    return (q_WP * axes.rotation_BP.conjugate()).normalized();
}

} // namespace frontier::core
