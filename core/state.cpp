// core/state.cpp: initial state, energy and momentum.
#include "core/state.h"

#include <cmath>
#include <sstream>

namespace frontier::core
{

State initialState(const Model& model)
{
    State state;
    state.bodies.reserve(model.bodies.size());
    for (const Body& body : model.bodies)
    {
        BodyState s;
        s.position_W = body.position_W;
        s.orientation_WB = body.orientation_WB.normalized();
        if (!body.isStatic)
        {
            s.velocity_W = body.velocity_W;
            s.angularVelocity_W = body.angularVelocity_W;
        }
        state.bodies.push_back(s);
    }
    // The joint frames are set at the model's initial pose (setJointFrames): every angle is 0.
    state.jointAngles.assign(model.joints.size(), 0.0);
    return state;
}

double bodyEnergyScale(const Model& model, std::size_t i, const BodyState& state)
{
    const Body& body = model.bodies[i];
    const double kinetic =
        0.5 * body.mass * state.velocity_W.squaredNorm() +
        0.5 * state.angularVelocity_W.dot(worldInertia(body, state) * state.angularVelocity_W);
    return kinetic + std::abs(body.mass * model.simulation.gravity.dot(state.position_W));
}

std::string startingStateDefect(const Model& model, std::size_t i)
{
    const Body& body = model.bodies[i];
    const auto beyond = [](const char* quantity, double value, const char* range)
    {
        std::ostringstream text;
        text << "its starting " << quantity << " is " << value << "; expected " << range;
        return text.str();
    };
    if (!isPosition(body.position_W))
    {
        return beyond("distance from the origin", body.position_W.stableNorm(), cPositionRange);
    }
    if (body.isStatic)
    {
        return {};
    }
    if (!(body.velocity_W.norm() <= cMaxSpeed))
    {
        return beyond("speed", body.velocity_W.stableNorm(), cSpeedRange);
    }
    if (!(body.angularVelocity_W.norm() <= cMaxAngularSpeed))
    {
        return beyond("angular speed", body.angularVelocity_W.stableNorm(), cAngularSpeedRange);
    }
    BodyState s;
    s.position_W = body.position_W;
    s.orientation_WB = body.orientation_WB.normalized();
    s.velocity_W = body.velocity_W;
    s.angularVelocity_W = body.angularVelocity_W;
    if (!std::isfinite(bodyEnergyScale(model, i, s)))
    {
        std::ostringstream text;
        text << "its initial energy is not finite (mass " << body.mass << " kg, gravity "
             << model.simulation.gravity.norm()
             << " m/s^2: too large for doubles); no run could report its energy";
        return text.str();
    }
    return {};
}

Mat3 worldInertia(const Body& body, const BodyState& state)
{
    return worldInertia(body, state.orientation_WB.toRotationMatrix());
}

Mat3 worldInertia(const Body& body, const Mat3& R_WB)
{
    return R_WB * body.inertia_B * R_WB.transpose();
}

double kineticEnergy(const Model& model, const State& state)
{
    double energy = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const Body& body = model.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        const BodyState& s = state.bodies[i];
        energy += 0.5 * body.mass * s.velocity_W.squaredNorm();
        // w . I_W w = w_B . I_B w_B with w_B = R^T w: one rotation of a vector instead of
        // forming R I_B R^T (the run loop evaluates this every step).
        const Vec3 w_B = s.orientation_WB.toRotationMatrix().transpose() * s.angularVelocity_W;
        energy += 0.5 * w_B.dot(body.inertia_B * w_B);
    }
    return energy;
}

double totalEnergy(const Model& model, const State& state)
{
    double potential = 0.0; // J, zero at the origin
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            potential -= model.bodies[i].mass * model.simulation.gravity.dot(state.bodies[i].position_W);
        }
    }
    return kineticEnergy(model, state) + potential;
}

Momentum totalMomentum(const Model& model, const State& state)
{
    Momentum p;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const Body& body = model.bodies[i];
        if (body.isStatic)
        {
            continue;
        }
        const BodyState& s = state.bodies[i];
        const Vec3 linear = body.mass * s.velocity_W;
        p.linear += linear;
        p.angular += s.position_W.cross(linear) + worldInertia(body, s) * s.angularVelocity_W;
    }
    return p;
}

} // namespace frontier::core
