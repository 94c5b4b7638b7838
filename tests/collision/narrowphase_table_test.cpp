// tests/collision/narrowphase_table_test.cpp: the narrowphase table (collision/narrowphase.cpp) has
// a pair function for every pair of collision kinds, the same either way round and the one the
// narrowphase's rules name, and every model shape that is not a plane becomes an instance of a kind
// the table knows.
#include "collision/internal.h"

#include <gtest/gtest.h>
#include <set>
#include <string>

namespace frontier::collision::test
{

namespace
{

using detail::CollisionKind;

CollisionKind kindAt(int k)
{
    return static_cast<CollisionKind>(k);
}

TEST(NarrowphaseTable, EveryPairOfKindsHasAFunction)
{
    for (int a = 0; a < detail::cCollisionKinds; ++a)
        for (int b = 0; b < detail::cCollisionKinds; ++b)
        {
            const char* name = detail::narrowphaseName(kindAt(a), kindAt(b));
            ASSERT_NE(name, nullptr) << "no narrowphase for " << detail::collisionKindName(kindAt(a)) << " - "
                                     << detail::collisionKindName(kindAt(b));
            EXPECT_EQ(std::string(name), std::string(detail::narrowphaseName(kindAt(b), kindAt(a))));
        }
}

// Each pair goes where the narrowphase's rules send it, written here as the rules read: two swept
// spheres (sphere, capsule) in closed form; two polytopes by their faces (two boxes by the box-box
// clipping); triangles against a polytope by its faces, against anything else by FCL's triangles;
// every other pair by the convex-convex route.
std::string expectedPairFunction(CollisionKind a, CollisionKind b)
{
    const auto sweptSphere = [](CollisionKind k)
    { return k == CollisionKind::Sphere || k == CollisionKind::Capsule; };
    const auto polytope = [](CollisionKind k) { return k == CollisionKind::Box || k == CollisionKind::Hull; };
    if (sweptSphere(a) && sweptSphere(b))
        return "sweptSpherePair";
    if (a == CollisionKind::Triangles || b == CollisionKind::Triangles)
        return polytope(a == CollisionKind::Triangles ? b : a) ? "trianglePolytopePair" : "triangleShapePair";
    if (a == CollisionKind::Box && b == CollisionKind::Box)
        return "boxBoxPair";
    if (polytope(a) && polytope(b))
        return "polytopePair";
    return "convexPair";
}

TEST(NarrowphaseTable, EveryPairGoesWhereTheRulesSendIt)
{
    for (int a = 0; a < detail::cCollisionKinds; ++a)
        for (int b = 0; b < detail::cCollisionKinds; ++b)
        {
            const char* name = detail::narrowphaseName(kindAt(a), kindAt(b));
            ASSERT_NE(name, nullptr);
            EXPECT_EQ(std::string(name), expectedPairFunction(kindAt(a), kindAt(b)))
                << detail::collisionKindName(kindAt(a)) << " - " << detail::collisionKindName(kindAt(b));
        }
}

TEST(NarrowphaseTable, KindsHaveDistinctNames)
{
    std::set<std::string> names;
    for (int k = 0; k < detail::cCollisionKinds; ++k)
        names.insert(detail::collisionKindName(kindAt(k)));
    EXPECT_EQ(names.size(), static_cast<std::size_t>(detail::cCollisionKinds));
}

core::Shape tetrahedron()
{
    core::Shape mesh;
    mesh.type = core::ShapeType::Mesh;
    mesh.vertices = {core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 1, 0), core::Vec3(0, 0, 1)};
    mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return mesh;
}

TEST(NarrowphaseTable, ShapesBecomeTheirKinds)
{
    const std::pair<core::ShapeType, CollisionKind> primitives[] = {
        {core::ShapeType::Box, CollisionKind::Box},
        {core::ShapeType::Sphere, CollisionKind::Sphere},
        {core::ShapeType::Capsule, CollisionKind::Capsule},
        {core::ShapeType::Cylinder, CollisionKind::Cylinder},
    };
    for (const auto& [type, kind] : primitives)
    {
        core::Shape shape;
        shape.type = type;
        shape.size = core::Vec3(1, 2, 3);
        shape.radius = 0.5;
        shape.length = 1.0;
        EXPECT_EQ(detail::makeShapeInstance(shape, 0, true).kind, kind);
    }
    // A moving mesh collides as its hull, a static one (or one asked for triangles) as triangles.
    EXPECT_EQ(detail::makeShapeInstance(tetrahedron(), 0, true).kind, CollisionKind::Hull);
    EXPECT_EQ(detail::makeShapeInstance(tetrahedron(), 0, false).kind, CollisionKind::Triangles);
}

} // namespace

} // namespace frontier::collision::test
