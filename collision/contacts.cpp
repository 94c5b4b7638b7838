// collision/contacts.cpp: the contact detector (FCL 0.7 with its default libccd solver).
//
// Pipeline of detect():
//   1. Pose every shape of a moving body (body frame at the centre of mass, shape pose in it).
//   2. Ground: each moving shape against each static plane, directly (planes never enter the
//      broadphase: FCL's bulk registration crashes on infinite AABBs). These
//      contacts are made here (plane_manifold.cpp), not by FCL, which returns one point for a
//      box, capsule or cylinder on a half-space; we return every box vertex, both capsule end
//      spheres, the cylinder rim points and the mesh vertices within the margin.
//   3. Everything else: a DynamicAABBTreeCollisionManagerd holding only the shapes of bodies
//      that have at least one allowed partner (AABBs grown by the margin). Its callback only
//      collects shape pairs of two bodies not both static; they are sorted and then tested in
//      that order, so the result never depends on the tree's traversal order. Each pair keeps
//      its state from the last call while the broadphase reports it (PairState: the filter's
//      answer; a proven distance, which skips the pair while its bodies have travelled less than
//      it exceeds the margin by; a separating axis, which skips the narrowphase while it still
//      proves the pair apart).
//   4. Narrowphase per pair: spheres and capsules against each other in closed form
//      (swept_spheres.cpp); pairs proven apart by more than the margin along an axis are done
//      (separation.cpp); every other pair with fcl::collide. Box-box keeps FCL's manifold
//      (up to 4 points). Moving meshes are their convex hulls of at most cHullCorners corners
//      (fcl::Convexd, built once here); a hull against a hull or a box, and a hull or box
//      against a static triangle mesh, get one face clipped against the other along FCL's
//      normal (polytope_manifold.cpp); two polytopes ask fcl::distance first and fcl::collide
//      only when they touch.
//      A capsule or cylinder against a box, capsule or cylinder gets one point from FCL, and a
//      mesh gets per-triangle points, so we add feature points (feature_manifold.cpp): box
//      vertices, capsule end spheres, cylinder rim points and mesh vertices tested against the
//      exact signed distance of the other shape, plus the capsule axis clipped to the other's
//      contact face. We chose this over a persistent contact cache: it gives the full manifold
//      in the very first step, keeps the contacts free of history (same state -> same contacts),
//      still works when FCL's single point never moves (a cache only grows when it wanders) and
//      costs a few dozen flops per feature. FCL's own point is dropped when the features
//      already reach its depth. Zero-normal/zero-depth FCL points (meshes) are dropped.
//   5. Per shape pair: merge points closer than a size-relative distance and keep at most 4
//      (manifold.cpp). Then all contacts are sorted by (bodyA, bodyB, point, depth).
//   Fast bodies (setStepTime, docs/method.md §10): a body travelling more than cSweptMargins
//   margins in a step has its broadphase box grown along its motion and its plane window widened
//   by its travel towards the plane; a pair of it that steps 4-5 leave without a contact is
//   advanced conservatively along the step's motion (sweptPair), and a hit gives a gap contact.
//
// Our code does no heap allocation per step once its vectors have grown; fcl::collide itself
// allocates a few small blocks per touching pair (measured: 1-3, about 20 for a mesh pair).
#include "collision/contacts.h"

#include "collision/internal.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/triangle.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <limits>
#include <map>
#include <stdexcept>

namespace frontier::collision
{

namespace
{

using detail::Mat3;
using detail::RawContact;
using detail::ShapeInstance;
using detail::Vec3;

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

std::shared_ptr<fcl::CollisionGeometryd> makeGeometry(const core::Shape& shape, const ShapeInstance& instance)
{
    switch (shape.type)
    {
    case core::ShapeType::Box:
        return std::make_shared<fcl::Boxd>(shape.size.x(), shape.size.y(), shape.size.z());
    case core::ShapeType::Sphere:
        return std::make_shared<fcl::Sphered>(shape.radius);
    case core::ShapeType::Capsule:
        return std::make_shared<fcl::Capsuled>(shape.radius, shape.length); // lz = segment (m)
    case core::ShapeType::Cylinder:
        return std::make_shared<fcl::Cylinderd>(shape.radius, shape.length); // lz = full height (m)
    case core::ShapeType::Mesh:
    {
        if (instance.convexHull)
        {
            const detail::ConvexHull& hull = instance.hull();
            return std::make_shared<fcl::Convexd>(std::make_shared<const std::vector<Vec3>>(hull.vertices),
                                                  static_cast<int>(hull.normals.size()),
                                                  std::make_shared<const std::vector<int>>(hull.faces));
        }
        if (shape.triangles.empty() || shape.vertices.empty())
            return nullptr;
        std::vector<fcl::Triangle> triangles;
        triangles.reserve(shape.triangles.size());
        for (const auto& t : shape.triangles)
            triangles.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                                   static_cast<std::size_t>(t[2]));
        auto mesh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
        mesh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(shape.vertices.size()));
        mesh->addSubModel(shape.vertices, triangles);
        mesh->endModel();
        return mesh;
    }
    case core::ShapeType::Plane:
        break;
    }
    return nullptr;
}

// A mesh colliding as triangles (FCL's BVH): a static mesh, or a moving one without a hull.
bool isTriangleMesh(const ShapeInstance& s)
{
    return s.type == core::ShapeType::Mesh && !s.convexHull;
}

void* indexToUserData(int index)
{
    return reinterpret_cast<void*>(static_cast<std::intptr_t>(index));
}

int userDataToIndex(const fcl::CollisionObjectd* object)
{
    return static_cast<int>(reinterpret_cast<std::intptr_t>(object->getUserData()));
}

bool contactLess(const Contact& a, const Contact& b)
{
    if (a.bodyA != b.bodyA)
        return a.bodyA < b.bodyA;
    if (a.bodyB != b.bodyB)
        return a.bodyB < b.bodyB;
    for (int k = 0; k < 3; ++k)
        if (a.point_W[k] != b.point_W[k])
            return a.point_W[k] < b.point_W[k];
    if (a.depth != b.depth)
        return a.depth < b.depth;
    for (int k = 0; k < 3; ++k)
        if (a.normal_W[k] != b.normal_W[k])
            return a.normal_W[k] < b.normal_W[k];
    return false;
}

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

// A body is searched along its motion when its travel over a step, |v| dt + |w| dt r (r: the
// distance of its farthest shape point from its centre of mass), exceeds this multiple of the
// margin; slower bodies are searched exactly as without the sweep. A slower body is seen within
// the margin at some step start before it overlaps anything by more than a margin
// (docs/method.md §10).
constexpr double cSweptMargins = 2.0;
// Conservative advancement (docs/method.md §10): it stops when the shapes are closer than this
// fraction of the margin (a hit) or after this many distance queries (taken as a miss: the next
// step looks again, from nearer).
constexpr double cSweepTolerance = 0.1;
constexpr int cSweepIterations = 64;

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

// Rounding allowance (m) of the travel bound: the pair must be proven farther apart than the
// margin by this much more before a pair is skipped on its bodies' travel alone.
constexpr double cTravelSlack = 1e-9;

} // namespace

struct ContactDetector::Impl
{
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
    void poseShape(int index, const core::State& state);
    void planePass(std::vector<Contact>& out);
    void sweptSpherePair(const ShapeInstance& a, const ShapeInstance& b, PairState& pair,
                         std::vector<Contact>& out);
    void narrowphase(int i, int j, PairState& pair, std::vector<Contact>& out);
    void addTravel(const core::State& state);
    void provenApart(PairState& pair, double distanceAtLeast) const;
    void sweepMotions(const core::State& state);
    double shapeReach(const ShapeInstance& s) const;
    fcl::Transform3d poseAt(const ShapeInstance& s, double tau, Mat3* turn) const;
    void sweptPair(int i, int j, std::vector<Contact>& out);
    bool nearestGap(int i, int j, RawContact& out, Vec3* apart = nullptr);
    void clipAgainstTriangles(int i, int j);
    void emit(int bodyA, int bodyB, std::vector<Contact>& out);
    static bool broadphaseCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data);
};

ContactDetector::Impl::Impl(const core::Model& model, double marginIn, MovingMeshes movingMeshes)
    : margin(marginIn), filter(model)
{
    triangle.geometry = triangleGeometry;
    const int bodyCount = static_cast<int>(model.bodies.size());
    bodyCollides.assign(model.bodies.size(), 0);
    // Shapes of one type and size share one FCL geometry and one ShapeGeometry (neither holds a
    // pose), so that a scene of many equal bodies costs one of each, not one per body; the same for
    // the inflated boxes. Meshes keep their own.
    struct Shared
    {
        std::shared_ptr<fcl::CollisionGeometryd> fcl;
        std::shared_ptr<const detail::ShapeGeometry> own;
    };
    std::map<std::array<double, 4>, Shared> geometries;
    std::size_t shapeCount = 0;
    for (const core::Body& body : model.bodies)
        for (const core::Shape& shape : body.shapes)
            shapeCount += shape.type == core::ShapeType::Plane ? 0 : 1;
    shapes.reserve(shapeCount);
    objects.reserve(shapeCount);
    inflatedBox.reserve(shapeCount);
    std::map<std::array<double, 3>, int> inflatedBySize;
    for (int b = 0; b < bodyCount; ++b)
    {
        const core::Body& body = model.bodies[static_cast<std::size_t>(b)];
        const Mat3 R_WB = body.orientation_WB.normalized().toRotationMatrix();
        for (const core::Shape& shape : body.shapes)
        {
            if (shape.type == core::ShapeType::Plane)
            {
                if (body.isStatic && shape.normal.norm() > 0.0) // moving planes are not supported
                {
                    planes.push_back({b, shape.normal.normalized(), shape.offset / shape.normal.norm()});
                    bodyCollides[static_cast<std::size_t>(b)] = 1;
                }
                continue;
            }
            const int index = static_cast<int>(shapes.size());
            const bool mesh = shape.type == core::ShapeType::Mesh;
            const bool box = shape.type == core::ShapeType::Box;
            Shared* shared =
                mesh ? nullptr
                     : &geometries[{static_cast<double>(shape.type), box ? shape.size.x() : shape.radius,
                                    box ? shape.size.y() : shape.length, box ? shape.size.z() : 0.0}];
            // Moving meshes collide as their convex hulls (built here, once); static ones keep
            // their triangles: terrain and fixtures may be concave, and nothing moves them into
            // each other (two static bodies never collide).
            shapes.push_back(
                detail::makeShapeInstance(shape, b, !body.isStatic && movingMeshes != MovingMeshes::Triangles,
                                          shared ? shared->own : nullptr,
                                          movingMeshes == MovingMeshes::ConvexHulls ? cHullCorners : 0));
            if (shared && !shared->own)
                shared->own = shapes.back().geometry;
            detail::setBodyPose(shapes.back(), R_WB, body.position_W);
            bodyCollides[static_cast<std::size_t>(b)] = 1;
            (body.isStatic ? staticShapes : movingShapes).push_back(index);
            std::unique_ptr<MarginObject> object;
            std::shared_ptr<fcl::CollisionGeometryd> geometry;
            if (mesh)
                geometry = makeGeometry(shape, shapes.back());
            else
            {
                if (!shared->fcl)
                    shared->fcl = makeGeometry(shape, shapes.back());
                geometry = shared->fcl;
            }
            if (geometry)
            {
                fcl::Transform3d tf = fcl::Transform3d::Identity();
                tf.linear() = shapes.back().R_WS;
                tf.translation() = shapes.back().p_WS;
                object = std::make_unique<MarginObject>(geometry, tf);
                object->setUserData(indexToUserData(index));
                object->updateFatAABB(margin);
            }
            objects.push_back(std::move(object));
            int inflated = -1;
            if (shape.type == core::ShapeType::Box)
            {
                const auto [it, added] = inflatedBySize.emplace(
                    std::array<double, 3>{shape.size.x(), shape.size.y(), shape.size.z()},
                    static_cast<int>(inflatedBoxes.size()));
                if (added)
                {
                    const Vec3 size = shape.size + Vec3::Constant(2.0 * margin);
                    inflatedBoxes.push_back(std::make_unique<fcl::CollisionObjectd>(
                        std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z()),
                        fcl::Transform3d::Identity()));
                }
                inflated = it->second;
            }
            inflatedBox.push_back(inflated);
        }
    }

    // Bodies that go to the broadphase: those with an FCL shape and an allowed partner among the
    // others with FCL shapes, counted in O(bodies + joints) (PairFilter::hasAllowedPartner).
    std::vector<char> fclBody(model.bodies.size(), 0);
    for (std::size_t s = 0; s < shapes.size(); ++s)
        if (objects[s])
            fclBody[static_cast<std::size_t>(shapes[s].body)] = 1;
    const std::vector<char> inBroadphase = filter.hasAllowedPartner(fclBody);
    registeredMoving.assign(shapes.size(), 0);
    std::vector<fcl::CollisionObjectd*> registered;
    for (std::size_t s = 0; s < shapes.size(); ++s)
    {
        if (!objects[s] || !inBroadphase[static_cast<std::size_t>(shapes[s].body)])
            continue;
        registered.push_back(objects[s].get());
        if (!filter.isStatic(shapes[s].body))
        {
            movingRegistered.push_back(objects[s].get());
            registeredMoving[s] = 1;
        }
    }
    // All at once: FCL builds the tree top-down in O(n log n), where inserting one at a time
    // degenerates on bodies laid along a line (a long chain). Every AABB here is finite (planes
    // never enter the broadphase).
    manager.registerObjects(registered);
    useBroadphase = !movingRegistered.empty();
    if (useBroadphase)
        manager.setup();

    // A moving shape that no plane and no other shape may touch (a chain whose links share a
    // group, say) is never posed: nothing would read its pose.
    std::erase_if(movingShapes,
                  [&](int index)
                  {
                      const int body = shapes[static_cast<std::size_t>(index)].body;
                      return !registeredMoving[static_cast<std::size_t>(index)] &&
                             std::none_of(planes.begin(), planes.end(),
                                          [&](const PlaneInstance& plane)
                                          { return filter.allowed(body, plane.body); });
                  });

    planeAllowed.reserve(movingShapes.size() * planes.size());
    for (const int index : movingShapes)
        for (const PlaneInstance& plane : planes)
            planeAllowed.push_back(
                filter.allowed(shapes[static_cast<std::size_t>(index)].body, plane.body) ? 1 : 0);

    bodyReach.assign(model.bodies.size(), 0.0);
    motions.assign(model.bodies.size(), BodyMotion{});
    bodyTravel.assign(model.bodies.size(), 0.0);
    lastPosition.assign(model.bodies.size(), Vec3::Zero());
    lastOrientation.assign(model.bodies.size(), core::Quat::Identity());
    for (const ShapeInstance& s : shapes)
        bodyReach[static_cast<std::size_t>(s.body)] =
            std::max(bodyReach[static_cast<std::size_t>(s.body)], s.p_BS.norm() + s.boundingRadius);
}

// Each moving body's motion over the coming step, and whether it is swept: its travel
// |v| dt + |w| dt r exceeds cSweptMargins margins (docs/method.md §10).
void ContactDetector::Impl::sweepMotions(const core::State& state)
{
    if (!(stepTime > 0.0))
    {
        if (anySwept) // switched off since the last call
            for (BodyMotion& m : motions)
                m.swept = false;
        anySwept = false;
        return;
    }
    anySwept = false;
    for (std::size_t b = 0; b < motions.size(); ++b)
    {
        BodyMotion& m = motions[b];
        const core::BodyState& body = state.bodies[b];
        const bool moves = !filter.isStatic(static_cast<int>(b));
        m.position = body.position_W;
        m.velocity = moves ? body.velocity_W : Vec3::Zero();
        m.angularVelocity = moves ? body.angularVelocity_W : Vec3::Zero();
        const double travel = (m.velocity.norm() + m.angularVelocity.norm() * bodyReach[b]) * stepTime;
        m.swept = moves && bodyCollides[b] && travel > cSweptMargins * margin;
        anySwept = anySwept || m.swept;
    }
}

// The farthest point of shape s from its body's centre of mass (m).
double ContactDetector::Impl::shapeReach(const ShapeInstance& s) const
{
    return s.p_BS.norm() + s.boundingRadius;
}

// Shape s's pose a fraction tau of the step ahead, its body moving with its velocities of the step
// start (the rotation exp(tau dt w) about the centre of mass, as the integrator turns it); turn
// receives that rotation.
fcl::Transform3d ContactDetector::Impl::poseAt(const ShapeInstance& s, double tau, Mat3* turn) const
{
    const BodyMotion& m = motions[static_cast<std::size_t>(s.body)];
    Mat3 Q = Mat3::Identity();
    const double angle = m.angularVelocity.norm() * tau * stepTime; // rad
    if (angle > 0.0)
        Q = Eigen::AngleAxisd(angle, m.angularVelocity.normalized()).toRotationMatrix();
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = Q * s.R_WS;
    tf.translation() = m.position + tau * stepTime * m.velocity + Q * (s.p_WS - m.position);
    *turn = Q;
    return tf;
}

void ContactDetector::Impl::poseShape(int index, const core::State& state)
{
    ShapeInstance& s = shapes[static_cast<std::size_t>(index)];
    const core::BodyState& body = state.bodies[static_cast<std::size_t>(s.body)];
    detail::setBodyPose(s, body.orientation_WB.normalized().toRotationMatrix(), body.position_W);
    if (MarginObject* object = objects[static_cast<std::size_t>(index)].get())
    {
        fcl::Transform3d tf = fcl::Transform3d::Identity();
        tf.linear() = s.R_WS;
        tf.translation() = s.p_WS;
        object->setTransform(tf);
        bool grown = false;
        const BodyMotion& m = motions[static_cast<std::size_t>(s.body)];
        if (m.swept)
        {
            // Along the travel over the step, and by the turn's reach on every side.
            const Vec3 d = stepTime * m.velocity; // m
            const Vec3 turn = Vec3::Constant(stepTime * m.angularVelocity.norm() * shapeReach(s));
            const Vec3 below = d.cwiseMin(Vec3::Zero()).cwiseAbs() + turn;
            const Vec3 above = d.cwiseMax(Vec3::Zero()) + turn;
            grown = object->updateFatAABB(margin, &below, &above);
        }
        else
            grown = object->updateFatAABB(margin);
        if (grown && registeredMoving[static_cast<std::size_t>(index)])
            changed.push_back(object);
    }
}

void ContactDetector::Impl::emit(int bodyA, int bodyB, std::vector<Contact>& out)
{
    for (const RawContact& c : raw)
        out.push_back({bodyA, bodyB, c.point_W, c.normal_W, c.depth});
    raw.clear();
}

void ContactDetector::Impl::planePass(std::vector<Contact>& out)
{
    const char* allowed = planeAllowed.data();
    for (const int index : movingShapes)
    {
        const ShapeInstance& s = shapes[static_cast<std::size_t>(index)];
        const BodyMotion& m = motions[static_cast<std::size_t>(s.body)];
        for (const PlaneInstance& plane : planes)
        {
            if (!*allowed++)
                continue;
            // A swept body's window reaches as far as it moves towards the plane in the step,
            // plus its turn's reach (docs/method.md §10); the solver's speculative rows then let
            // it close the gap, not pass it.
            double window = margin; // m
            if (m.swept)
                window += stepTime * (std::max(0.0, -plane.normal.dot(m.velocity)) +
                                      m.angularVelocity.norm() * shapeReach(s));
            if (plane.normal.dot(s.p_WS) - plane.offset - s.boundingRadius >= window)
                continue;
            ++stats.planeTests;
            raw.clear();
            detail::planeContacts(s, plane.normal, plane.offset, window, raw);
            detail::mergeAndReduce(raw, 0, s.mergeDistance);
            emit(s.body, plane.body, out);
        }
    }
}

bool ContactDetector::Impl::broadphaseCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2,
                                               void* data)
{
    auto* self = static_cast<Impl*>(data);
    int i = userDataToIndex(o1);
    int j = userDataToIndex(o2);
    int bi = self->shapes[static_cast<std::size_t>(i)].body;
    int bj = self->shapes[static_cast<std::size_t>(j)].body;
    if (bi == bj || (self->filter.isStatic(bi) && self->filter.isStatic(bj)))
        return false; // the filter is asked once per pair, when detect() first sees it (PairState)
    // A is the moving body; of two moving bodies, the lower index.
    if (self->filter.isStatic(bi) || (!self->filter.isStatic(bj) && bj < bi))
    {
        std::swap(i, j);
        std::swap(bi, bj);
    }
    self->shapePairs.emplace_back(i, j);
    return false; // never stop early
}

void ContactDetector::Impl::narrowphase(int i, int j, PairState& pair, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    const bool aTriangles = isTriangleMesh(a);
    const bool bTriangles = isTriangleMesh(b);
    const bool triangles = aTriangles || bTriangles;
    const bool polytopes = detail::usesPolytopeManifold(a, b);
    // Proven apart by more than the margin and the bodies' travel since: still apart beyond the
    // margin, no contact (any point of a shape moved at most its body's travel).
    if (pair.apart > 0.0 && pair.apart - (bodyTravel[static_cast<std::size_t>(a.body)] - pair.travelA) -
                                    (bodyTravel[static_cast<std::size_t>(b.body)] - pair.travelB) >
                                margin + cTravelSlack)
    {
        ++stats.separatedPairs;
        return;
    }
    pair.apart = 0.0;
    if (detail::isSweptSphere(a.type) && detail::isSweptSphere(b.type))
    {
        sweptSpherePair(a, b, pair, out);
        return;
    }
    // Apart beyond the margin along the axis that proved it last time, or along one of
    // separatedBeyond's: no contact within the margin, nothing for FCL to do.
    double separation = 0.0;
    if (pair.axis_S != Vec3::Zero() &&
        detail::separatedAlongAxis(a, b, a.R_WS * pair.axis_S, margin, &separation))
    {
        provenApart(pair, separation);
        ++stats.separatedPairs;
        return;
    }
    Vec3 axis_W = Vec3::Zero();
    if (detail::separatedBeyond(a, b, margin, &axis_W, &separation))
    {
        pair.axis_S = a.R_WS.transpose() * axis_W;
        provenApart(pair, separation);
        ++stats.separatedPairs;
        return;
    }
    pair.axis_S.setZero();
    axis_W.setZero(); // nearestGap sets it when it finds the pair apart beyond the margin

    if (polytopes)
    {
        // Two polytopes (hulls, boxes) are mostly apart, resting within the margin or farther:
        // fcl::distance alone says so, and the face clipping needs nothing more than the gap's
        // normal. FCL's collide (MPR: the normal and depth of an overlap) runs for the pairs
        // that touch.
        RawContact gap;
        const bool near = nearestGap(i, j, gap, &axis_W);
        if (near || axis_W != Vec3::Zero())
        {
            ++stats.narrowphaseTests;
            if (!near)
            {
                pair.axis_S = a.R_WS.transpose() * axis_W; // apart beyond the margin along it
                if (detail::separatedAlongAxis(a, b, axis_W, margin, &separation))
                    provenApart(pair, separation); // FCL's gap, proven by the support functions
                return;
            }
            raw.clear();
            detail::polytopeContacts(a, b, gap, margin, raw);
            detail::mergeAndReduce(raw, 0, std::min(a.mergeDistance, b.mergeDistance));
            emit(a.body, b.body, out);
            return;
        }
    }

    // FCL 0.7 computes a shape against a triangle mesh as the mesh against the shape, whatever
    // the argument order, and reports it that way (measured: the normal from the mesh towards
    // the shape, the triangle as primitive b1). So the mesh goes first, and its normals are
    // turned round when the mesh is b. Its sphere-triangle test returns the depth negated.
    const bool meshFirst = bTriangles && !aTriangles;
    result.clear(); // CollisionResult accumulates otherwise
    fcl::collide(objects[static_cast<std::size_t>(meshFirst ? j : i)].get(),
                 objects[static_cast<std::size_t>(meshFirst ? i : j)].get(),
                 triangles ? meshRequest : request, result);
    ++stats.narrowphaseTests;

    // FCL's points, normal from a to b, positive depth. Drop the degenerate ones (BVH meshes
    // give zero normals and zero depths).
    const double normalSign = meshFirst ? -1.0 : 1.0;
    const double depthSign =
        (aTriangles && b.type == core::ShapeType::Sphere) || (bTriangles && a.type == core::ShapeType::Sphere)
            ? -1.0
            : 1.0;
    raw.clear();
    rawTriangles.clear();
    double fclDepth = -std::numeric_limits<double>::infinity();
    RawContact deepest;
    for (std::size_t k = 0; k < result.numContacts(); ++k)
    {
        const fcl::Contactd& c = result.getContact(k);
        const double length = c.normal.norm();
        const double depth = depthSign * c.penetration_depth;
        if (!(length > 0.5) || !(depth > 0.0) || !c.pos.allFinite())
            continue;
        raw.push_back({c.pos, normalSign * (c.normal / length), depth});
        rawTriangles.push_back(c.b1); // the triangle, when one shape is a triangle mesh (it went first)
        if (depth > fclDepth)
        {
            fclDepth = depth;
            deepest = raw.back();
        }
    }

    if (polytopes)
    {
        // A hull against a hull or a box: one face clipped against the other along FCL's normal
        // (or, apart, the normal of the gap) for the whole patch.
        RawContact reference = deepest;
        raw.clear();
        if (fclDepth > 0.0 || nearestGap(i, j, reference, &axis_W))
            detail::polytopeContacts(a, b, reference, margin, raw);
    }
    else if (triangles && !(aTriangles && bTriangles) && (detail::isPolytope(a) || detail::isPolytope(b)))
    {
        clipAgainstTriangles(i, j);
    }
    else if (detail::usesFeatureManifold(a, b))
    {
        const std::size_t fclCount = raw.size();
        detail::featureContacts(a, b, fclCount > 0 ? &deepest : nullptr, margin, raw);
        if (fclCount > 0 && raw.size() > fclCount)
        {
            double featureDepth = -std::numeric_limits<double>::infinity();
            for (std::size_t k = fclCount; k < raw.size(); ++k)
                featureDepth = std::max(featureDepth, raw[k].depth);
            // FCL's single point is redundant when the features reach its depth.
            if (fclDepth <= featureDepth + std::max(0.1 * margin, 1e-6))
                raw.erase(raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(fclCount));
        }
    }
    const int inflatedIndex = inflatedBox[static_cast<std::size_t>(i)];
    if (raw.empty() && inflatedIndex >= 0 && b.type == core::ShapeType::Box)
    {
        fcl::CollisionObjectd* inflated = inflatedBoxes[static_cast<std::size_t>(inflatedIndex)].get();
        inflated->setTransform(objects[static_cast<std::size_t>(i)]->getTransform()); // box i's pose
        // Two boxes apart: the manifold of a grown by the margin, depths less the margin (< 0).
        result.clear();
        fcl::collide(inflated, objects[static_cast<std::size_t>(j)].get(), request, result);
        for (std::size_t k = 0; k < result.numContacts(); ++k)
        {
            const fcl::Contactd& c = result.getContact(k);
            const double length = c.normal.norm();
            if (length > 0.5 && c.penetration_depth > 0.0 && c.pos.allFinite())
                raw.push_back({c.pos, c.normal / length, c.penetration_depth - margin});
        }
    }
    else if (raw.empty() && !triangles && !polytopes)
    {
        // Apart: a speculative contact at the nearest points when the gap is below the margin,
        // so that a body arriving fast is caught before it sinks in (depth = -gap).
        RawContact gap;
        if (nearestGap(i, j, gap, &axis_W))
            raw.push_back(gap);
    }
    if (axis_W != Vec3::Zero())
        pair.axis_S = a.R_WS.transpose() * axis_W; // found apart beyond the margin along it
    detail::mergeAndReduce(raw, 0, std::min(a.mergeDistance, b.mergeDistance));
    emit(a.body, b.body, out);
}

// Pair is farther apart than distanceAtLeast (m, > margin) at the bodies' present travel.
void ContactDetector::Impl::provenApart(PairState& pair, double distanceAtLeast) const
{
    pair.apart = distanceAtLeast;
    pair.travelA = bodyTravel[static_cast<std::size_t>(shapes[static_cast<std::size_t>(pair.i)].body)];
    pair.travelB = bodyTravel[static_cast<std::size_t>(shapes[static_cast<std::size_t>(pair.j)].body)];
}

// Adds each body's move since the last call to its travel: |dp| of its centre of mass plus what
// the turn moves the farthest shape point, 2 |sin(angle / 2)| reach = 2 |vec(q_last* q)| reach.
void ContactDetector::Impl::addTravel(const core::State& state)
{
    for (std::size_t b = 0; b < bodyTravel.size(); ++b)
    {
        if (!bodyCollides[b])
            continue;
        const core::BodyState& body = state.bodies[b];
        const core::Quat q = body.orientation_WB.normalized();
        if (travelStarted)
            bodyTravel[b] += (body.position_W - lastPosition[b]).norm() +
                             2.0 * (lastOrientation[b].conjugate() * q).vec().norm() * bodyReach[b];
        lastPosition[b] = body.position_W;
        lastOrientation[b] = q;
    }
    travelStarted = true;
}

// A box or a hull (one of shapes i and j) against a triangle mesh (the other): the contacts of
// the polytope clipped against each triangle that FCL reported touching (raw, rawTriangles),
// with FCL's contact there as the reference; they replace raw.
void ContactDetector::Impl::clipAgainstTriangles(int i, int j)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    const bool meshIsB = isTriangleMesh(b);
    const fcl::CollisionObjectd& object = *objects[static_cast<std::size_t>(meshIsB ? j : i)];
    const auto& mesh = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(*object.collisionGeometry());
    const fcl::Transform3d& tf = object.getTransform();
    clipped.clear();
    for (std::size_t k = 0; k < raw.size(); ++k)
    {
        const std::intptr_t t = rawTriangles[k];
        if (t < 0 || t >= mesh.num_tris)
            continue;
        const fcl::Triangle& corners = mesh.tri_indices[t];
        if (!detail::setTrianglePolytope(tf * mesh.vertices[corners[0]], tf * mesh.vertices[corners[1]],
                                         tf * mesh.vertices[corners[2]], *triangleGeometry, triangle))
            continue;
        if (meshIsB)
            detail::polytopeContacts(a, triangle, raw[k], margin, clipped);
        else
            detail::polytopeContacts(triangle, b, raw[k], margin, clipped);
    }
    raw.swap(clipped);
}

// The nearest points of shapes i and j when they are apart by less than the margin: a contact
// halfway between them, normal from i towards j, depth = -gap. False when they touch, overlap or
// are farther apart; when farther apart, `apart` (if given) receives the unit direction from i's
// nearest point to j's, along which they are separated by the gap (for PairState).
bool ContactDetector::Impl::nearestGap(int i, int j, RawContact& out, Vec3* apart)
{
    distanceResult.clear();
    const double gap =
        fcl::distance(objects[static_cast<std::size_t>(i)].get(), objects[static_cast<std::size_t>(j)].get(),
                      distanceRequest, distanceResult);
    if (!(gap > 0.0))
        return false;
    const Vec3 pa = distanceResult.nearest_points[0];
    const Vec3 pb = distanceResult.nearest_points[1];
    const Vec3 d = pb - pa;
    if (!(d.norm() > 1e-12) || !pa.allFinite() || !pb.allFinite())
        return false;
    if (!(gap < margin))
    {
        if (apart != nullptr)
            *apart = d / d.norm();
        return false;
    }
    out = {0.5 * (pa + pb), d / d.norm(), -gap};
    return true;
}

// Spheres and capsules in closed form (swept_spheres.cpp) instead of libccd's MPR and GJK; a
// capsule pair then gets its feature points as FCL's point would, the closed-form point kept
// unless the features reach its depth.
void ContactDetector::Impl::sweptSpherePair(const ShapeInstance& a, const ShapeInstance& b, PairState& pair,
                                            std::vector<Contact>& out)
{
    ++stats.narrowphaseTests;
    raw.clear();
    RawContact closest;
    double separation = 0.0; // m: the segments' distance less the radii, exact
    const bool near = detail::sweptSphereContact(a, b, margin, closest, &separation);
    if (!near && separation > margin)
        provenApart(pair, separation);
    // A pair farther apart than the margin has no feature within it either: each feature is a
    // point of one segment with that capsule's radius, no nearer the other than the segments are.
    if (near && detail::usesFeatureManifold(a, b))
    {
        detail::featureContacts(a, b, near && closest.depth > 0.0 ? &closest : nullptr, margin, raw);
    }
    if (near)
    {
        double featureDepth = -std::numeric_limits<double>::infinity();
        for (const RawContact& c : raw)
            featureDepth = std::max(featureDepth, c.depth);
        if (raw.empty() || closest.depth > featureDepth + std::max(0.1 * margin, 1e-6))
            raw.push_back(closest);
    }
    detail::mergeAndReduce(raw, 0, std::min(a.mergeDistance, b.mergeDistance));
    emit(a.body, b.body, out);
}

// A pair with a swept body that is farther apart than the margin at the step start: conservative
// advancement along both bodies' motion over the step (docs/method.md §10). The pair's distance
// shrinks by at most mu = dt (|v_B - v_A| + |w_A| r_A + |w_B| r_B) over the whole step, so advancing
// by distance / mu never passes a touch. When the shapes come within cSweepTolerance of the
// margin before the step ends, the contact is that of the touch, carried back to the step start:
// the touch's normal, the points where they were at the start, the gap between them along the
// normal (depth = -gap). A pair that passes by (or moves apart) gets none, so a fast body is
// never stopped by what it would miss.
void ContactDetector::Impl::sweptPair(int i, int j, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    const BodyMotion& ma = motions[static_cast<std::size_t>(a.body)];
    const BodyMotion& mb = motions[static_cast<std::size_t>(b.body)];
    const Vec3& va = ma.velocity; // zero for a static body (sweepMotions)
    const Vec3& vb = mb.velocity;
    const double wa = ma.angularVelocity.norm();
    const double wb = mb.angularVelocity.norm();
    const double mu = stepTime * ((vb - va).norm() + wa * shapeReach(a) + wb * shapeReach(b)); // m per step
    if (!(mu > 0.0))
        return;
    const fcl::CollisionGeometryd* ga = objects[static_cast<std::size_t>(i)]->collisionGeometry().get();
    const fcl::CollisionGeometryd* gb = objects[static_cast<std::size_t>(j)]->collisionGeometry().get();
    const double tolerance = cSweepTolerance * margin; // m
    const bool triangles = isTriangleMesh(a) || isTriangleMesh(b);
    if (isTriangleMesh(a) && isTriangleMesh(b))
        return; // two triangle meshes (a moving mesh without its hull): not swept
    double tau = 0.0;
    Mat3 turnA = Mat3::Identity();
    Mat3 turnB = Mat3::Identity();
    for (int k = 0; k < cSweepIterations; ++k)
    {
        const fcl::Transform3d tfA = poseAt(a, tau, &turnA);
        const fcl::Transform3d tfB = poseAt(b, tau, &turnB);
        distanceResult.clear();
        const double d = fcl::distance(ga, tfA, gb, tfB, distanceRequest, distanceResult);
        ++stats.narrowphaseTests;
        if (!(d >= 0.0))
            return; // touching already (the margin search's business at tau = 0) or no answer
        if (k == 0 && d < margin && !triangles)
            return; // within the margin: the ordinary search saw it (triangles report no gaps)
        if (d < tolerance)
        {
            Vec3 pa = distanceResult.nearest_points[0];
            Vec3 pb = distanceResult.nearest_points[1];
            if (triangles)
            {
                // FCL 0.7 gives a mesh-shape pair's nearest points in the frames of the mesh
                // ([0]) and of the shape ([1]), whatever the argument order (measured).
                const bool meshIsA = isTriangleMesh(a);
                pa = tfA * distanceResult.nearest_points[meshIsA ? 0 : 1];
                pb = tfB * distanceResult.nearest_points[meshIsA ? 1 : 0];
            }
            const Vec3 between = pb - pa;
            if (!(between.norm() > 1e-12) || !pa.allFinite() || !pb.allFinite())
                return;
            const Vec3 n = between / between.norm();
            // The touching points where they were at the step start.
            const Vec3 ca = ma.position + tau * stepTime * va;
            const Vec3 pa0 = ma.position + turnA.transpose() * (pa - ca);
            const Vec3 cb = mb.position + tau * stepTime * vb;
            const Vec3 pb0 = mb.position + turnB.transpose() * (pb - cb);
            const double gap = std::max((pb0 - pa0).dot(n), d); // m
            raw.clear();
            raw.push_back({0.5 * (pa0 + pb0), n, -gap});
            emit(a.body, b.body, out);
            return;
        }
        tau += (d - 0.5 * tolerance) / mu;
        if (tau > 1.0)
            return; // apart over the whole step
    }
}

ContactDetector::ContactDetector(const core::Model& model, double margin, MovingMeshes movingMeshes)
    : mImpl(std::make_unique<Impl>(model, margin, movingMeshes))
{
}

ContactDetector::~ContactDetector() = default;

void ContactDetector::detect(const core::State& state, std::vector<Contact>& out)
{
    Impl& m = *mImpl;
    if (state.bodies.size() != m.bodyCollides.size())
        throw std::invalid_argument("ContactDetector::detect: the state does not match the model");
    out.clear();
    ++m.stats.detectCalls;

    m.sweepMotions(state);
    m.addTravel(state);
    m.changed.clear();
    for (const int index : m.movingShapes)
        m.poseShape(index, state);
    if (!m.staticPosed)
    {
        for (const int index : m.staticShapes)
            m.poseShape(index, state);
        m.staticPosed = true;
        if (m.useBroadphase)
            m.manager.update();
    }
    else if (m.useBroadphase && !m.changed.empty())
        m.manager.update(m.changed);

    m.planePass(out);

    if (m.useBroadphase)
    {
        m.shapePairs.clear();
        m.manager.collide(&m, &Impl::broadphaseCallback);
        std::sort(m.shapePairs.begin(), m.shapePairs.end());
        // Each pair's state from the last call, if the broadphase reported it then too (both
        // lists sorted: one merge pass); a pair it no longer reports is forgotten.
        m.nextPairStates.clear();
        std::size_t last = 0;
        for (const auto& [i, j] : m.shapePairs)
        {
            while (last < m.pairStates.size() &&
                   std::pair(m.pairStates[last].i, m.pairStates[last].j) < std::pair(i, j))
                ++last;
            if (last < m.pairStates.size() && m.pairStates[last].i == i && m.pairStates[last].j == j)
                m.nextPairStates.push_back(m.pairStates[last]);
            else
                m.nextPairStates.push_back({i, j,
                                            m.filter.allowed(m.shapes[static_cast<std::size_t>(i)].body,
                                                             m.shapes[static_cast<std::size_t>(j)].body),
                                            Vec3::Zero()});
            if (!m.nextPairStates.back().allowed)
                continue;
            ++m.stats.broadphasePairs;
            const std::size_t before = out.size();
            m.narrowphase(i, j, m.nextPairStates.back(), out);
            if (m.anySwept && out.size() == before &&
                (m.motions[static_cast<std::size_t>(m.shapes[static_cast<std::size_t>(i)].body)].swept ||
                 m.motions[static_cast<std::size_t>(m.shapes[static_cast<std::size_t>(j)].body)].swept))
                m.sweptPair(i, j, out);
        }
        std::swap(m.pairStates, m.nextPairStates);
    }

    std::sort(out.begin(), out.end(), contactLess);
    m.stats.contacts += static_cast<long>(out.size());
}

const std::vector<std::pair<int, int>>& ContactDetector::candidatePairs() const
{
    Impl& m = *mImpl;
    if (!m.candidatesReady)
    {
        const int n = static_cast<int>(m.bodyCollides.size());
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j)
                if (m.bodyCollides[static_cast<std::size_t>(i)] &&
                    m.bodyCollides[static_cast<std::size_t>(j)] && m.filter.allowed(i, j))
                    m.candidates.emplace_back(i, j);
        m.candidatesReady = true;
    }
    return m.candidates;
}

long long ContactDetector::candidatePairCount() const
{
    return mImpl->filter.allowedPairCount(mImpl->bodyCollides);
}

double contactMargin(double dt)
{
    return std::clamp(5.0 * dt, 2e-3, 0.05);
}

void ContactDetector::setStepTime(double dt)
{
    mImpl->stepTime = dt > 0.0 ? dt : 0.0;
}

double ContactDetector::margin() const
{
    return mImpl->margin;
}

const DetectorStats& ContactDetector::stats() const
{
    return mImpl->stats;
}

} // namespace frontier::collision
