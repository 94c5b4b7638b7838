// collision/starting_overlaps.cpp: robot links that overlap where the robot starts.
//
// Robot files model links that touch or interpenetrate in their zero pose (a shoulder housing
// around its upper arm, two meshes drawn through each other). Pushing such a pair apart at the
// first step would fight the joints between them, so, as Drake and MoveIt do, a pair of one
// robot's links that overlaps in the initial pose never collides.
#include "collision/contacts.h"

#include <algorithm>

namespace frontier::collision
{

std::vector<std::pair<int, int>> startingOverlaps(const core::Model& model)
{
    std::vector<int> robotOf(model.bodies.size(), -1);
    for (std::size_t r = 0; r < model.robots.size(); ++r)
    {
        const core::Robot& robot = model.robots[r];
        if (!robot.selfCollision)
        {
            continue; // its links share a collision group already
        }
        for (int i = robot.firstBody; i < robot.firstBody + robot.bodyCount; ++i)
        {
            robotOf[static_cast<std::size_t>(i)] = static_cast<int>(r);
        }
    }
    std::vector<std::pair<int, int>> out;
    if (std::all_of(robotOf.begin(), robotOf.end(), [](int r) { return r < 0; }))
    {
        return out;
    }
    ContactDetector detector(model, 0.0);
    std::vector<Contact> contacts;
    detector.detect(core::initialState(model), contacts);
    for (const Contact& c : contacts)
    {
        if (c.depth <= 0.0 || c.bodyB < 0)
        {
            continue;
        }
        const int robot = robotOf[static_cast<std::size_t>(c.bodyA)];
        if (robot >= 0 && robot == robotOf[static_cast<std::size_t>(c.bodyB)])
        {
            out.emplace_back(std::min(c.bodyA, c.bodyB), std::max(c.bodyA, c.bodyB));
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

} // namespace frontier::collision
