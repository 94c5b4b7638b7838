// core/failure_hint.cpp: the likely cause of a failed run (see core/failure_hint.h).
#include "core/failure_hint.h"

#include "core/joints/coordinates.h"
#include "core/joints/joint_types.h"

#include <iomanip>
#include <sstream>

namespace frontier::core
{

namespace
{
std::string bodyName(const Model& model, int body)
{
    return body < 0 ? std::string("the world")
                    : "'" + model.bodies[static_cast<std::size_t>(body)].name + "'";
}

// The unit of the coordinate the joint's limits bound.
const char* jointUnit(const Joint& joint)
{
    return jointTypeInfo(joint.type).limitCoordinate == JointCoordinate::Slide ? "m" : "rad";
}
} // namespace

StartDefects findStartDefects(const std::vector<Contact>& contacts, const std::vector<ExtraBlock>& extra,
                              const Model& model, const State& state)
{
    StartDefects start;
    for (const Contact& contact : contacts)
    {
        if (contact.depth <= cDeepOverlap)
        {
            continue;
        }
        ++start.deepOverlaps;
        if (contact.depth > start.overlapM)
        {
            start.overlapM = contact.depth;
            start.overlapBodyA = contact.bodyA;
            start.overlapBodyB = contact.bodyB;
        }
    }
    for (const ExtraBlock& block : extra)
    {
        if (block.kind == ExtraBlock::Kind::Limit && block.error(0) > start.limitExcess)
        {
            start.limitExcess = block.error(0);
            start.limitJoint = block.source;
            start.limitCoordinate = jointCoordinate(model, state, block.source);
        }
    }
    return start;
}

std::string failureHint(const Model& model, const StartDefects& start, bool recovering,
                        double rotationPerStep, int fastestBody)
{
    std::ostringstream hint;
    hint << std::setprecision(3);
    if (recovering && start.deepOverlaps > 0)
    {
        hint << "; likely cause: the scene starts with " << bodyName(model, start.overlapBodyA) << " "
             << start.overlapM << " m deep in " << bodyName(model, start.overlapBodyB);
        if (start.deepOverlaps > 1)
        {
            hint << " (the deepest of " << start.deepOverlaps << " overlaps beyond " << cDeepOverlap << " m)";
        }
        hint << ": separate them in the scene (a smaller --dt does not help)";
    }
    else if (recovering && start.limitJoint >= 0)
    {
        const Joint& joint = model.joints[static_cast<std::size_t>(start.limitJoint)];
        const char* unit = jointUnit(joint);
        hint << "; likely cause: joint '" << joint.name << "' starts at " << start.limitCoordinate << " "
             << unit << ", " << start.limitExcess << " " << unit << " beyond its limits ["
             << (*joint.limits)[0] << ", " << (*joint.limits)[1] << "] " << unit
             << ": start it within them (a smaller --dt does not help)";
    }
    else if (rotationPerStep > cFastRotationPerStep)
    {
        hint << "; body " << bodyName(model, fastestBody) << " turned " << rotationPerStep
             << " rad in one step: try a smaller --dt";
    }
    return hint.str();
}

} // namespace frontier::core
