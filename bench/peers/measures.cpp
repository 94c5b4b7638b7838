// bench/peers/measures.cpp
#include "bench/peers/measures.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace frontier::peers
{

double jointGap(const core::Model& model, const std::vector<Pose>& poses)
{
    double gap = 0.0;
    for (const core::Joint& joint : model.joints)
    {
        const Pose& c = poses[static_cast<std::size_t>(joint.child)];
        const core::Vec3 onChild = c.position_W + c.orientation_WB * joint.anchorChild;
        core::Vec3 onParent = joint.anchorParent; // world coordinates for a world parent
        if (joint.parent != core::cWorld)
        {
            const Pose& p = poses[static_cast<std::size_t>(joint.parent)];
            onParent = p.position_W + p.orientation_WB * joint.anchorParent;
        }
        gap = std::max(gap, (onChild - onParent).norm());
    }
    return gap;
}

Energy energyByDifferences(const core::Model& model, const std::vector<Pose>& before,
                           const std::vector<Pose>& middle, const std::vector<Pose>& after, double h)
{
    Energy energy;
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
    {
        const core::Body& body = model.bodies[b];
        const core::Vec3 v = (after[b].position_W - before[b].position_W) / (2.0 * h);
        core::Quat d = after[b].orientation_WB * before[b].orientation_WB.conjugate();
        if (d.w() < 0.0)
            d.coeffs() = -d.coeffs(); // the same rotation, by the short way
        const Eigen::AngleAxisd turn(d);
        const core::Vec3 w = turn.axis() * (turn.angle() / (2.0 * h));
        const core::Mat3 R = middle[b].orientation_WB.toRotationMatrix();
        const core::Mat3 I_W = R * body.inertia_B * R.transpose();
        const double kinetic = 0.5 * body.mass * v.squaredNorm() + 0.5 * w.dot(I_W * w);
        energy.kinetic += kinetic;
        energy.total += kinetic - body.mass * model.simulation.gravity.dot(middle[b].position_W);
    }
    return energy;
}

double positionError(const std::vector<Pose>& a, const std::vector<Pose>& b)
{
    double error = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
        error = std::max(error, (a[i].position_W - b[i].position_W).norm());
    return error;
}

} // namespace frontier::peers
