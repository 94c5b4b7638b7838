// collision/internal.h: private to collision/ (never include it from other folders). Shape
// instances in world pose (a moving mesh as its convex hull), raw contacts between two shapes,
// and the helpers that build contact manifolds without FCL: the plane manifolds, the
// feature-point manifolds of capsules, cylinders and meshes, the clipped faces of polytopes,
// and the merge/reduce step. FCL stays out of this header.
#pragma once

#include "collision/convex_hull.h"
#include "collision/filter.h"
#include "core/model.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace frontier::collision::detail
{

using core::Mat3;
using core::Vec3;

// A contact between two shapes a and b, before it is assigned to bodies.
struct RawContact
{
    Vec3 point_W = Vec3::Zero();   // m, middle of the overlap
    Vec3 normal_W = Vec3::UnitZ(); // unit, from shape a towards shape b
    double depth = 0.0;            // m, > 0 penetrating, < 0 a gap within the margin
};

using collision::ConvexHull;

// The geometry of a shape in its own frame S that does not depend on where the shape is: a box's
// polytope, a mesh's vertices and hull. Instances of equal shapes share one (a chain of a million
// equal boxes holds one box polytope, not a million).
struct ShapeGeometry
{
    std::vector<Vec3> meshVertices;    // Mesh: unique vertices in S (m); the hull's when convexHull
    Vec3 meshBoxCentre = Vec3::Zero(); // Mesh: centre of the box in S that holds meshVertices (m)
    Vec3 meshBoxHalf = Vec3::Zero();   // Mesh: its half extents along S's axes (m)
    // convexHull: each corner's neighbours along the hull's edges, for hill climbing to the corner
    // furthest along a direction (hullExtremeCorner) in a few steps instead of a pass over all.
    std::vector<std::vector<int>> hullNeighbours;
    std::vector<int> hullSeeds; // the corners furthest along the 26 directions of a cube's faces,
                                // edges and corners: the climb starts at the best of them
    // The shape as a convex polytope, in S: the hull of a convexHull mesh, or a box's 8 corners
    // and 6 faces (for the face clipping of polytope_manifold.cpp); empty for other shapes.
    ConvexHull hull;
    // convexHull: how many corners the mesh's full hull has, and how far (m) that full hull reaches
    // beyond `hull` when `hull` keeps only some of them (capConvexHull; 0 when it keeps all).
    int fullHullCorners = 0;
    double hullDeviation = 0.0;
};

// How a shape collides: the key of the narrowphase table (narrowphase.cpp). A mesh is a Hull when
// it collides as its convex hull (a moving mesh), Triangles when as its triangles (FCL's BVH: a
// static mesh, or one without a 3-d hull). Planes are not instances (the plane pass handles them).
enum class CollisionKind : std::uint8_t
{
    Sphere,
    Capsule,
    Box,
    Cylinder,
    Hull,
    Triangles, // the last kind: cCollisionKinds counts up to it
};
inline constexpr int cCollisionKinds = static_cast<int>(CollisionKind::Triangles) + 1;

// "sphere", "capsule", "box", "cylinder", "hull", "triangles".
const char* collisionKindName(CollisionKind kind);

// The name of the narrowphase function of a pair of kinds (narrowphase.cpp's table), in either
// order; nullptr when the table has no entry for the pair.
const char* narrowphaseName(CollisionKind a, CollisionKind b);

// One non-plane shape of one body, with its geometry in its own frame S and its current pose.
struct ShapeInstance
{
    int body = 0; // index in core::Model::bodies
    core::ShapeType type = core::ShapeType::Box;
    // Mesh of a moving body: it collides as its convex hull (FCL's Convex, GJK/EPA), not as
    // triangles (FCL's BVH). False for static meshes (terrain may be concave) and for meshes
    // without a 3-d hull (flat or collinear vertices: they keep the triangles).
    bool convexHull = false;
    CollisionKind kind = CollisionKind::Box;       // set with type and convexHull
    Vec3 halfExtents = Vec3::Zero();               // Box (m)
    double radius = 0.0;                           // Sphere, Capsule, Cylinder (m)
    double halfLength = 0.0;                       // Capsule: half segment; Cylinder: half height (m)
    double boundingRadius = 0.0;                   // of a sphere about the shape origin holding the shape (m)
    double mergeDistance = 0.0;                    // contacts of one pair closer than this are merged (m)
    std::shared_ptr<const ShapeGeometry> geometry; // never null once made
    // Fixed pose in the body frame.
    Mat3 R_BS = Mat3::Identity();
    Vec3 p_BS = Vec3::Zero(); // m
    // Current pose in the world.
    Mat3 R_WS = Mat3::Identity();
    Vec3 p_WS = Vec3::Zero(); // m

    const ConvexHull& hull() const { return geometry->hull; }
    const std::vector<Vec3>& meshVertices() const { return geometry->meshVertices; }
};

// Index of the hull corner of `s` (a convexHull mesh) furthest along u_S (shape frame): the hill
// climb over its edges ends at the maximum, as a convex polytope's edge graph has no other peak.
int hullExtremeCorner(const ShapeInstance& s, const Vec3& u_S);
int hullExtremeCorner(const ShapeGeometry& s, const Vec3& u_S);

// Corner k (0..7, bit i set = +x_i side) of a box with the given half extents, shape frame (m).
inline Vec3 boxCorner(const Vec3& half, int k)
{
    return Vec3((k & 1) ? half.x() : -half.x(), (k & 2) ? half.y() : -half.y(),
                (k & 4) ? half.z() : -half.z());
}

// Unit directions (cos, sin) of the points sampled on each cylinder rim.
inline constexpr int cRimSamples = 8;
const std::array<std::array<double, 2>, cRimSamples>& rimDirections();

// Builds the instance (everything but the world pose) from a model shape of a given body. A
// mesh becomes its convex hull when meshAsHull and it has one, of at most maxHullCorners corners
// when that is positive (capConvexHull), of all of them when it is 0. `shared`, when given, is the
// geometry of an instance of an equal shape (same type and sizes): the instance shares it
// instead of building its own. A mesh ignores it (its geometry is its own).
ShapeInstance makeShapeInstance(const core::Shape& shape, int body, bool meshAsHull,
                                std::shared_ptr<const ShapeGeometry> shared = nullptr,
                                int maxHullCorners = 0);

// World pose from the body pose: R_WS = R_WB R_BS, p_WS = p_WB + R_WB p_BS.
void setBodyPose(ShapeInstance& s, const Mat3& R_WB, const Vec3& p_WB);

// --- plane_manifold.cpp ---------------------------------------------------------------------
// Appends the contacts of shape s against the solid half-space n . x <= offset (n unit, world)
// whose separation is below margin (m). Normals are -n (from the shape towards the plane).
// Box: vertices; Sphere: one point; Capsule: both end spheres; Cylinder: rim points; Mesh:
// vertices. The caller merges and reduces them (mergeAndReduce).
void planeContacts(const ShapeInstance& s, const Vec3& n, double offset, double margin,
                   std::vector<RawContact>& out);

// --- feature_manifold.cpp -------------------------------------------------------------------
// Signed distance (m, < 0 inside) from a world point to a Box, Sphere, Capsule, Cylinder or
// convex-hull instance, and the unit outward direction grad_W of that distance at the point.
// A hull's distance outside costs O(faces x corners); at or above exactBelow (m) its cheap lower
// bound (the largest face-plane distance) is returned instead.
double signedDistance(const ShapeInstance& s, const Vec3& p_W, Vec3& grad_W,
                      double exactBelow = std::numeric_limits<double>::infinity());

// True for the pairs whose FCL result gets the feature points added: a capsule or a cylinder
// against a box, capsule or cylinder (FCL gives one point), and a mesh against a shape with a
// distance function (box, sphere, capsule, cylinder, hull): GJK/EPA gives a hull one point,
// and a triangle mesh gets per-triangle points, not the mesh's corners.
bool usesFeatureManifold(const ShapeInstance& a, const ShapeInstance& b);

// Appends the feature contacts of a against b and of b against a (normals from a towards b):
// box vertices, capsule end spheres, cylinder rim points and mesh vertices of one shape, plus the ends of the
// capsule axis (or of a lying cylinder's contact line) clipped to the other shape's contact
// face, each tested against the exact signed distance of the other shape and kept while the
// separation is below margin (m). reference, when not null, is FCL's deepest contact: it
// orients the features and, where a point sits on an edge of the other shape (where its
// distance gradient is ambiguous), gives that point's normal and its depth below the plane
// of the reference contact.
void featureContacts(const ShapeInstance& a, const ShapeInstance& b, const RawContact* reference,
                     double margin, std::vector<RawContact>& out);

// --- polytope_manifold.cpp -----------------------------------------------------------------
// The narrowphase table (narrowphase.cpp) sends here a hull against a hull or a box, and a box
// or a hull against each triangle of a triangle mesh (box-box keeps FCL's own manifold).

// Appends the contacts of two polytopes whose separation is below margin (m), normals from a
// towards b: one face clipped against the other along the best of the reference normal and
// the two faces it picks, or the reference contact itself for an edge against an edge.
// reference: FCL's deepest contact, or the nearest points of a gap below the margin.
void polytopeContacts(const ShapeInstance& a, const ShapeInstance& b, const RawContact& reference,
                      double margin, std::vector<RawContact>& out);

// Makes `out` the triangle t0 t1 t2 (world, counter-clockwise seen from the side it faces) as
// a flat polytope in the world frame: two faces, front and back, written into `geometry`, the
// geometry out points to (its storage is reused). False for a degenerate triangle.
bool setTrianglePolytope(const Vec3& t0_W, const Vec3& t1_W, const Vec3& t2_W, ShapeGeometry& geometry,
                         ShapeInstance& out);

// --- separation.cpp -------------------------------------------------------------------------
// True when a and b are proven farther apart than margin (m) along some axis: the centre line,
// a box's face normals, a capsule's or cylinder's axis. A convex hull's extent along an axis
// is exact (its corners); a triangle mesh counts as its bounding sphere. axis, when given,
// receives the unit world axis that proved it, separation the separation along it (m, > margin:
// a lower bound of the distance).
bool separatedBeyond(const ShapeInstance& a, const ShapeInstance& b, double margin, Vec3* axis = nullptr,
                     double* separation = nullptr);

// True when a and b are proven farther apart than margin (m) along the unit world axis u (the
// same test as separatedBeyond's for one axis); separation as there.
bool separatedAlongAxis(const ShapeInstance& a, const ShapeInstance& b, const Vec3& u, double margin,
                        double* separation = nullptr);

// --- swept_spheres.cpp ----------------------------------------------------------------------
// Spheres and capsules (sphere-swept segments) against each other in closed form (the
// narrowphase table's sweptSpherePair).

// The contact of two spheres or capsules when their separation is below margin (m): on the line
// joining the closest points of their segments, normal from a towards b, depth = the radii less
// the segments' distance (< 0 a gap). False when they are farther apart.
// separation, when given, receives the segments' distance less the radii (m) either way.
bool sweptSphereContact(const ShapeInstance& a, const ShapeInstance& b, double margin, RawContact& out,
                        double* separation = nullptr);

// --- manifold.cpp ---------------------------------------------------------------------------
// Cleans the contacts out[begin, end) of one shape pair in place and shrinks the vector: drops
// non-finite ones, keeps the deepest of those closer than mergeDistance (m), and reduces the
// rest to at most maxPoints (deepest, then the ones spanning the largest area). Deterministic.
void mergeAndReduce(std::vector<RawContact>& out, std::size_t begin, double mergeDistance,
                    std::size_t maxPoints = 4);

// --- filter.cpp -----------------------------------------------------------------------------
// The pair rule is public (collision/filter.h).
using collision::PairFilter;

} // namespace frontier::collision::detail
