// collision/narrowphase.cpp: the narrowphase of one shape pair. The early-outs every pair shares
// come first (proven apart on the bodies' travel since, or along an axis); then the pair function
// that the table below selects by the collision kinds of the two shapes (detail::CollisionKind).
// The table is the one place that says which function handles which pair of kinds; each family of
// pairs has its function in narrowphase_pairs.cpp. A new shape kind adds a row and a column here
// (tests/collision/narrowphase_table_test.cpp fails while one is missing).
#include "collision/detector.h"

#include <array>
#include <initializer_list>

namespace frontier::collision
{

namespace
{

using detail::CollisionKind;
using detail::ShapeInstance;
using detail::Vec3;

// Rounding allowance (m) of the travel bound: the pair must be proven farther apart than the
// margin by this much more before a pair is skipped on its bodies' travel alone.
constexpr double cTravelSlack = 1e-9;

} // namespace

// One entry of the table: the pair function, whether the separating-axis early-outs run before
// it (the closed-form sphere and capsule pairs are cheaper than those tests), and its name.
struct ContactDetector::Impl::PairEntry
{
    PairFunction run = nullptr;
    bool axisTests = true;
    const char* name = nullptr;
};

namespace
{

using Impl = ContactDetector::Impl;
using Table = std::array<std::array<Impl::PairEntry, detail::cCollisionKinds>, detail::cCollisionKinds>;

// Every kind of `as` against every kind of `bs`, in either order.
constexpr void add(Table& table, std::initializer_list<CollisionKind> as,
                   std::initializer_list<CollisionKind> bs, Impl::PairEntry entry)
{
    for (const CollisionKind a : as)
        for (const CollisionKind b : bs)
        {
            table[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = entry;
            table[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = entry;
        }
}

constexpr Table makeTable()
{
    using enum CollisionKind;
    Table t{};
    add(t, {Sphere, Capsule}, {Sphere, Capsule}, {&Impl::sweptSpherePair, false, "sweptSpherePair"});
    add(t, {Hull}, {Hull, Box}, {&Impl::polytopePair, true, "polytopePair"});
    add(t, {Box}, {Box}, {&Impl::boxBoxPair, true, "boxBoxPair"});
    add(t, {Sphere, Capsule}, {Box, Cylinder, Hull}, {&Impl::convexPair, true, "convexPair"});
    add(t, {Box, Cylinder, Hull}, {Cylinder}, {&Impl::convexPair, true, "convexPair"});
    add(t, {Triangles}, {Box, Hull}, {&Impl::trianglePolytopePair, true, "trianglePolytopePair"});
    add(t, {Triangles}, {Sphere, Capsule, Cylinder, Triangles},
        {&Impl::triangleShapePair, true, "triangleShapePair"});
    return t;
}

constexpr Table cPairTable = makeTable();

const Impl::PairEntry& entryOf(CollisionKind a, CollisionKind b)
{
    return cPairTable[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
}

} // namespace

void ContactDetector::Impl::narrowphase(int i, int j, PairState& pair, std::vector<Contact>& out)
{
    const ShapeInstance& a = shapes[static_cast<std::size_t>(i)];
    const ShapeInstance& b = shapes[static_cast<std::size_t>(j)];
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
    const PairEntry& entry = entryOf(a.kind, b.kind);
    if (entry.axisTests && separatedOnAxes(a, b, pair))
        return;
    (this->*entry.run)(i, j, pair, out);
}

// Apart beyond the margin along the axis that proved it last time, or along one of
// separatedBeyond's: no contact within the margin, nothing for FCL to do. Else the pair's axis
// is cleared (the pair function sets it when it finds the pair apart beyond the margin).
bool ContactDetector::Impl::separatedOnAxes(const ShapeInstance& a, const ShapeInstance& b, PairState& pair)
{
    double separation = 0.0;
    if (pair.axis_S != Vec3::Zero() &&
        detail::separatedAlongAxis(a, b, a.R_WS * pair.axis_S, margin, &separation))
    {
        provenApart(pair, separation);
        ++stats.separatedPairs;
        return true;
    }
    Vec3 axis_W = Vec3::Zero();
    if (detail::separatedBeyond(a, b, margin, &axis_W, &separation))
    {
        pair.axis_S = a.R_WS.transpose() * axis_W;
        provenApart(pair, separation);
        ++stats.separatedPairs;
        return true;
    }
    pair.axis_S.setZero();
    return false;
}

// Pair is farther apart than distanceAtLeast (m, > margin) at the bodies' present travel.
void ContactDetector::Impl::provenApart(PairState& pair, double distanceAtLeast) const
{
    pair.apart = distanceAtLeast;
    pair.travelA = bodyTravel[static_cast<std::size_t>(shapes[static_cast<std::size_t>(pair.i)].body)];
    pair.travelB = bodyTravel[static_cast<std::size_t>(shapes[static_cast<std::size_t>(pair.j)].body)];
}

namespace detail
{

const char* narrowphaseName(CollisionKind a, CollisionKind b)
{
    return entryOf(a, b).name;
}

} // namespace detail

} // namespace frontier::collision
