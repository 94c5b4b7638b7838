// collision/feature_manifold.cpp: extra contact points for the pairs where FCL (libccd GJK/EPA)
// returns a single point although the shapes can touch along a line or a patch: a capsule or a
// cylinder against a box, a capsule or a cylinder. The features of one shape (box
// vertices, capsule end spheres, cylinder rim points) are tested against the exact signed
// distance of the other, which is cheap and closed-form for these four primitives. A capsule
// lying on a box gets both end spheres, a cylinder standing on a box its rim, a box on a
// cylinder's cap its corners: a full manifold in one step, with no state kept between steps.
// A capsule (or a lying cylinder) across a narrower box is held along a line that its end
// points do not reach, so the capsule axis is also clipped to the box's contact face (or a
// cylinder's cap, or the other's axial extent) and the two ends of the clipped part tested.
// A mesh that collides as its convex hull has an exact signed distance too (the largest
// face-plane distance inside, the nearest face polygon outside), and its corners are features,
// so a sphere, capsule or cylinder on a hull gets its patch the same way. (A hull against a
// hull or a box is two polytopes: polytope_manifold.cpp clips their faces instead.)
#include "collision/internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace frontier::collision::detail
{

namespace
{

bool isRound(core::ShapeType t)
{
    return t == core::ShapeType::Capsule || t == core::ShapeType::Cylinder;
}

bool hasFeatures(core::ShapeType t)
{
    return isRound(t) || t == core::ShapeType::Box;
}

bool hasDistance(const ShapeInstance& s)
{
    return hasFeatures(s.type) || s.type == core::ShapeType::Sphere || s.convexHull;
}

double sign(double x)
{
    return x >= 0.0 ? 1.0 : -1.0;
}

// The corners of face k of a hull, counter-clockwise seen from outside: calls f(a, b) for each
// edge from a to b.
template <class F> void forEachFaceEdge(const ConvexHull& h, std::size_t k, F&& f)
{
    const auto start = static_cast<std::size_t>(h.faceStart[k]);
    const auto n = static_cast<std::size_t>(h.faces[start]);
    for (std::size_t i = 0; i < n; ++i)
    {
        const auto a = static_cast<std::size_t>(h.faces[start + 1 + i]);
        const auto b = static_cast<std::size_t>(h.faces[start + 1 + (i + 1) % n]);
        f(h.vertices[a], h.vertices[b]);
    }
}

// Signed distance in the shape frame; grad is the unit outward direction there. exactBelow: see
// hullSignedDistance (the other shapes are always exact).
double localDistance(const ShapeInstance& s, const Vec3& p, double exactBelow, Vec3& grad)
{
    switch (s.type)
    {
    case core::ShapeType::Box:
    {
        const Vec3 q = p.cwiseAbs() - s.halfExtents;
        int k = 0;
        const double inside = q.maxCoeff(&k);
        if (inside > 0.0)
        {
            const Vec3 outside = q.cwiseMax(0.0);
            const double d = outside.norm();
            grad = Vec3(sign(p.x()) * outside.x(), sign(p.y()) * outside.y(), sign(p.z()) * outside.z()) / d;
            return d;
        }
        grad = Vec3::Zero();
        grad[k] = sign(p[k]);
        return inside;
    }
    case core::ShapeType::Sphere:
    {
        const double r = p.norm();
        grad = r > 0.0 ? Vec3(p / r) : Vec3(Vec3::UnitZ());
        return r - s.radius;
    }
    case core::ShapeType::Capsule:
    {
        const Vec3 v(p.x(), p.y(), p.z() - std::clamp(p.z(), -s.halfLength, s.halfLength));
        const double r = v.norm();
        grad = r > 0.0 ? Vec3(v / r) : Vec3(Vec3::UnitX());
        return r - s.radius;
    }
    case core::ShapeType::Cylinder:
    {
        const double rho = std::hypot(p.x(), p.y());
        const Vec3 radial = rho > 0.0 ? Vec3(p.x() / rho, p.y() / rho, 0.0) : Vec3(Vec3::UnitX());
        const double qx = rho - s.radius;
        const double qz = std::abs(p.z()) - s.halfLength;
        const Vec3 axial(0.0, 0.0, sign(p.z()));
        if (qx > 0.0 && qz > 0.0)
        {
            const double d = std::hypot(qx, qz);
            grad = (qx * radial + qz * axial) / d;
            return d;
        }
        grad = qx > qz ? radial : axial;
        return std::max(qx, qz);
    }
    case core::ShapeType::Mesh:
        if (s.convexHull)
            return hullSignedDistance(s.hull(), p, grad, exactBelow);
        break;
    case core::ShapeType::Plane:
        break;
    }
    grad = Vec3::UnitZ();
    return 1e300; // not supported (triangle meshes): never in contact
}

// Calls f(centre_W, radius) for each point feature of s: box vertices (radius 0), capsule end
// spheres (radius r), cylinder rim samples and the rim points farthest along `toward` (radius 0),
// mesh vertices (radius 0), the sphere itself (radius r).
template <class F> void forEachPointFeature(const ShapeInstance& s, const Vec3& toward_W, F&& f)
{
    const Mat3& R = s.R_WS;
    const Vec3& p = s.p_WS;
    switch (s.type)
    {
    case core::ShapeType::Box:
        for (int k = 0; k < 8; ++k)
            f(Vec3(p + R * boxCorner(s.halfExtents, k)), 0.0);
        break;
    case core::ShapeType::Capsule:
        f(Vec3(p + s.halfLength * R.col(2)), s.radius);
        f(Vec3(p - s.halfLength * R.col(2)), s.radius);
        break;
    case core::ShapeType::Cylinder:
    {
        const Vec3 axisUnit = R.col(2);
        const Vec3 out = toward_W - toward_W.dot(axisUnit) * axisUnit;
        const double outNorm = out.norm();
        for (const double side : {1.0, -1.0})
        {
            const Vec3 centre = p + side * s.halfLength * axisUnit;
            if (outNorm > 1e-9)
                f(Vec3(centre + (s.radius / outNorm) * out), 0.0);
            for (const auto& [c, sn] : rimDirections())
                f(Vec3(centre + s.radius * (c * R.col(0) + sn * R.col(1))), 0.0);
        }
        break;
    }
    case core::ShapeType::Mesh:
        for (const Vec3& vertex : s.meshVertices())
            f(Vec3(p + R * vertex), 0.0);
        break;
    case core::ShapeType::Sphere:
        f(p, s.radius); // against a mesh: exact against a hull, where libccd's point is approximate
        break;
    case core::ShapeType::Plane:
        break;
    }
}

// The support function of s: max over x in s of d . x (m), d unit, world.
double supportHeight(const ShapeInstance& s, const Vec3& d_W)
{
    const Vec3 d = s.R_WS.transpose() * d_W;
    double h = d_W.dot(s.p_WS);
    switch (s.type)
    {
    case core::ShapeType::Box:
        return h + d.cwiseAbs().dot(s.halfExtents);
    case core::ShapeType::Sphere:
        return h + s.radius;
    case core::ShapeType::Capsule:
        return h + s.halfLength * std::abs(d.z()) + s.radius;
    case core::ShapeType::Cylinder:
        return h + s.halfLength * std::abs(d.z()) + s.radius * std::hypot(d.x(), d.y());
    case core::ShapeType::Mesh:
    {
        double best = s.meshVertices().empty() ? 0.0 : -1e300;
        for (const Vec3& v : s.meshVertices())
            best = std::max(best, d.dot(v));
        return h + best;
    }
    case core::ShapeType::Plane:
        break;
    }
    return h;
}

// The line along which s can touch something in direction `toward`: a capsule's axis (radius r)
// or a lying cylinder's side line (radius 0). False for other shapes and upright cylinders.
bool lineFeature(const ShapeInstance& s, const Vec3& toward_W, Vec3& p0, Vec3& p1, double& radius)
{
    const Vec3 axis = s.R_WS.col(2);
    if (s.type == core::ShapeType::Capsule)
    {
        p0 = s.p_WS - s.halfLength * axis;
        p1 = s.p_WS + s.halfLength * axis;
        radius = s.radius;
        return true;
    }
    if (s.type == core::ShapeType::Cylinder)
    {
        const Vec3 out = toward_W - toward_W.dot(axis) * axis;
        const double outNorm = out.norm();
        if (outNorm < 0.9) // more than ~25 degrees from lying on its side: the rims hold it
            return false;
        const Vec3 side = s.p_WS + (s.radius / outNorm) * out;
        p0 = side - s.halfLength * axis;
        p1 = side + s.halfLength * axis;
        radius = 0.0;
        return true;
    }
    return false;
}

// Narrows [t0, t1] to where lo <= a + b t <= hi. False when empty.
bool clipLinear(double a, double b, double lo, double hi, double& t0, double& t1)
{
    if (std::abs(b) < 1e-12)
        return a >= lo && a <= hi;
    double ta = (lo - a) / b;
    double tb = (hi - a) / b;
    if (ta > tb)
        std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    return t0 <= t1;
}

// Narrows [t0, t1] of the segment p0 + t (p1 - p0) to the part facing the contact face of
// `other` (normal_W: the contact normal, either sign): a box's face rectangle, a cylinder's cap
// disk or axial extent, a capsule's axial extent. False when nothing is left.
bool clipToContactRegion(const ShapeInstance& other, const Vec3& normal_W, const Vec3& p0_W, const Vec3& p1_W,
                         double& t0, double& t1)
{
    const Mat3 RT = other.R_WS.transpose();
    const Vec3 a = RT * (p0_W - other.p_WS);
    const Vec3 b = RT * (p1_W - p0_W);
    const Vec3 n = RT * normal_W;
    switch (other.type)
    {
    case core::ShapeType::Box:
    {
        int face = 0;
        n.cwiseAbs().maxCoeff(&face);
        for (int i = 0; i < 3; ++i)
            if (i != face && !clipLinear(a[i], b[i], -other.halfExtents[i], other.halfExtents[i], t0, t1))
                return false;
        return true;
    }
    case core::ShapeType::Capsule:
        return clipLinear(a.z(), b.z(), -other.halfLength, other.halfLength, t0, t1);
    case core::ShapeType::Cylinder:
    {
        if (std::abs(n.z()) < 0.7) // against the side
            return clipLinear(a.z(), b.z(), -other.halfLength, other.halfLength, t0, t1);
        // Against a cap: |a_xy + t b_xy| <= r.
        const double qa = b.x() * b.x() + b.y() * b.y();
        const double qb = a.x() * b.x() + a.y() * b.y();
        const double qc = a.x() * a.x() + a.y() * a.y() - other.radius * other.radius;
        if (qa < 1e-24)
            return qc <= 0.0;
        const double disc = qb * qb - qa * qc;
        if (disc < 0.0)
            return false;
        const double root = std::sqrt(disc);
        t0 = std::max(t0, (-qb - root) / qa);
        t1 = std::min(t1, (-qb + root) / qa);
        return t0 <= t1;
    }
    case core::ShapeType::Mesh:
    {
        if (!other.convexHull)
            break;
        // The hull's face turned most towards the segment (its outward normal closest to -n),
        // then the prism over that face polygon: inside each edge's side plane.
        const ConvexHull& h = other.hull();
        std::size_t face = 0;
        for (std::size_t k = 1; k < h.normals.size(); ++k)
            if (-n.dot(h.normals[k]) > -n.dot(h.normals[face]))
                face = k;
        bool kept = true;
        forEachFaceEdge(h, face,
                        [&](const Vec3& q0, const Vec3& q1)
                        {
                            const Vec3 inward = h.normals[face].cross(q1 - q0);
                            kept = kept && clipLinear(inward.dot(a - q0), inward.dot(b), 0.0,
                                                      std::numeric_limits<double>::infinity(), t0, t1);
                        });
        return kept;
    }
    case core::ShapeType::Sphere:
    case core::ShapeType::Plane:
        break;
    }
    return false;
}

// Tests features of one shape against the other shape of the pair and appends the contacts.
struct FeatureTester
{
    const ShapeInstance& other;  // the shape the features are tested against
    bool otherIsB;               // the features belong to a (true) or to b (false)
    const RawContact* reference; // FCL's deepest contact, normal a -> b, or null
    double margin;
    std::vector<RawContact>& out;

    // The unit direction from the feature's shape towards the other one.
    Vec3 towardOther(const ShapeInstance& self) const
    {
        if (reference)
            return otherIsB ? reference->normal_W : Vec3(-reference->normal_W);
        if (!hasDistance(other)) // a triangle mesh: centre to centre
            return (other.p_WS - self.p_WS).normalized();
        Vec3 grad;
        signedDistance(other, self.p_WS, grad);
        return -grad;
    }

    void test(const Vec3& centre, double radius) const
    {
        Vec3 grad;
        const double separation = signedDistance(other, centre, grad, margin + radius) - radius;
        if (!(separation < margin))
            return;
        if (reference)
        {
            const Vec3 m = otherIsB ? reference->normal_W : Vec3(-reference->normal_W);
            if (grad.dot(m) > -0.866)
            {
                // On an edge of the other shape (its distance gradient is more than 30 degrees
                // off the contact normal): use the normal of the pair and the depth below the
                // other shape's supporting plane facing us.
                const Vec3 deepest = centre + radius * m;
                const double depth = std::min(supportHeight(other, -m) + m.dot(deepest), reference->depth);
                if (depth > -margin)
                    out.push_back({deepest - 0.5 * depth * m, reference->normal_W, depth});
                return;
            }
        }
        const Vec3 deepest = centre - radius * grad; // the feature's point deepest into `other`
        out.push_back({deepest - 0.5 * separation * grad, otherIsB ? Vec3(-grad) : grad, -separation});
    }

    void run(const ShapeInstance& self) const
    {
        const Vec3 toward = towardOther(self);
        // A hull's distance costs O(faces) per feature, so features farther than the margin
        // beyond its supporting plane across `toward` (a lower bound of their distance) are
        // skipped first. (The closed-form distances of the primitives are cheaper than this.)
        const double nearest = other.convexHull ? -supportHeight(other, -toward) - margin
                                                : -std::numeric_limits<double>::infinity();
        forEachPointFeature(self, toward,
                            [&](const Vec3& centre, double radius)
                            {
                                if (toward.dot(centre) + radius > nearest)
                                    test(centre, radius);
                            });
        Vec3 p0, p1;
        double radius = 0.0;
        if (!lineFeature(self, toward, p0, p1, radius))
            return;
        double t0 = 0.0;
        double t1 = 1.0;
        if (!clipToContactRegion(other, toward, p0, p1, t0, t1))
            return;
        test(Vec3(p0 + t0 * (p1 - p0)), radius);
        if (t1 > t0)
            test(Vec3(p0 + t1 * (p1 - p0)), radius);
    }
};

} // namespace

double signedDistance(const ShapeInstance& s, const Vec3& p_W, Vec3& grad_W, double exactBelow)
{
    Vec3 grad;
    const double d = localDistance(s, s.R_WS.transpose() * (p_W - s.p_WS), exactBelow, grad);
    grad_W = s.R_WS * grad;
    return d;
}

bool usesFeatureManifold(const ShapeInstance& a, const ShapeInstance& b)
{
    if (a.type == core::ShapeType::Mesh || b.type == core::ShapeType::Mesh)
        return hasDistance(a) || hasDistance(b);
    return (isRound(a.type) || isRound(b.type)) && hasFeatures(a.type) && hasFeatures(b.type);
}

void featureContacts(const ShapeInstance& a, const ShapeInstance& b, const RawContact* reference,
                     double margin, std::vector<RawContact>& out)
{
    FeatureTester{b, true, reference, margin, out}.run(a);
    FeatureTester{a, false, reference, margin, out}.run(b);
}

} // namespace frontier::collision::detail
