// bench/peers/tree.cpp: the model's joint tree in parent-before-child order.
#include "bench/peers/tree.h"

#include "bench/peers/engine.h"

#include <string>

namespace frontier::peers
{

std::vector<TreeLink> jointTree(const core::Model& model)
{
    const int n = static_cast<int>(model.bodies.size());
    for (const core::Body& body : model.bodies)
    {
        if (body.isStatic)
            throw Unsupported("body '" + body.name + "' is static: the harness runs moving bodies only");
        if (!body.velocity_W.isZero() || !body.angularVelocity_W.isZero())
            throw Unsupported("body '" + body.name +
                              "' starts moving: the harness starts every body at rest");
    }
    if (!model.actuators.empty() || !model.loads.empty())
        throw Unsupported("the scene has actuators or loads: the harness does not translate them");
    std::vector<int> parentJoint(static_cast<std::size_t>(n), -1);
    std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
    int worldJoints = 0;
    int rootJoint = -1;
    for (int j = 0; j < static_cast<int>(model.joints.size()); ++j)
    {
        const core::Joint& joint = model.joints[static_cast<std::size_t>(j)];
        if (joint.type != core::JointType::Ball && joint.type != core::JointType::Revolute &&
            joint.type != core::JointType::Fixed)
            throw Unsupported("joint '" + joint.name +
                              "': the harness translates ball, revolute and fixed joints");
        if (joint.limits)
            throw Unsupported("joint '" + joint.name + "' has limits: the harness does not translate them");
        if (parentJoint[static_cast<std::size_t>(joint.child)] >= 0)
            throw Unsupported("body '" + model.bodies[static_cast<std::size_t>(joint.child)].name +
                              "' is the child of two joints (a loop)");
        parentJoint[static_cast<std::size_t>(joint.child)] = j;
        if (joint.parent == core::cWorld)
        {
            ++worldJoints;
            rootJoint = j;
        }
        else
            children[static_cast<std::size_t>(joint.parent)].push_back(joint.child);
    }
    int root = -1;
    int freeRoots = 0;
    for (int b = 0; b < n; ++b)
        if (parentJoint[static_cast<std::size_t>(b)] < 0)
        {
            ++freeRoots;
            root = b;
        }
    if (worldJoints + freeRoots != 1)
        throw Unsupported("the bodies form " + std::to_string(worldJoints + freeRoots) +
                          " trees: the harness runs one");
    if (worldJoints == 1)
        root = model.joints[static_cast<std::size_t>(rootJoint)].child;

    std::vector<TreeLink> order;
    order.reserve(static_cast<std::size_t>(n));
    order.push_back(
        {root, parentJoint[static_cast<std::size_t>(root)], worldJoints == 1 ? core::cWorld : -1});
    for (std::size_t k = 0; k < order.size(); ++k)
        for (int c : children[static_cast<std::size_t>(order[k].body)])
            order.push_back({c, parentJoint[static_cast<std::size_t>(c)], order[k].body});
    if (static_cast<int>(order.size()) != n)
        throw Unsupported("some bodies are not in the root's tree (a loop among them)");
    return order;
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
