// bench/peers/contacts.h: what every engine needs to give the scene's collision shapes to its own
// contact machinery, and the engine-independent penetration measure.
//
// Which pairs collide is Frontier's rule (docs/method.md §10: not two static bodies, not two
// bodies of one non-empty group, not contact.ignore pairs, not bodies joined by a joint unless it
// says collideConnected), asked of Frontier's own filter for each pair.
#pragma once

#include "bench/peers/engine.h"
#include "collision/contacts.h"
#include "collision/convex_hull.h"
#include "collision/filter.h"
#include "core/state.h"

#include <memory>
#include <utility>
#include <vector>

namespace frontier::peers
{

// False when no two bodies of the model can ever collide (no shapes, or every body with shapes
// moving and in one group, as the generated chains): the engines then get no collision geometry.
bool hasContacts(const core::Model& model);

// A mesh shape as the peers collide it: its convex hull, in the shape's frame (Frontier collides a
// moving mesh as its hull; the peers do so for static meshes too). Throws Unsupported when the
// mesh has no 3-d hull.
collision::ConvexHull meshHull(const core::Body& body, const core::Shape& shape);

// Pairs (i < j) of bodies with shapes, not both static, that the filter keeps apart.
std::vector<std::pair<int, int>> excludedPairs(const core::Model& model, const collision::PairFilter& filter);

// The deepest overlap (m, >= 0) between any two bodies that may collide, found by Frontier's
// ContactDetector on an engine's poses.
class PenetrationMeter
{
  public:
    explicit PenetrationMeter(const core::Model& model);
    double deepest(const std::vector<Pose>& poses);

  private:
    const core::Model& mModel;
    bool mContacts;
    std::unique_ptr<collision::ContactDetector> mDetector;
    core::State mState;
    std::vector<collision::Contact> mFound;
};

} // namespace frontier::peers
