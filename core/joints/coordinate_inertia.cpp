// core/joints/coordinate_inertia.cpp: the composite rigid body on a joint's child side.
#include "core/joints/coordinate_inertia.h"

#include <cstdint>
#include <vector>

namespace frontier::core
{

double coordinateInertia(const Model& model, int jointIndex, JointCoordinate coordinate)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    const Body& child = model.bodies[static_cast<std::size_t>(joint.child)];
    const Vec3 anchor_W = child.position_W + child.orientation_WB * joint.anchorChild;
    const Vec3 axis_W =
        joint.parent == cWorld
            ? joint.axisParent
            : Vec3(model.bodies[static_cast<std::size_t>(joint.parent)].orientation_WB * joint.axisParent);
    // The child's side: a walk over the other joints that never enters the parent (nor the world
    // or a static body).
    std::vector<std::vector<int>> neighbours(model.bodies.size());
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const Joint& other = model.joints[k];
        if (static_cast<int>(k) != jointIndex && isMovingBody(model, other.parent))
        {
            neighbours[static_cast<std::size_t>(other.parent)].push_back(other.child);
            neighbours[static_cast<std::size_t>(other.child)].push_back(other.parent);
        }
    }
    std::vector<std::uint8_t> seen(model.bodies.size(), 0);
    std::vector<int> pending = {joint.child};
    seen[static_cast<std::size_t>(joint.child)] = 1;
    if (isMovingBody(model, joint.parent))
    {
        seen[static_cast<std::size_t>(joint.parent)] = 1;
    }
    double inertia = 0.0;
    while (!pending.empty())
    {
        const int b = pending.back();
        pending.pop_back();
        const Body& body = model.bodies[static_cast<std::size_t>(b)];
        if (coordinate == JointCoordinate::Slide)
        {
            inertia += body.mass;
        }
        else
        {
            const Vec3 axis_B = body.orientation_WB.conjugate() * axis_W;
            inertia += axis_B.dot(body.inertia_B * axis_B) +
                       body.mass * axis_W.cross(body.position_W - anchor_W).squaredNorm();
        }
        for (const int next : neighbours[static_cast<std::size_t>(b)])
        {
            if (!seen[static_cast<std::size_t>(next)])
            {
                seen[static_cast<std::size_t>(next)] = 1;
                pending.push_back(next);
            }
        }
    }
    return inertia;
}

} // namespace frontier::core
