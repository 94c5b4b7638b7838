// tests/support/collision_response.cpp: sticking/sliding collision response (docs/method.md §1) on
// the joint solver of choice, by Schur complement of the three collision rows.
#include "tests/support/collision_response.h"

#include "core/contact_rows.h"

#include <cmath>

namespace frontier::core
{

namespace
{
Vec6 bodyVelocity(const BodyState& s)
{
    Vec6 u;
    u << s.velocity_W, s.angularVelocity_W;
    return u;
}
} // namespace

CollisionOutcome respondToCollision(const Model& model, const State& state, const CollisionEvent& event,
                                    SolverKind solverKind, int pgsIterations)
{
    const FrontierLayout layout = buildFrontierLayout(model);
    RowSystem system;
    assembleRows(model, layout, state, 0.0, system); // an instant: drives give no impulse
    auto solver = makeSolver(solverKind, pgsIterations);
    solver->factor(system);

    const std::size_t nb = model.bodies.size();
    const std::size_t nj = model.joints.size();
    const ContactRows rows =
        contactRows(model, state, event.bodyA, event.bodyB, event.point_W, event.normal_W);
    const bool bMoves = isMovingBody(model, event.bodyB);
    auto rowVelocity = [&](const BlockVector& x) -> Eigen::Vector3d
    {
        Eigen::Vector3d v = rows.J_A * x.body[static_cast<std::size_t>(event.bodyA)];
        if (bMoves)
        {
            v += rows.J_B * x.body[static_cast<std::size_t>(event.bodyB)];
        }
        return v;
    };

    // Base: momenta of the pre-impact velocities, joint rows kept (c = 0).
    BlockVector rhs, base;
    rhs.resize(nb, nj);
    rhs.setZero();
    BlockVector pre;
    pre.resize(nb, nj);
    pre.setZero();
    for (std::size_t i = 0; i < nb; ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        pre.body[i] = bodyVelocity(state.bodies[i]);
        rhs.body[i].head<3>() = system.mass[i] * pre.body[i].head<3>();
        rhs.body[i].tail<3>() = system.inertia_W[i] * pre.body[i].tail<3>();
    }
    solver->solve(rhs, base);
    const Eigen::Vector3d before = rowVelocity(pre);

    // Response to a unit impulse along each collision row: one solve each (columns of G).
    BlockVector unit[3];
    Mat3 G;
    for (int k = 0; k < 3; ++k)
    {
        rhs.setZero();
        rhs.body[static_cast<std::size_t>(event.bodyA)] = rows.J_A.row(k).transpose();
        if (bMoves)
        {
            rhs.body[static_cast<std::size_t>(event.bodyB)] = rows.J_B.row(k).transpose();
        }
        solver->solve(rhs, unit[k]);
        G.col(k) = rowVelocity(unit[k]);
    }

    CollisionOutcome out;
    out.approachSpeed = -before(0);
    const Eigen::Vector3d now = rowVelocity(base);
    // Sticking: normal -> -e * before, tangential -> 0.
    const Eigen::Vector3d target(-event.restitution * before(0), 0.0, 0.0);
    Eigen::Vector3d lambda = G.ldlt().solve(target - now);
    const double tangential = lambda.tail<2>().norm();
    if (tangential > event.friction * lambda(0))
    {
        // Sliding: friction mu P_N opposing the sliding direction.
        Eigen::Vector2d slide = before.tail<2>();
        if (slide.norm() < 1e-12)
        {
            slide = -lambda.tail<2>();
        }
        const Eigen::Vector2d dir =
            slide.norm() > 0.0 ? Eigen::Vector2d(slide.normalized()) : Eigen::Vector2d::Zero();
        // lambda = P_N (1, -mu dir): friction on A is along +slide (A slides by -slide relative to B).
        const Eigen::Vector3d shape(1.0, -event.friction * dir(0), -event.friction * dir(1));
        const double pn = (target(0) - now(0)) / G.row(0).dot(shape);
        lambda = pn * shape;
        out.sliding = true;
    }

    out.bodies = state.bodies;
    out.jointImpulses.assign(nj, Vec6::Zero());
    for (std::size_t i = 0; i < nb; ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        Vec6 u = base.body[i];
        for (int k = 0; k < 3; ++k)
        {
            u += lambda(k) * unit[k].body[i];
        }
        out.bodies[i].velocity_W = u.head<3>();
        out.bodies[i].angularVelocity_W = u.tail<3>();
    }
    for (std::size_t j = 0; j < nj; ++j)
    {
        Vec6 l = base.joint[j];
        for (int k = 0; k < 3; ++k)
        {
            l += lambda(k) * unit[k].joint[j];
        }
        out.jointImpulses[j] = l;
    }
    out.impulseOnA_W = (rows.J_A.leftCols<3>().transpose() * lambda);
    return out;
}

} // namespace frontier::core
