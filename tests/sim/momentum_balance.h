// tests/sim/momentum_balance.h: Newton's second law over one step, for every moving body, from
// what the simulator reports it passed (core::Simulator::jointChildImpulses, contactImpulses):
//     m (v' - v) = m g h + sum of its joints' impulses (as child, minus those as parent)
//                        + sum of its contacts' impulses (as body B, minus those as body A).
// Penetration removal and drift displacement move positions, not velocities, so this holds to
// round-off for the linear impulses (those of ball, hinge, universal and weld rows, and of rails
// to the world, which do not depend on the pose they are reported at).
#pragma once

#include "core/simulator.h"

#include <algorithm>
#include <span>
#include <string>
#include <vector>

namespace frontier::test
{

struct SecondLawResidual
{
    double relative = 0.0; // the largest |m (v' - v) - m g h - received| over the bodies, over `scale`
    double scale = 0.0;    // N s: the step's largest joint or contact impulse or weight impulse
    std::string body;      // where the largest residual is
};

inline SecondLawResidual secondLawResidual(const core::Model& model, const core::State& before,
                                           const core::State& after, const std::vector<core::Vec6>& joints,
                                           std::span<const core::ContactImpulse> contacts)
{
    std::vector<core::Vec3> received(model.bodies.size(), core::Vec3::Zero()); // N s
    SecondLawResidual out;
    auto pass = [&](int from, int to, const core::Vec3& impulse)
    {
        received[static_cast<std::size_t>(to)] += impulse;
        if (core::isMovingBody(model, from))
        {
            received[static_cast<std::size_t>(from)] -= impulse;
        }
        out.scale = std::max(out.scale, impulse.norm());
    };
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        pass(model.joints[k].parent, model.joints[k].child, joints[k].head<3>());
    }
    for (const core::ContactImpulse& c : contacts)
    {
        pass(c.contact.bodyA, c.contact.bodyB, c.impulse_W);
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const core::Body& body = model.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        const core::Vec3 gravity = body.mass * model.simulation.dt * model.simulation.gravity;
        out.scale = std::max(out.scale, gravity.norm());
        const core::Vec3 change = body.mass * (after.bodies[i].velocity_W - before.bodies[i].velocity_W);
        const double error = (change - gravity - received[i]).norm();
        if (error >= worst)
        {
            worst = error;
            out.body = body.name;
        }
    }
    out.relative = out.scale > 0.0 ? worst / out.scale : 0.0;
    return out;
}

} // namespace frontier::test
