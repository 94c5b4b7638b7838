// core/collision_response.h: the paper's collision response (docs/method.md §1): one collision of
// articulated bodies, Moore and Wilhelms' impulse model with restitution and Coulomb friction.
//
// The collision is three rows (normal n, tangents t1, t2) at the contact point between body A
// and body B (or the world). Sticking: after the impact the normal relative velocity is -e times
// the one before and the contact point does not slide. Sliding (when the sticking impulse leaves
// the friction cone |P_T| <= mu P_N): the friction impulse is mu P_N against the pre-impact
// sliding direction (or, with no pre-impact sliding, against the sticking impulse's tangential
// part), and only the normal condition is kept. The rows are solved together with every joint,
// exactly: the joint system is factored once and the 3x3 collision system (its Schur complement
// G = J_c A^-1 J_c^T, docs/method.md §5) takes three more O(n) solves.
#pragma once

#include "core/impulse_solver.h"

namespace frontier::core
{

struct CollisionEvent
{
    int bodyA = 0;                 // a moving body
    int bodyB = cWorld;            // another body, or cWorld / a static body
    Vec3 point_W = Vec3::Zero();   // contact point (m)
    Vec3 normal_W = Vec3::UnitZ(); // unit, from A towards B (approaching: (v_B - v_A) . n < 0)
    double restitution = 0.0;      // Newton e
    double friction = 0.0;         // Coulomb mu
};

struct CollisionOutcome
{
    std::vector<BodyState> bodies;    // post-impact state (poses unchanged)
    Vec3 impulseOnA_W = Vec3::Zero(); // collision impulse on A (N s); B receives the negative
    std::vector<Vec6> jointImpulses;  // lambda per joint index (N s / N m s), zero for loop joints
    bool sliding = false;
    double approachSpeed = 0.0; // -(v_B - v_A) . n before the impact (m/s)
};

CollisionOutcome respondToCollision(const Model& model, const State& state, const CollisionEvent& event,
                                    SolverKind solver, int pgsIterations = 20);

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
