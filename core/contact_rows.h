// core/contact_rows.h: the rows of one contact point between body A and body B (or the world):
// normal n and tangents t1, t2, as the Jacobian of the relative velocity of the contact point.
#pragma once

#include "core/joints/joint_rows.h" // Mat6
#include "core/model.h"
#include "core/state.h"

namespace frontier::core
{

// The three collision rows: row k is d_k . (velocity of B's point - velocity of A's point),
// d_0 = n, d_1, d_2 tangents. J_A, J_B are 3 x 6 (J_B zero for a world/static B).
struct ContactRows
{
    Eigen::Matrix<double, 3, 6> J_A = Eigen::Matrix<double, 3, 6>::Zero();
    Eigen::Matrix<double, 3, 6> J_B = Eigen::Matrix<double, 3, 6>::Zero();
    Mat3 directions = Mat3::Identity(); // columns n, t1, t2
};
ContactRows contactRows(const Model& model, const State& state, int bodyA, int bodyB, const Vec3& point_W,
                        const Vec3& normal_W);
// The same rows, the first `count` of them, written into rows 0 .. count - 1 of J_A and J_B (the
// 6 x 6 storage of an extra-row block; other rows untouched, J_B untouched for a world/static B).
void writeContactRows(const Model& model, const State& state, int bodyA, int bodyB, const Vec3& point_W,
                      const Vec3& normal_W, int count, Mat6& J_A, Mat6& J_B);

} // namespace frontier::core
