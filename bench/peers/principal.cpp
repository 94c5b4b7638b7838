// bench/peers/principal.cpp: body frames turned onto principal axes.
#include "bench/peers/principal.h"

#include "core/free_rotation.h"

#include <cmath>

namespace frontier::peers
{

core::Model inPrincipalFrames(const core::Model& model, std::vector<core::Quat>& rotation_BP)
{
    core::Model out = model;
    rotation_BP.assign(model.bodies.size(), core::Quat::Identity());
    for (std::size_t b = 0; b < out.bodies.size(); ++b)
    {
        core::Body& body = out.bodies[b];
        const core::Mat3& I = body.inertia_B;
        const double offDiagonal = std::abs(I(0, 1)) + std::abs(I(0, 2)) + std::abs(I(1, 2));
        if (body.isStatic || offDiagonal <= 1e-12 * I.trace())
            continue;
        const core::PrincipalAxes axes = core::principalAxes(I);
        const core::Quat& r = axes.rotation_BP;
        rotation_BP[b] = r;
        body.orientation_WB = (body.orientation_WB * r).normalized();
        body.inertia_B = axes.moments.asDiagonal();
        for (core::Shape& shape : body.shapes)
        {
            shape.position_BS = r.conjugate() * shape.position_BS;
            shape.rotation_BS = r.conjugate() * shape.rotation_BS;
        }
    }
    for (core::Joint& joint : out.joints)
    {
        const auto turned = [&](int b, const core::Vec3& v)
        { return b == core::cWorld ? v : rotation_BP[static_cast<std::size_t>(b)].conjugate() * v; };
        joint.anchorParent = turned(joint.parent, joint.anchorParent);
        joint.axisParent = turned(joint.parent, joint.axisParent);
        joint.perpParent1 = turned(joint.parent, joint.perpParent1);
        joint.perpParent2 = turned(joint.parent, joint.perpParent2);
        joint.anchorChild = turned(joint.child, joint.anchorChild);
        joint.axisChild = turned(joint.child, joint.axisChild);
        joint.perpChild1 = turned(joint.child, joint.perpChild1);
        joint.angleChildAxis = turned(joint.child, joint.angleChildAxis);
        const core::Quat parent = joint.parent == core::cWorld
                                      ? core::Quat::Identity()
                                      : rotation_BP[static_cast<std::size_t>(joint.parent)];
        joint.restRotation_AB =
            parent.conjugate() * joint.restRotation_AB * rotation_BP[static_cast<std::size_t>(joint.child)];
    }
    return out;
}

} // namespace frontier::peers
