// core/step/positions.cpp: position update, displacements and the carried angular momentum.
#include "core/step/positions.h"

namespace frontier::core
{

namespace
{
// exp of a rotation vector (rad) as a unit quaternion.
Quat rotationFromVector(const Vec3& theta)
{
    const double angle = theta.norm();
    if (angle < 1e-12)
    {
        return Quat(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
    }
    return Quat(Eigen::AngleAxisd(angle, theta / angle));
}
} // namespace

std::vector<std::uint8_t> bodiesHeldInRotation(const Model& model)
{
    std::vector<std::uint8_t> held(model.bodies.size(), 0);
    for (const Joint& joint : model.joints)
    {
        if (!holdsRotation(joint.type))
        {
            continue;
        }
        for (const int body : {joint.parent, joint.child})
        {
            if (isMovingBody(model, body))
            {
                held[static_cast<std::size_t>(body)] = 1;
            }
        }
    }
    return held;
}

void chooseRotationUpdates(const Model& model, const std::vector<std::uint8_t>& heldInRotation,
                           const RowSystem& rows, const State& state, double dt, bool rattle,
                           std::vector<std::uint8_t>& freeRotation)
{
    // docs/method.md §4, eq. (8a), compared squared (no roots): h |w x L| > cTurnRad |L|, and
    // h |w| <= cStepTurnRad for a body a joint holds in rotation (beyond it the free rotations of
    // two bodies so joined differ by too much for the drift correction; exp(h w) turns them alike).
    constexpr double cTurnRad = 1e-6;
    constexpr double cStepTurnRad = 0.25;
    freeRotation.assign(model.bodies.size(), rattle ? 1 : 0);
    if (rattle)
    {
        return;
    }
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        const Vec3& w = state.bodies[i].angularVelocity_W;
        const Vec3 momentum = rows.inertia_W[i] * w; // N m s
        const double hh = dt * dt;
        const bool turns =
            hh * w.cross(momentum).squaredNorm() > cTurnRad * cTurnRad * momentum.squaredNorm();
        const bool slow = hh * w.squaredNorm() <= cStepTurnRad * cStepTurnRad;
        freeRotation[i] = turns && (heldInRotation[i] == 0 || slow) ? 1 : 0;
    }
}

void integratePositions(const Model& model, const std::vector<BodyState>& start,
                        const std::vector<PrincipalAxes>& principal, const RowSystem& rows,
                        const std::vector<std::uint8_t>& freeRotation, double dt, State& state)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        s.position_W = start[i].position_W + dt * s.velocity_W;
        s.orientation_WB =
            freeRotation[i] != 0
                ? rotateFreely(start[i].orientation_WB, principal[i], rows.inertia_W[i] * s.angularVelocity_W,
                               dt)
                : (rotationFromVector(dt * s.angularVelocity_W) * start[i].orientation_WB).normalized();
    }
}

void displacePositions(const Model& model, const BlockVector& displacement, State& state,
                       std::vector<BodyState>& start)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        const Quat turn = rotationFromVector(displacement.body[i].tail<3>());
        s.position_W += displacement.body[i].head<3>();
        s.orientation_WB = (turn * s.orientation_WB).normalized();
        start[i].position_W += displacement.body[i].head<3>();
        start[i].orientation_WB = (turn * start[i].orientation_WB).normalized();
    }
}

void carryAngularMomentum(const Model& model, const std::vector<PrincipalAxes>& principal,
                          const RowSystem& rows, State& state)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const Body& body = model.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        BodyState& s = state.bodies[i];
        const Vec3 momentum = rows.inertia_W[i] * s.angularVelocity_W;
        // I_W^-1 L in the principal frame P of the new orientation: w = R_WP diag(1/I) R_WP^T L.
        const Quat toWorld = s.orientation_WB * principal[i].rotation_BP;
        s.angularVelocity_W = toWorld * (toWorld.conjugate() * momentum).cwiseQuotient(principal[i].moments);
    }
}

} // namespace frontier::core
