// tests/sim/joint_models.h: one-joint models built in code for the joint angle, limit, damping
// and friction tests: a rod on a hinge, a box spinning on a hinge through its centre, a box
// sliding on a rail, and a hanging chain of hinged rods.
#pragma once

#include "core/model.h"

#include <array>
#include <optional>
#include <string>

namespace frontier::sim::test
{

// Both integrators, for tests that hold for each.
inline constexpr core::IntegratorKind cIntegrators[] = {core::IntegratorKind::Euler,
                                                        core::IntegratorKind::Rattle};

// A box body of full extents `size` (m) and mass (kg), its solid-box inertia, at `position`.
inline core::Body jointTestBox(const std::string& name, double mass, const core::Vec3& size,
                               const core::Vec3& position)
{
    core::Body body;
    body.name = name;
    body.mass = mass;
    const core::Vec3 s2 = size.cwiseProduct(size);
    body.inertia_B =
        (mass / 12.0 * core::Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
    body.position_W = position;
    return body;
}

// A joint to a parent (a body index or cWorld) with its frames set at the model's initial pose.
inline core::Joint& addTestJoint(core::Model& model, core::JointType type, int parent, int child,
                                 const core::Vec3& anchor_W, const core::Vec3& axis_W)
{
    core::Joint joint;
    joint.name = "joint" + std::to_string(model.joints.size());
    joint.type = type;
    joint.parent = parent;
    joint.child = child;
    core::setJointFrames(model, joint, anchor_W, axis_W);
    model.joints.push_back(joint);
    return model.joints.back();
}

inline core::Model emptyTestModel(const core::Vec3& gravity, core::IntegratorKind integrator, double dt)
{
    core::Model model;
    model.name = "joint test";
    model.simulation.dt = dt;
    model.simulation.gravity = gravity;
    model.simulation.integrator = integrator;
    return model;
}

// A 1 kg rod 0.5 m long along +x from a hinge at (0, 0, 1) about +y (a positive angle moves the
// tip down), horizontal at the start and turning at w0 (rad/s) about +y.
inline core::Model hingedRod(double w0, std::optional<std::array<double, 2>> limits,
                             const core::Vec3& gravity,
                             core::IntegratorKind integrator = core::IntegratorKind::Euler, double dt = 1e-3)
{
    core::Model model = emptyTestModel(gravity, integrator, dt);
    core::Body rod = jointTestBox("rod", 1.0, core::Vec3(0.5, 0.04, 0.04), core::Vec3(0.25, 0.0, 1.0));
    rod.angularVelocity_W = core::Vec3(0.0, w0, 0.0);
    rod.velocity_W = rod.angularVelocity_W.cross(core::Vec3(0.25, 0.0, 0.0)); // consistent with the hinge
    model.bodies.push_back(rod);
    addTestJoint(model, core::JointType::Revolute, core::cWorld, 0, core::Vec3(0.0, 0.0, 1.0),
                 core::Vec3::UnitY())
        .limits = limits;
    return model;
}

// A 2 kg box 0.2 x 0.2 x 0.1 m on a hinge to the world through its centre along z, spinning at w0
// (rad/s) about z: I = m (0.2^2 + 0.2^2) / 12 about the hinge.
inline core::Model spinningBox(double w0, core::IntegratorKind integrator = core::IntegratorKind::Euler,
                               double dt = 1e-3)
{
    core::Model model = emptyTestModel(core::Vec3::Zero(), integrator, dt);
    core::Body box = jointTestBox("wheel", 2.0, core::Vec3(0.2, 0.2, 0.1), core::Vec3(0.0, 0.0, 1.0));
    box.angularVelocity_W = core::Vec3(0.0, 0.0, w0);
    model.bodies.push_back(box);
    addTestJoint(model, core::JointType::Revolute, core::cWorld, 0, box.position_W, core::Vec3::UnitZ());
    return model;
}

// A 3 kg box on a rail to the world along `axis_W` through its centre, moving at v0 (m/s) along it.
inline core::Model slidingBox(double v0, const core::Vec3& axis_W, const core::Vec3& gravity,
                              core::IntegratorKind integrator = core::IntegratorKind::Euler, double dt = 1e-3)
{
    core::Model model = emptyTestModel(gravity, integrator, dt);
    core::Body box = jointTestBox("slider", 3.0, core::Vec3(0.2, 0.1, 0.1), core::Vec3(0.0, 0.0, 1.0));
    box.velocity_W = v0 * axis_W.normalized();
    model.bodies.push_back(box);
    addTestJoint(model, core::JointType::Prismatic, core::cWorld, 0, box.position_W, axis_W);
    return model;
}

// n rods 0.4 m long, hinged end to end about +y from (0, 0, 2), straight along +x at the start.
inline core::Model hingedChain(int n, core::IntegratorKind integrator = core::IntegratorKind::Euler)
{
    core::Model model = emptyTestModel(core::Vec3(0.0, 0.0, -9.81), integrator, 1e-3);
    const double length = 0.4;
    for (int i = 0; i < n; ++i)
    {
        model.bodies.push_back(jointTestBox("link" + std::to_string(i), 0.5 + 0.25 * i,
                                            core::Vec3(length, 0.04, 0.04),
                                            core::Vec3((i + 0.5) * length, 0.0, 2.0)));
        addTestJoint(model, core::JointType::Revolute, i == 0 ? core::cWorld : i - 1, i,
                     core::Vec3(i * length, 0.0, 2.0), core::Vec3::UnitY());
    }
    return model;
}

} // namespace frontier::sim::test
