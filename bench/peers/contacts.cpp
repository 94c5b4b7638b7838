// bench/peers/contacts.cpp
#include "bench/peers/contacts.h"

#include <algorithm>

namespace frontier::peers
{

bool hasContacts(const core::Model& model)
{
    const std::string* group = nullptr;
    bool oneGroup = true;
    int withShapes = 0;
    for (const core::Body& body : model.bodies)
    {
        if (body.shapes.empty())
            continue;
        ++withShapes;
        if (body.isStatic || body.group.empty() || (group && *group != body.group))
            oneGroup = false;
        group = &body.group;
    }
    return withShapes >= 2 && !oneGroup;
}

collision::ConvexHull meshHull(const core::Body& body, const core::Shape& shape)
{
    collision::ConvexHull hull;
    std::string reason;
    if (!collision::computeConvexHull(shape.vertices, hull, reason))
        throw Unsupported("body '" + body.name + "': mesh '" + shape.meshFile + "' has no convex hull (" +
                          reason + ")");
    return hull;
}

std::vector<std::pair<int, int>> excludedPairs(const core::Model& model, const collision::PairFilter& filter)
{
    std::vector<std::pair<int, int>> out;
    const int n = static_cast<int>(model.bodies.size());
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
        {
            const core::Body& a = model.bodies[static_cast<std::size_t>(i)];
            const core::Body& b = model.bodies[static_cast<std::size_t>(j)];
            if (a.shapes.empty() || b.shapes.empty() || (a.isStatic && b.isStatic))
                continue;
            if (!filter.allowed(i, j))
                out.emplace_back(i, j);
        }
    return out;
}

PenetrationMeter::PenetrationMeter(const core::Model& model)
    : mModel(model), mContacts(hasContacts(model)), mState(core::initialState(model))
{
    if (mContacts)
        mDetector = std::make_unique<collision::ContactDetector>(model, 1e-4);
}

double PenetrationMeter::deepest(const std::vector<Pose>& poses)
{
    if (!mContacts)
        return 0.0;
    for (std::size_t b = 0; b < mModel.bodies.size(); ++b)
        if (!mModel.bodies[b].isStatic)
        {
            mState.bodies[b].position_W = poses[b].position_W;
            mState.bodies[b].orientation_WB = poses[b].orientation_WB.normalized();
        }
    mDetector->detect(mState, mFound);
    double depth = 0.0;
    for (const collision::Contact& c : mFound)
        depth = std::max(depth, c.depth);
    return depth;
}

} // namespace frontier::peers
