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
//   4. Narrowphase per pair (narrowphase.cpp): the early-outs, then the pair function that a
//      table keyed by the two shapes' collision kinds selects (narrowphase_pairs.cpp).
//      Spheres and capsules against each other in closed form
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

#include "collision/detector.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/triangle.h>
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

} // namespace

ContactDetector::Impl::Impl(const core::Model& model, double marginIn, MovingMeshes movingMeshes)
    : margin(marginIn), filter(model)
{
    triangle.geometry = triangleGeometry;
    bodyCollides.assign(model.bodies.size(), 0);
    std::size_t shapeCount = 0;
    for (const core::Body& body : model.bodies)
        for (const core::Shape& shape : body.shapes)
            shapeCount += shape.type == core::ShapeType::Plane ? 0 : 1;
    shapes.reserve(shapeCount);
    objects.reserve(shapeCount);
    inflatedBox.reserve(shapeCount);
    // Shapes of one type and size share one FCL geometry and one ShapeGeometry, so that a scene
    // of many equal bodies costs one of each, not one per body; the same for the inflated boxes.
    // Meshes keep their own.
    SharedGeometries geometries;
    InflatedBySize inflatedBySize;
    for (int b = 0; b < static_cast<int>(model.bodies.size()); ++b)
    {
        const core::Body& body = model.bodies[static_cast<std::size_t>(b)];
        const Mat3 R_WB = body.orientation_WB.normalized().toRotationMatrix();
        for (const core::Shape& shape : body.shapes)
            addShape(model, b, shape, R_WB, movingMeshes, geometries, inflatedBySize);
    }
    registerBroadphase();
    dropUnreachableShapes();
    planeAllowed.reserve(movingShapes.size() * planes.size());
    for (const int index : movingShapes)
        for (const PlaneInstance& plane : planes)
            planeAllowed.push_back(
                filter.allowed(shapes[static_cast<std::size_t>(index)].body, plane.body) ? 1 : 0);
    startMotions(model.bodies.size());
}

// One shape of body b: a static plane joins `planes`; any other shape becomes an instance posed
// at the body's pose (R_WB, body.position_W), with its FCL object and, for a box, its inflated box.
void ContactDetector::Impl::addShape(const core::Model& model, int b, const core::Shape& shape,
                                     const Mat3& R_WB, MovingMeshes movingMeshes,
                                     SharedGeometries& geometries, InflatedBySize& inflatedBySize)
{
    const core::Body& body = model.bodies[static_cast<std::size_t>(b)];
    if (shape.type == core::ShapeType::Plane)
    {
        if (body.isStatic && shape.normal.norm() > 0.0) // moving planes are not supported
        {
            planes.push_back({b, shape.normal.normalized(), shape.offset / shape.normal.norm()});
            bodyCollides[static_cast<std::size_t>(b)] = 1;
        }
        return;
    }
    const int index = static_cast<int>(shapes.size());
    const bool mesh = shape.type == core::ShapeType::Mesh;
    const bool box = shape.type == core::ShapeType::Box;
    Shared* shared = mesh ? nullptr
                          : &geometries[{static_cast<double>(shape.type), box ? shape.size.x() : shape.radius,
                                         box ? shape.size.y() : shape.length, box ? shape.size.z() : 0.0}];
    // Moving meshes collide as their convex hulls (built here, once); static ones keep their
    // triangles: terrain and fixtures may be concave, and nothing moves them into each other (two
    // static bodies never collide).
    shapes.push_back(detail::makeShapeInstance(
        shape, b, !body.isStatic && movingMeshes != MovingMeshes::Triangles, shared ? shared->own : nullptr,
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
    if (box)
    {
        const auto [it, added] =
            inflatedBySize.emplace(std::array<double, 3>{shape.size.x(), shape.size.y(), shape.size.z()},
                                   static_cast<int>(inflatedBoxes.size()));
        if (added)
        {
            const Vec3 size = shape.size + Vec3::Constant(2.0 * margin);
            inflatedBoxes.push_back(std::make_unique<fcl::CollisionObjectd>(
                std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z()), fcl::Transform3d::Identity()));
        }
        inflated = it->second;
    }
    inflatedBox.push_back(inflated);
}

// Bodies that go to the broadphase: those with an FCL shape and an allowed partner among the
// others with FCL shapes, counted in O(bodies + joints) (PairFilter::hasAllowedPartner).
void ContactDetector::Impl::registerBroadphase()
{
    std::vector<char> fclBody(bodyCollides.size(), 0);
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
}

// A moving shape that no plane and no other shape may touch (a chain whose links share a group,
// say) is never posed: nothing would read its pose.
void ContactDetector::Impl::dropUnreachableShapes()
{
    std::erase_if(movingShapes,
                  [&](int index)
                  {
                      const int body = shapes[static_cast<std::size_t>(index)].body;
                      return !registeredMoving[static_cast<std::size_t>(index)] &&
                             std::none_of(planes.begin(), planes.end(),
                                          [&](const PlaneInstance& plane)
                                          { return filter.allowed(body, plane.body); });
                  });
}

// Per body: its reach, and its motion and travel before the first detect() call.
void ContactDetector::Impl::startMotions(std::size_t bodyCount)
{
    bodyReach.assign(bodyCount, 0.0);
    motions.assign(bodyCount, BodyMotion{});
    bodyTravel.assign(bodyCount, 0.0);
    lastPosition.assign(bodyCount, Vec3::Zero());
    lastOrientation.assign(bodyCount, core::Quat::Identity());
    for (const ShapeInstance& s : shapes)
        bodyReach[static_cast<std::size_t>(s.body)] =
            std::max(bodyReach[static_cast<std::size_t>(s.body)], s.p_BS.norm() + s.boundingRadius);
}

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

// by distance / mu never passes a touch. When the shapes come within cSweepTolerance of the
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
    const bool aTriangles = a.kind == detail::CollisionKind::Triangles;
    const bool bTriangles = b.kind == detail::CollisionKind::Triangles;
    const bool triangles = aTriangles || bTriangles;
    if (aTriangles && bTriangles)
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
                const bool meshIsA = aTriangles;
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
