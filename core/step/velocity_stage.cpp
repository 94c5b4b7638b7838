// core/step/velocity_stage.cpp: gravity kick, momentum right-hand side, pose comparison.
#include "core/step/velocity_stage.h"

namespace frontier::core
{

void kickByGravity(const Model& model, State& state, double h)
{
    const Vec3 dv = h * model.simulation.gravity;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            state.bodies[i].velocity_W += dv;
        }
    }
}

void setMomentumRhs(const Model& model, const RowSystem& rows, const State& state, double tEnd,
                    double driveStep, const Actuation& actuation, BlockVector& rhs)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        const BodyState& s = state.bodies[i];
        rhs.body[i].head<3>() = rows.mass[i] * s.velocity_W;
        rhs.body[i].tail<3>() = rows.inertia_W[i] * s.angularVelocity_W;
    }
    for (Vec6& c : rhs.joint)
    {
        c.setZero();
    }
    actuation.setRowTargets(state, tEnd, driveStep, rhs); // servos and motors in their blocks
}

bool samePose(const Model& model, const State& state, const std::vector<BodyState>& pose)
{
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const BodyState& now = state.bodies[i];
        const BodyState& then = pose[i];
        if (now.position_W != then.position_W || now.orientation_WB.coeffs() != then.orientation_WB.coeffs())
        {
            return false;
        }
    }
    return true;
}

} // namespace frontier::core
