// tests/support/collision_response.h: the paper's collision response (docs/method.md §1): one collision of
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

} // namespace frontier::core
