// collision/detector.h: private to collision/ (FCL's types appear here, never in a public header).
// The state of ContactDetector (contacts.h) shared by its files: contacts.cpp (construction,
// posing, the plane pass, the broadphase, the swept search), narrowphase.cpp (the table of pair
// functions keyed by the collision kinds of two shapes) and narrowphase_pairs.cpp (those
// functions).
#pragma once

#include "collision/contacts.h"
#include "collision/internal.h"

#include <array>
#include <cstdint>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace frontier::collision
{

namespace detail
{

// A collision object whose world AABB is grown by the margin, so that the broadphase also
// reports pairs a little apart (the feature manifolds report gaps below the margin).
class MarginObject : public fcl::CollisionObjectd
{
  public:
    using fcl::CollisionObjectd::CollisionObjectd;

    // Sets the AABB the broadphase sees: the shape's own grown by the margin would do, but it
    // moves a little every step and FCL re-inserts a leaf whose box changed. So the box kept is
    // grown by twice the margin and only replaced when the margin-grown one leaves it (a "fat"
    // AABB): a body at rest, or moving less than a margin, keeps its leaf. Returns true when the
    // box changed. The broadphase then reports a few more pairs, all of them at least a margin
    // apart, which the narrowphase rejects: the contacts are the same.
    // A body that moves fast (docs/method.md §10) has its box grown further by its travel over
    // the step: below by sweepBelow, above by sweepAbove (m, >= 0 per axis).
    bool updateFatAABB(double margin, const Vec3* sweepBelow = nullptr, const Vec3* sweepAbove = nullptr)
    {
        computeAABB();
        fcl::AABBd needed = aabb;
        needed.min_.array() -= margin;
        needed.max_.array() += margin;
        if (sweepBelow != nullptr)
        {
            needed.min_ -= *sweepBelow;
            needed.max_ += *sweepAbove;
        }
        if (mHasFat && mFat.contain(needed))
        {
            aabb = mFat;
            return false;
        }
        mFat = needed;
        mFat.min_.array() -= margin;
        mFat.max_.array() += margin;
        mHasFat = true;
        aabb = mFat;
        return true;
    }

  private:
    fcl::AABBd mFat;
    bool mHasFat = false;
};

struct PlaneInstance
{
    int body = 0;
    Vec3 normal = Vec3::UnitZ(); // unit, world
    double offset = 0.0;         // m
};

// A body's motion over one step, for the swept search (docs/method.md §10).
struct BodyMotion
{
    Vec3 position = Vec3::Zero();        // centre of mass at the step start (m)
    Vec3 velocity = Vec3::Zero();        // m/s
    Vec3 angularVelocity = Vec3::Zero(); // rad/s
    bool swept = false;                  // travels more than cSweptMargins margins in a step
};

// What the detector keeps of a shape pair from one detect() call to the next while the broadphase
// reports it (collision/README.md "Per-pair state"): how far apart the pair was last proven to be,
// with how far its bodies had travelled then, and the axis along which it was found apart, in
// shape a's frame. While the bodies have not travelled the proven distance less the margin
// between them, the pair is still apart beyond the margin; else the axis, tried first, proves it
// in one support-function test, where the axes of separatedBeyond may not and FCL's collide and
// distance would (the same result: no contact). It only ever skips work whose outcome it proves.
struct PairState
{
    int i = 0;                  // shape a
    int j = 0;                  // shape b
    bool allowed = false;       // the filter allows the pair of their bodies (asked once per pair)
    Vec3 axis_S = Vec3::Zero(); // unit, shape a's frame; zero: none yet
    double apart = 0.0;         // m: a lower bound of the distance when last proven apart; 0: none
    double travelA = 0.0;       // m: body a's travel (ContactDetector::Impl::bodyTravel) then
    double travelB = 0.0;       // m: body b's
};

} // namespace detail

struct ContactDetector::Impl
{
    using Mat3 = detail::Mat3;
    using Vec3 = detail::Vec3;
    using RawContact = detail::RawContact;
    using ShapeInstance = detail::ShapeInstance;
    using PairState = detail::PairState;
    using BodyMotion = detail::BodyMotion;
    using PlaneInstance = detail::PlaneInstance;
    using MarginObject = detail::MarginObject;
    // Shapes of one type and size share one FCL geometry and one ShapeGeometry (neither holds a
    // pose), keyed by type and sizes; the inflated boxes one object per box size.
    struct Shared
    {
        std::shared_ptr<fcl::CollisionGeometryd> fcl;
        std::shared_ptr<const detail::ShapeGeometry> own;
    };
    using SharedGeometries = std::map<std::array<double, 4>, Shared>;
    using InflatedBySize = std::map<std::array<double, 3>, int>;

    double margin = 1e-3;  // m
    double stepTime = 0.0; // s; the swept search is off while 0
    detail::PairFilter filter;
    std::vector<char> bodyCollides;  // per body: has a shape that can touch something
    std::vector<double> bodyReach;   // per body: farthest shape point from the centre of mass (m)
    std::vector<BodyMotion> motions; // per body, this detect() call (swept search)
    // Per body: an upper bound (m) of how far any point of its shapes has moved over the states
    // detect() was given so far (the sum over calls of |dp| + 2 |sin(angle / 2)| reach), and the
    // pose of the last call. bodyTravel now less bodyTravel then bounds the move in between.
    std::vector<double> bodyTravel;
    std::vector<Vec3> lastPosition;
    std::vector<core::Quat> lastOrientation;
    bool travelStarted = false;
    bool anySwept = false;                              // some body is swept this call
    std::vector<ShapeInstance> shapes;                  // non-plane shapes, in body order
    std::vector<std::unique_ptr<MarginObject>> objects; // per shape; null for a mesh without triangles
    // Boxes grown by the margin on every side: colliding one with the other box of a pair gives
    // FCL's box-box manifold while they are still apart, for speculative contacts. One object per
    // distinct box size, given the box's pose when it is used; per shape its index, -1 for others.
    std::vector<std::unique_ptr<fcl::CollisionObjectd>> inflatedBoxes;
    std::vector<int> inflatedBox;
    std::vector<PlaneInstance> planes;
    std::vector<int> movingShapes; // shapes of moving bodies that can touch something: posed per call
    std::vector<char>
        planeAllowed; // per moving shape (its place in movingShapes) and plane: the filter allows it
    std::vector<int> staticShapes;                        // shapes of static bodies
    std::vector<fcl::CollisionObjectd*> movingRegistered; // moving objects in the manager
    std::vector<char> registeredMoving;                   // per shape: in movingRegistered
    std::vector<fcl::CollisionObjectd*> changed;          // scratch: their AABBs changed this step
    fcl::DynamicAABBTreeCollisionManagerd manager;
    bool useBroadphase = false;
    bool staticPosed = false;

    // Per shape pair of the last call's broadphase, in the order of shapePairs (sorted): what
    // narrowphase() learnt of it (PairState). The next call's pairs are matched against it.
    std::vector<PairState> pairStates;
    std::vector<PairState> nextPairStates;

    // Scratch, reused every step.
    std::vector<std::pair<int, int>> shapePairs;
    fcl::CollisionRequestd request{8, true};
    fcl::CollisionRequestd meshRequest{64, true};
    fcl::CollisionResultd result;
    fcl::DistanceRequestd distanceRequest{true}; // with nearest points (world frame)
    fcl::DistanceResultd distanceResult;
    std::vector<RawContact> raw;
    std::vector<std::intptr_t> rawTriangles; // per FCL point in raw: the triangle of the mesh in the pair
    std::vector<RawContact> clipped;
    // One triangle of a mesh as a flat polytope (polytope_manifold.cpp), and its geometry.
    std::shared_ptr<detail::ShapeGeometry> triangleGeometry = std::make_shared<detail::ShapeGeometry>();
    ShapeInstance triangle;

    bool candidatesReady = false;
    std::vector<std::pair<int, int>> candidates;
    DetectorStats stats;

    Impl(const core::Model& model, double marginIn, MovingMeshes movingMeshes);
    // Construction steps (contacts.cpp).
    void addShape(const core::Model& model, int b, const core::Shape& shape, const Mat3& R_WB,
                  MovingMeshes movingMeshes, SharedGeometries& geometries, InflatedBySize& inflatedBySize);
    void registerBroadphase();
    void dropUnreachableShapes();
    void startMotions(std::size_t bodyCount);

    void poseShape(int index, const core::State& state);
    void planePass(std::vector<Contact>& out);
    void addTravel(const core::State& state);
    void provenApart(PairState& pair, double distanceAtLeast) const;
    void sweepMotions(const core::State& state);
    double shapeReach(const ShapeInstance& s) const;
    fcl::Transform3d poseAt(const ShapeInstance& s, double tau, Mat3* turn) const;
    void sweptPair(int i, int j, std::vector<Contact>& out);
    void emit(int bodyA, int bodyB, std::vector<Contact>& out);
    static bool broadphaseCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data);

    // A pair function of the narrowphase table, and the table's entry (narrowphase.cpp).
    using PairFunction = void (Impl::*)(int i, int j, PairState& pair, std::vector<Contact>& out);
    struct PairEntry;

    // The narrowphase of shapes i and j (narrowphase.cpp): the early-outs every pair shares, then
    // the pair function its collision kinds select in the table (detail::NarrowphaseTable).
    void narrowphase(int i, int j, PairState& pair, std::vector<Contact>& out);
    bool separatedOnAxes(const ShapeInstance& a, const ShapeInstance& b, PairState& pair);

    // Pair functions (narrowphase_pairs.cpp), one per family of kind pairs; each appends the
    // pair's contacts to out (or proves the pair apart in `pair`).
    void sweptSpherePair(int i, int j, PairState& pair, std::vector<Contact>& out);
    void polytopePair(int i, int j, PairState& pair, std::vector<Contact>& out);
    void boxBoxPair(int i, int j, PairState& pair, std::vector<Contact>& out);
    void convexPair(int i, int j, PairState& pair, std::vector<Contact>& out);
    void trianglePolytopePair(int i, int j, PairState& pair, std::vector<Contact>& out);
    void triangleShapePair(int i, int j, PairState& pair, std::vector<Contact>& out);

    // Steps the pair functions share (narrowphase_pairs.cpp).
    RawContact collideFcl(int i, int j, double& fclDepth);
    void collideWithFeatures(int i, int j);
    void inflatedBoxContacts(int i, int j);
    bool nearestGap(int i, int j, RawContact& out, Vec3* apart = nullptr);
    void clipAgainstTriangles(int i, int j);
    void finishPair(const ShapeInstance& a, const ShapeInstance& b, std::vector<Contact>& out);
};

} // namespace frontier::collision
