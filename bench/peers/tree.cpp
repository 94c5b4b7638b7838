// bench/peers/tree.cpp: the model's joint tree in parent-before-child order.
#include "bench/peers/tree.h"

#include "bench/peers/engine.h"

#include <string>

namespace frontier::peers
{

namespace
{

// A tree that starts moving must move as one rigid body (v_i = v_root + w x (x_i - x_root), one w):
// its joints then start at rest and the root's velocity is the only one a reduced-coordinate
// engine needs. A tree joined to the world must start at rest.
void checkInitialVelocities(const core::Model& model, const std::vector<TreeLink>& order)
{
    constexpr double cTolerance = 1e-6; // m/s, rad/s (the scene files' rounding)
    std::size_t k = 0;
    while (k < order.size())
    {
        const core::Body& root = model.bodies[static_cast<std::size_t>(order[k].body)];
        const bool joinedToWorld = order[k].joint >= 0;
        for (++k; k < order.size() && !isRoot(order[k]); ++k)
        {
            const core::Body& body = model.bodies[static_cast<std::size_t>(order[k].body)];
            const core::Vec3 rigid =
                root.velocity_W + root.angularVelocity_W.cross(body.position_W - root.position_W);
            if ((body.velocity_W - rigid).norm() > cTolerance ||
                (body.angularVelocity_W - root.angularVelocity_W).norm() > cTolerance)
                throw Unsupported("body '" + body.name +
                                  "' does not start with its tree's rigid velocity: the harness starts "
                                  "every joint at rest");
        }
        if (joinedToWorld && (!root.velocity_W.isZero() || !root.angularVelocity_W.isZero()))
            throw Unsupported("body '" + root.name +
                              "' is joined to the world and starts moving: the harness starts every "
                              "joint at rest");
    }
}

} // namespace

std::vector<TreeLink> jointTree(const core::Model& model)
{
    const int n = static_cast<int>(model.bodies.size());
    if (!model.actuators.empty() || !model.loads.empty())
        throw Unsupported("the scene has actuators or loads: the harness does not translate them");
    std::vector<int> parentJoint(static_cast<std::size_t>(n), -1);
    std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
    for (int j = 0; j < static_cast<int>(model.joints.size()); ++j)
    {
        const core::Joint& joint = model.joints[static_cast<std::size_t>(j)];
        if (joint.type != core::JointType::Ball && joint.type != core::JointType::Revolute &&
            joint.type != core::JointType::Fixed && joint.type != core::JointType::Angle)
            throw Unsupported("joint '" + joint.name +
                              "': the harness translates ball, revolute, angle and fixed joints");
        if (joint.limits && joint.type != core::JointType::Revolute)
            throw Unsupported("joint '" + joint.name +
                              "' has limits: the harness translates those of revolute joints only");
        if (joint.damping != 0.0 || joint.friction != 0.0)
            throw Unsupported("joint '" + joint.name +
                              "' has damping or friction: the harness does not translate them");
        if (parentJoint[static_cast<std::size_t>(joint.child)] >= 0)
            throw Unsupported("body '" + model.bodies[static_cast<std::size_t>(joint.child)].name +
                              "' is the child of two joints (a loop)");
        parentJoint[static_cast<std::size_t>(joint.child)] = j;
        if (treeParent(model, joint) != core::cWorld)
            children[static_cast<std::size_t>(joint.parent)].push_back(joint.child);
    }

    std::vector<TreeLink> order;
    order.reserve(static_cast<std::size_t>(n));
    int moving = 0;
    for (int b = 0; b < n; ++b)
    {
        if (model.bodies[static_cast<std::size_t>(b)].isStatic)
            continue;
        ++moving;
        const int j = parentJoint[static_cast<std::size_t>(b)];
        if (j >= 0 && treeParent(model, model.joints[static_cast<std::size_t>(j)]) != core::cWorld)
            continue; // not a root
        const std::size_t first = order.size();
        order.push_back({b, j, core::cWorld});
        for (std::size_t k = first; k < order.size(); ++k)
            for (int c : children[static_cast<std::size_t>(order[k].body)])
                order.push_back({c, parentJoint[static_cast<std::size_t>(c)], order[k].body});
    }
    if (static_cast<int>(order.size()) != moving)
        throw Unsupported("some bodies are not in a tree with a root (a loop among them)");
    checkInitialVelocities(model, order);
    return order;
}

int treeParent(const core::Model& model, const core::Joint& joint)
{
    if (joint.parent == core::cWorld || model.bodies[static_cast<std::size_t>(joint.parent)].isStatic)
        return core::cWorld;
    return joint.parent;
}

core::Vec3 parentAnchor(const core::Model& model, const core::Joint& joint)
{
    if (joint.parent == core::cWorld || treeParent(model, joint) != core::cWorld)
        return joint.anchorParent;
    const core::Body& parent = model.bodies[static_cast<std::size_t>(joint.parent)];
    return parent.position_W + parent.orientation_WB * joint.anchorParent;
}

core::Quat parentRotation(const core::Model& model, const core::Joint& joint)
{
    if (joint.parent == core::cWorld)
        return core::Quat::Identity();
    return model.bodies[static_cast<std::size_t>(joint.parent)].orientation_WB;
}

core::Quat relativeRotation(const core::Model& model, int a, int b)
{
    const core::Quat& qb = model.bodies[static_cast<std::size_t>(b)].orientation_WB;
    if (a == core::cWorld)
        return qb;
    return model.bodies[static_cast<std::size_t>(a)].orientation_WB.conjugate() * qb;
}

core::Vec3 relativePosition(const core::Model& model, int a, int b)
{
    const core::Vec3& xb = model.bodies[static_cast<std::size_t>(b)].position_W;
    if (a == core::cWorld)
        return xb;
    const core::Body& body = model.bodies[static_cast<std::size_t>(a)];
    return body.orientation_WB.conjugate() * (xb - body.position_W);
}

} // namespace frontier::peers
