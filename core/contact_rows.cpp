// core/contact_rows.cpp: the contact Jacobian (three rows per contact point), for the contact
// blocks of every step (core/extra_rows.cpp) and the one-collision response of the tests.
#include "core/contact_rows.h"

#include <cmath>

namespace frontier::core
{

namespace
{
// Rows 0 .. count - 1 of the collision rows into J_A, J_B (3 x 6 or 6 x 6), with the directions.
template <class Rows>
void fillContactRows(const Model& model, const State& state, int bodyA, int bodyB, const Vec3& point_W,
                     const Vec3& normal_W, int count, Rows& J_A, Rows& J_B, Mat3& directions)
{
    const Vec3 n = normal_W.normalized();
    const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 t1 = (helper - helper.dot(n) * n).normalized();
    const Vec3 t2 = n.cross(t1);
    directions.col(0) = n;
    directions.col(1) = t1;
    directions.col(2) = t2;
    const Vec3 r_A = point_W - state.bodies[static_cast<std::size_t>(bodyA)].position_W;
    const bool bMoves = isMovingBody(model, bodyB);
    const Vec3 r_B =
        bMoves ? Vec3(point_W - state.bodies[static_cast<std::size_t>(bodyB)].position_W) : Vec3::Zero();
    for (int k = 0; k < count; ++k)
    {
        const Vec3 d = directions.col(k);
        J_A.template block<1, 3>(k, 0) = -d.transpose();
        J_A.template block<1, 3>(k, 3) = -r_A.cross(d).transpose();
        if (bMoves)
        {
            J_B.template block<1, 3>(k, 0) = d.transpose();
            J_B.template block<1, 3>(k, 3) = r_B.cross(d).transpose();
        }
    }
}
} // namespace

ContactRows contactRows(const Model& model, const State& state, int bodyA, int bodyB, const Vec3& point_W,
                        const Vec3& normal_W)
{
    ContactRows rows;
    fillContactRows(model, state, bodyA, bodyB, point_W, normal_W, 3, rows.J_A, rows.J_B, rows.directions);
    return rows;
}

void writeContactRows(const Model& model, const State& state, int bodyA, int bodyB, const Vec3& point_W,
                      const Vec3& normal_W, int count, Mat6& J_A, Mat6& J_B)
{
    Mat3 directions;
    fillContactRows(model, state, bodyA, bodyB, point_W, normal_W, count, J_A, J_B, directions);
}

} // namespace frontier::core
