// core/free_rotation.cpp: principal axes and the split free rigid-body rotation.
#include "core/free_rotation.h"

#include <Eigen/Eigenvalues>

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
    const auto rotateAbout = [&](int axis, double t)
    {
        // Exact flow of pi_k^2 / (2 I_k): a rotation about principal axis k at rate pi_k / I_k.
        const Quat r(Eigen::AngleAxisd(t * pi(axis) / axes.moments(axis), Vec3::Unit(axis)));
        q_WP = q_WP * r;
        pi = r.conjugate() * pi;
    };
    rotateAbout(0, 0.5 * h);
    rotateAbout(1, 0.5 * h);
    rotateAbout(2, h);
    rotateAbout(1, 0.5 * h);
    rotateAbout(0, 0.5 * h);
    return (q_WP * axes.rotation_BP.conjugate()).normalized();
}

} // namespace frontier::core
