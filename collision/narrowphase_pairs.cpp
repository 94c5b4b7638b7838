// collision/narrowphase_pairs.cpp: the pair functions of the narrowphase table (narrowphase.cpp),
// one per family of collision kinds, and the steps they share.
//   sweptSpherePair       spheres and capsules against each other, in closed form (swept_spheres.cpp)
//   polytopePair          a hull against a hull or a box: fcl::distance first, fcl::collide only
//                         when they touch, then one face clipped against the other
//                         (polytope_manifold.cpp)
//   boxBoxPair            FCL's box-box manifold (up to 4 points); apart, that of the box grown by
//                         the margin
//   convexPair            the other convex pairs: FCL's point, the feature points where one shape
//                         has features (feature_manifold.cpp), a gap contact at the nearest points
//                         when apart by less than the margin
//   trianglePolytopePair  a box or a hull against a triangle mesh: clipped against each triangle
//                         FCL reports touching
//   triangleShapePair     a sphere, capsule, cylinder or triangle mesh against a triangle mesh:
//                         FCL's per-triangle points, plus the feature points
// FCL 0.7 computes a shape against a triangle mesh as the mesh against the shape, whatever the
// argument order, and reports it that way (measured: the normal from the mesh towards the shape,
// the triangle as primitive b1). So the mesh goes first, and its normals are turned round when the
// mesh is b. Its sphere-triangle test returns the depth negated.
#include "collision/detector.h"

#include <algorithm>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/triangle.h>
#include <limits>

namespace frontier::collision
{

namespace
{

using detail::CollisionKind;
using detail::RawContact;
using detail::ShapeInstance;
using detail::Vec3;

bool isTriangles(const ShapeInstance& s)
{
    return s.kind == CollisionKind::Triangles;
}

} // namespace

// Spheres and capsules in closed form (swept_spheres.cpp) instead of libccd's MPR and GJK; a
// capsule pair then gets its feature points as FCL's point would, the closed-form point kept
// unless the features reach its depth.
void ContactDetector::Impl::sweptSpherePair(int i, int j, PairState& pair, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
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
    finishPair(a, b, out);
}

// Two polytopes (hulls, boxes) are mostly apart, resting within the margin or farther:
// fcl::distance alone says so, and the face clipping needs nothing more than the gap's normal.
// FCL's collide (MPR: the normal and depth of an overlap) runs for the pairs that touch; one face
// is then clipped against the other along FCL's normal (or, apart, the normal of the gap).
void ContactDetector::Impl::polytopePair(int i, int j, PairState& pair, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    Vec3 axis_W = Vec3::Zero(); // nearestGap sets it when it finds the pair apart beyond the margin
    RawContact gap;
    const bool near = nearestGap(i, j, gap, &axis_W);
    if (near || axis_W != Vec3::Zero())
    {
        ++stats.narrowphaseTests;
        if (!near)
        {
            pair.axis_S = a.R_WS.transpose() * axis_W; // apart beyond the margin along it
            double separation = 0.0;
            if (detail::separatedAlongAxis(a, b, axis_W, margin, &separation))
                provenApart(pair, separation); // FCL's gap, proven by the support functions
            return;
        }
        raw.clear();
        detail::polytopeContacts(a, b, gap, margin, raw);
        finishPair(a, b, out);
        return;
    }
    double fclDepth = 0.0;
    RawContact reference = collideFcl(i, j, fclDepth);
    raw.clear();
    if (fclDepth > 0.0 || nearestGap(i, j, reference, &axis_W))
        detail::polytopeContacts(a, b, reference, margin, raw);
    if (axis_W != Vec3::Zero())
        pair.axis_S = a.R_WS.transpose() * axis_W;
    finishPair(a, b, out);
}

// FCL's box-box manifold; two boxes apart get that of box a grown by the margin (speculative
// contacts).
void ContactDetector::Impl::boxBoxPair(int i, int j, PairState& /*pair*/, std::vector<Contact>& out)
{
    double fclDepth = 0.0;
    collideFcl(i, j, fclDepth);
    if (raw.empty())
        inflatedBoxContacts(i, j);
    finishPair(shapes[static_cast<std::size_t>(i)], shapes[static_cast<std::size_t>(j)], out);
}

// FCL's point, the feature points (detail::usesFeatureManifold), and apart, a speculative contact
// at the nearest points when the gap is below the margin, so that a body arriving fast is caught
// before it sinks in (depth = -gap).
void ContactDetector::Impl::convexPair(int i, int j, PairState& pair, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    collideWithFeatures(i, j);
    Vec3 axis_W = Vec3::Zero(); // nearestGap sets it when it finds the pair apart beyond the margin
    RawContact gap;
    if (raw.empty() && nearestGap(i, j, gap, &axis_W))
        raw.push_back(gap);
    if (axis_W != Vec3::Zero())
        pair.axis_S = a.R_WS.transpose() * axis_W; // found apart beyond the margin along it
    finishPair(a, b, out);
}

void ContactDetector::Impl::trianglePolytopePair(int i, int j, PairState& /*pair*/, std::vector<Contact>& out)
{
    double fclDepth = 0.0;
    collideFcl(i, j, fclDepth);
    clipAgainstTriangles(i, j);
    finishPair(shapes[static_cast<std::size_t>(i)], shapes[static_cast<std::size_t>(j)], out);
}

void ContactDetector::Impl::triangleShapePair(int i, int j, PairState& /*pair*/, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    collideWithFeatures(i, j);
    finishPair(a, b, out);
}

// fcl::collide of shapes i and j: its points into raw (normal from a to b, positive depth; the
// degenerate ones dropped: BVH meshes give zero normals and zero depths), the triangle of each
// into rawTriangles when one shape is a triangle mesh. Returns the deepest point, its depth in
// fclDepth (-infinity when there is none).
RawContact ContactDetector::Impl::collideFcl(int i, int j, double& fclDepth)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    const bool aTriangles = isTriangles(a);
    const bool bTriangles = isTriangles(b);
    const bool meshFirst = bTriangles && !aTriangles;
    result.clear(); // CollisionResult accumulates otherwise
    fcl::collide(objects[static_cast<std::size_t>(meshFirst ? j : i)].get(),
                 objects[static_cast<std::size_t>(meshFirst ? i : j)].get(),
                 aTriangles || bTriangles ? meshRequest : request, result);
    ++stats.narrowphaseTests;
    const double normalSign = meshFirst ? -1.0 : 1.0;
    const double depthSign =
        (aTriangles && b.type == core::ShapeType::Sphere) || (bTriangles && a.type == core::ShapeType::Sphere)
            ? -1.0
            : 1.0;
    raw.clear();
    rawTriangles.clear();
    fclDepth = -std::numeric_limits<double>::infinity();
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
    return deepest;
}

// fcl::collide of shapes i and j, then the feature points of both appended (where
// detail::usesFeatureManifold says): FCL's points are dropped when the features reach their
// depth, as its single point is then redundant.
void ContactDetector::Impl::collideWithFeatures(int i, int j)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    double fclDepth = 0.0;
    const RawContact deepest = collideFcl(i, j, fclDepth);
    if (!detail::usesFeatureManifold(a, b))
        return;
    const std::size_t fclCount = raw.size();
    detail::featureContacts(a, b, fclCount > 0 ? &deepest : nullptr, margin, raw);
    if (fclCount > 0 && raw.size() > fclCount)
    {
        double featureDepth = -std::numeric_limits<double>::infinity();
        for (std::size_t k = fclCount; k < raw.size(); ++k)
            featureDepth = std::max(featureDepth, raw[k].depth);
        if (fclDepth <= featureDepth + std::max(0.1 * margin, 1e-6))
            raw.erase(raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(fclCount));
    }
}

// Two boxes apart: the manifold of box i grown by the margin against box j, depths less the
// margin (< 0), into raw.
void ContactDetector::Impl::inflatedBoxContacts(int i, int j)
{
    const int inflatedIndex = inflatedBox[static_cast<std::size_t>(i)];
    fcl::CollisionObjectd* inflated = inflatedBoxes[static_cast<std::size_t>(inflatedIndex)].get();
    inflated->setTransform(objects[static_cast<std::size_t>(i)]->getTransform()); // box i's pose
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

// The pair's contacts in raw merged and reduced (manifold.cpp), then given to bodies a and b.
void ContactDetector::Impl::finishPair(const ShapeInstance& a, const ShapeInstance& b,
                                       std::vector<Contact>& out)
{
    detail::mergeAndReduce(raw, 0, std::min(a.mergeDistance, b.mergeDistance));
    emit(a.body, b.body, out);
}

// A box or a hull (one of shapes i and j) against a triangle mesh (the other): the contacts of
// the polytope clipped against each triangle that FCL reported touching (raw, rawTriangles),
// with FCL's contact there as the reference; they replace raw.
void ContactDetector::Impl::clipAgainstTriangles(int i, int j)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
    const bool meshIsB = b.kind == detail::CollisionKind::Triangles;
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

} // namespace frontier::collision
