// core/state.cpp: initial state, energy and momentum.
#include "core/state.h"

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
