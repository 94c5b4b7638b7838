// tests/collision/shortcuts_test.cpp: the detector's shortcuts past FCL, checked against FCL.
// Sphere and capsule pairs, solved in closed form (collision/swept_spheres.cpp), for random
// poses against two oracles: the distance
// between the two axis segments by golden-section search (the distance from a point of one
// segment to the other is convex along it), and FCL itself (fcl::collide says whether they
// overlap; libccd's MPR depth is never below the true one; fcl::distance gives the gap).
#include "test_models.h"

#include <algorithm>
#include <cstdio>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>
#include <memory>
#include <random>

namespace frontier::collision::test
{
namespace
{

std::shared_ptr<fcl::CollisionGeometryd> fclShape(const core::Shape& s)
{
    switch (s.type)
    {
    case core::ShapeType::Sphere:
        return std::make_shared<fcl::Sphered>(s.radius);
    case core::ShapeType::Box:
        return std::make_shared<fcl::Boxd>(s.size.x(), s.size.y(), s.size.z());
    case core::ShapeType::Cylinder:
        return std::make_shared<fcl::Cylinderd>(s.radius, s.length);
    default:
        return std::make_shared<fcl::Capsuled>(s.radius, s.length);
    }
}

fcl::Transform3d pose(const Vec3& p, const Quat& q)
{
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = q.toRotationMatrix();
    tf.translation() = p;
    return tf;
}

struct Axis
{
    Vec3 start, end;
};

Axis axisOf(const core::Shape& shape, const Vec3& p, const Quat& q)
{
    const Vec3 half = shape.type == core::ShapeType::Capsule ? Vec3(0.5 * shape.length * (q * Vec3::UnitZ()))
                                                             : Vec3::Zero();
    return {p - half, p + half};
}

// Distance (m) from x to the segment, by projection.
double pointToSegment(const Vec3& x, const Axis& s)
{
    const Vec3 d = s.end - s.start;
    const double t =
        d.squaredNorm() > 0.0 ? std::clamp((x - s.start).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (s.start + t * d - x).norm();
}

// Distance between two segments: golden-section search over the first one's parameter.
double segmentDistance(const Axis& one, const Axis& two)
{
    auto f = [&](double s) { return pointToSegment(one.start + s * (one.end - one.start), two); };
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 200 && hi - lo > 1e-15; ++k)
    {
        const double x1 = hi - g * (hi - lo);
        const double x2 = lo + g * (hi - lo);
        if (f(x1) <= f(x2))
            hi = x2;
        else
            lo = x1;
    }
    return std::min({f(0.5 * (lo + hi)), f(0.0), f(1.0)});
}

// Random draws one per statement, in the order g++ took them when these tests were written: the
// order in which a compiler evaluates the arguments of one call is unspecified (g++ goes right to
// left, clang left to right), and the tests' inputs must not depend on it.
template <class Draw> Quat drawQuat(Draw&& draw)
{
    const double z = draw(), y = draw(), x = draw(), w = draw();
    return Quat(w, x, y, z).normalized();
}

template <class Draw> Vec3 drawVec(Draw&& draw)
{
    const double z = draw(), y = draw(), x = draw();
    return Vec3(x, y, z);
}

template <class Radius, class Length> core::Shape drawCapsule(Radius&& radius, Length&& length)
{
    const double l = length();
    return capsule(radius(), l);
}

} // namespace

TEST(SweptSpheres, DepthsAndGapsMatchTheSegmentDistanceAndFcl)
{
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> radius(0.03, 0.08);
    std::uniform_real_distribution<double> length(0.1, 0.5);
    constexpr double cMargin = 0.01; // m
    int overlaps = 0, gaps = 0, apart = 0;
    double worstExact = 0.0, worstGapFcl = 0.0;
    for (int trial = 0; trial < 400; ++trial)
    {
        auto r = [&] { return radius(rng); };
        auto l = [&] { return length(rng); };
        auto u = [&] { return unit(rng); };
        const core::Shape a = trial % 4 == 0 ? sphere(r()) : drawCapsule(r, l);
        const core::Shape b = trial % 3 == 0 ? sphere(r()) : drawCapsule(r, l);
        const Quat qa = drawQuat(u);
        const Quat qb = drawQuat(u);
        const Vec3 pb = 0.25 * drawVec(u);
        const double expected =
            a.radius + b.radius - segmentDistance(axisOf(a, Vec3::Zero(), qa), axisOf(b, pb, qb)); // m

        core::Model model;
        model.bodies.push_back(moving("a", a, Vec3::Zero(), qa));
        model.bodies.push_back(moving("b", b, pb, qb));
        const std::vector<Contact> contacts = detectAll(model, cMargin);
        fcl::CollisionObjectd oa(fclShape(a), pose(Vec3::Zero(), qa));
        fcl::CollisionObjectd ob(fclShape(b), pose(pb, qb));
        fcl::CollisionRequestd request(1, true);
        fcl::CollisionResultd result;
        fcl::collide(&oa, &ob, request, result);

        if (expected <= -cMargin)
        {
            ++apart;
            EXPECT_TRUE(contacts.empty()) << "trial " << trial << ": apart by " << -expected << " m";
            EXPECT_FALSE(result.isCollision());
            continue;
        }
        ASSERT_FALSE(contacts.empty()) << "trial " << trial << ": depth " << expected << " m, no contact";
        double deepest = -1e9;
        for (const Contact& c : contacts)
        {
            deepest = std::max(deepest, c.depth);
            EXPECT_GT(c.normal_W.dot(pb), -1e-9); // from a towards b
        }
        // The closed-form point is exact; feature points (capsule end spheres) may stand in for
        // it when they come within a tenth of the margin of its depth.
        EXPECT_LE(deepest, expected + 1e-9) << "trial " << trial;
        EXPECT_GE(deepest, expected - 0.1 * cMargin - 1e-9) << "trial " << trial;
        if (a.type == core::ShapeType::Sphere || b.type == core::ShapeType::Sphere)
        {
            // No feature points with a sphere: the one closed-form point, exact.
            EXPECT_EQ(contacts.size(), 1u);
            worstExact = std::max(worstExact, std::abs(deepest - expected));
        }
        if (expected > 1e-9)
        {
            ++overlaps;
            ASSERT_TRUE(result.isCollision()) << "trial " << trial;
            EXPECT_GE(result.getContact(0).penetration_depth, expected - 1e-6) << "trial " << trial;
        }
        else if (expected < -1e-9)
        {
            ++gaps;
            EXPECT_FALSE(result.isCollision()) << "trial " << trial;
            fcl::DistanceRequestd distanceRequest(true);
            fcl::DistanceResultd distanceResult;
            const double gap = fcl::distance(&oa, &ob, distanceRequest, distanceResult);
            worstGapFcl = std::max(worstGapFcl, std::abs(gap + expected));
        }
    }
    std::printf("%d overlapping, %d near, %d apart: sphere pairs' depth vs segment distance %.2g m, "
                "gap oracle vs fcl::distance %.2g m\n",
                overlaps, gaps, apart, worstExact, worstGapFcl);
    EXPECT_GT(overlaps, 30);
    EXPECT_GT(gaps, 5);
    EXPECT_GT(apart, 30);
    EXPECT_LT(worstExact, 1e-9);
    EXPECT_LT(worstGapFcl, 1e-6); // the oracle agrees with FCL's GJK where both apply
}

// Pairs with a box or a cylinder that the detector proves apart along an axis (centre line, face
// normals, axes: collision/separation.cpp) skip FCL. Whatever the path, for random poses: no
// contact exactly when FCL's distance is at least the margin.
TEST(SeparatedPairs, NoContactExactlyWhenFclSaysApartBeyondTheMargin)
{
    std::mt19937 rng(2027);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> size(0.05, 0.3);
    constexpr double cMargin = 0.01; // m
    long skipped = 0;
    int apart = 0, near = 0;
    for (int trial = 0; trial < 600; ++trial)
    {
        auto shape = [&](int k)
        {
            switch (k % 4)
            {
            case 0:
            {
                const double z = size(rng), y = size(rng), x = size(rng); // one draw per statement
                return box(x, y, z);
            }
            case 1:
            {
                const double l = size(rng);
                return cylinder(0.5 * size(rng), l);
            }
            case 2:
            {
                const double l = size(rng);
                return capsule(0.3 * size(rng), l);
            }
            default:
                return sphere(0.5 * size(rng));
            }
        };
        const core::Shape a = shape(trial);
        const core::Shape b = shape(trial / 4 + (trial % 4 == 3 ? 0 : 1)); // not two spheres/capsules only
        auto u = [&] { return unit(rng); };
        const Quat qa = drawQuat(u);
        const Quat qb = drawQuat(u);
        const Vec3 pb = 0.35 * drawVec(u);
        core::Model model;
        model.bodies.push_back(moving("a", a, Vec3::Zero(), qa));
        model.bodies.push_back(moving("b", b, pb, qb));
        ContactDetector detector(model, cMargin);
        std::vector<Contact> contacts;
        detector.detect(core::initialState(model), contacts);
        skipped += detector.stats().separatedPairs;

        fcl::CollisionObjectd oa(fclShape(a), pose(Vec3::Zero(), qa));
        fcl::CollisionObjectd ob(fclShape(b), pose(pb, qb));
        fcl::DistanceRequestd request(true);
        fcl::DistanceResultd result;
        const double gap = fcl::distance(&oa, &ob, request, result); // m; -1 when overlapping
        if (gap >= cMargin + 1e-6)
        {
            ++apart;
            EXPECT_TRUE(contacts.empty()) << "trial " << trial << ": gap " << gap << " m";
        }
        else if (gap < cMargin - 1e-6)
        {
            ++near;
            EXPECT_FALSE(contacts.empty()) << "trial " << trial << ": gap " << gap << " m, no contact";
        }
    }
    std::printf("%d pairs apart beyond the margin (%ld skipped without FCL), %d near or overlapping\n", apart,
                skipped, near);
    EXPECT_GT(apart, 100);
    EXPECT_GT(near, 50);
    EXPECT_GT(skipped, 100); // the shortcut is taken (others are culled by the AABBs first)
}

} // namespace frontier::collision::test
