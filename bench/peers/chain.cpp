// bench/peers/chain.cpp
#include "bench/peers/chain.h"

#include <string>

namespace frontier::peers
{

core::Model chainOfBoxes(int n, double tipMassRatio)
{
    constexpr double cLength = 0.1; // m, joint to joint
    constexpr double cWidth = 0.02; // m
    constexpr double cMass = 0.1;   // kg
    core::Model model;
    model.name =
        "chain of " + std::to_string(n) + " boxes" +
        (tipMassRatio != 1.0 ? ", tip " + std::to_string(static_cast<long>(tipMassRatio)) + ":1" : "");
    model.simulation.dt = 0.001;
    core::Shape box;
    box.type = core::ShapeType::Box;
    box.size = core::Vec3(cLength, cWidth, cWidth);
    model.bodies.reserve(static_cast<std::size_t>(n));
    model.joints.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
        core::Body body;
        body.name = "link" + std::to_string(i);
        body.mass = cMass * (i == n - 1 ? tipMassRatio : 1.0);
        const double a = cLength * cLength, b = cWidth * cWidth;
        body.inertia_B = (body.mass / 12.0 * core::Vec3(2.0 * b, a + b, a + b)).asDiagonal();
        body.shapes.push_back(box);
        body.group = "chain";
        body.position_W = core::Vec3((i + 0.5) * cLength, 0.0, 2.0);
        model.bodies.push_back(body);
        core::Joint joint;
        joint.name = "joint" + std::to_string(i);
        joint.type = core::JointType::Ball;
        joint.parent = i == 0 ? core::cWorld : i - 1;
        joint.child = i;
        joint.anchorParent = i == 0 ? core::Vec3(0.0, 0.0, 2.0) : core::Vec3(0.5 * cLength, 0.0, 0.0);
        joint.anchorChild = core::Vec3(-0.5 * cLength, 0.0, 0.0);
        model.joints.push_back(joint);
    }
    return model;
}

} // namespace frontier::peers
