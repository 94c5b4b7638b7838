// collision/manifold.cpp: merge near-duplicate contacts of one shape pair and keep at most four.
// Four well-spread points hold any flat contact patch; more only make the contact rows of the
// solver redundant (and the dense solvers ill-conditioned).
#include "collision/internal.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace frontier::collision::detail
{

namespace
{

bool finite(const RawContact& c)
{
    return c.point_W.allFinite() && c.normal_W.allFinite() && std::isfinite(c.depth);
}

// Deepest first; ties broken by the point so that the order never depends on the input order.
bool deeper(const RawContact& a, const RawContact& b)
{
    if (a.depth != b.depth)
        return a.depth > b.depth;
    return std::lexicographical_compare(a.point_W.data(), a.point_W.data() + 3, b.point_W.data(),
                                        b.point_W.data() + 3);
}

double triangleArea2(const Vec3& a, const Vec3& b, const Vec3& c)
{
    return (b - a).cross(c - a).norm(); // twice the area (m^2)
}

// Drops the non-finite contacts from begin on.
void dropNonFinite(std::vector<RawContact>& out, std::size_t begin)
{
    const auto first = out.begin() + static_cast<std::ptrdiff_t>(begin);
    out.erase(std::remove_if(first, out.end(), [](const RawContact& c) { return !finite(c); }), out.end());
}

// Greedy merge: a contact closer than sqrt(merge2) (m) to a deeper kept one is dropped.
void mergeNear(std::vector<RawContact>& out, std::size_t begin, double merge2)
{
    std::size_t kept = begin;
    for (std::size_t i = begin; i < out.size(); ++i)
    {
        bool near = false;
        for (std::size_t j = begin; j < kept && !near; ++j)
            near = (out[i].point_W - out[j].point_W).squaredNorm() < merge2;
        if (!near)
            out[kept++] = out[i];
    }
    out.resize(kept);
}

// The contact from begin on with the largest score of its point, and that score.
template <class Score>
std::pair<std::size_t, double> argmax(const std::vector<RawContact>& out, std::size_t begin, Score score)
{
    std::size_t best = begin;
    double bestScore = -1.0;
    for (std::size_t i = begin; i < out.size(); ++i)
    {
        const double value = score(out[i].point_W);
        if (value > bestScore)
        {
            bestScore = value;
            best = i;
        }
    }
    return std::pair{best, bestScore};
}

struct Selection
{
    std::array<std::size_t, 4> index; // into out
    std::size_t count;
};

// The deepest (out[begin]), the farthest from it, the one spanning the largest triangle with
// them, and the one adding the most area to that triangle: at most maxPoints (1 to 4) of them.
Selection selectSpread(const std::vector<RawContact>& out, std::size_t begin, double merge2,
                       std::size_t maxPoints)
{
    auto point = [&](std::size_t i) -> const Vec3& { return out[i].point_W; };
    Selection s{{begin, begin, begin, begin}, 1};
    const Vec3 p0 = point(s.index[0]);
    if (maxPoints >= 2)
        s.index[s.count++] = argmax(out, begin, [&](const Vec3& q) { return (q - p0).squaredNorm(); }).first;
    if (maxPoints >= 3)
    {
        const Vec3 p1 = point(s.index[1]);
        const double span2 = (p1 - p0).squaredNorm();
        const auto [i2, area] = argmax(out, begin, [&](const Vec3& q) { return triangleArea2(p0, p1, q); });
        if (area > 1e-6 * span2)
            s.index[s.count++] = i2;
        else
        {
            // Collinear: keep both ends of the line (and the deepest point, already in).
            const auto [end2, dist2] =
                argmax(out, begin, [&](const Vec3& q) { return (q - p1).squaredNorm(); });
            if ((point(end2) - p0).squaredNorm() > merge2 && (p1 - p0).squaredNorm() < dist2)
                s.index[s.count++] = end2;
        }
    }
    if (maxPoints >= 4 && s.count == 3)
    {
        const Vec3 p1 = point(s.index[1]);
        const Vec3 p2 = point(s.index[2]);
        const double area = triangleArea2(p0, p1, p2);
        const auto [i3, total] =
            argmax(out, begin,
                   [&](const Vec3& q) {
                       return triangleArea2(p0, p1, q) + triangleArea2(p1, p2, q) + triangleArea2(p2, p0, q);
                   });
        if (total > area * (1.0 + 1e-6))
            s.index[s.count++] = i3;
    }
    return s;
}

} // namespace

void mergeAndReduce(std::vector<RawContact>& out, std::size_t begin, double mergeDistance,
                    std::size_t maxPoints)
{
    dropNonFinite(out, begin);
    if (out.size() <= begin + 1)
        return; // one contact or none: nothing to merge or reduce
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(begin), out.end(), deeper);
    const double merge2 = mergeDistance * mergeDistance;
    mergeNear(out, begin, merge2);
    maxPoints = std::clamp<std::size_t>(maxPoints, 1, 4);
    if (out.size() - begin <= maxPoints)
        return;

    const Selection s = selectSpread(out, begin, merge2, maxPoints);
    std::array<RawContact, 4> chosen;
    for (std::size_t k = 0; k < s.count; ++k)
        chosen[k] = out[s.index[k]];
    for (std::size_t k = 0; k < s.count; ++k)
        out[begin + k] = chosen[k];
    out.resize(begin + s.count);
}

} // namespace frontier::collision::detail
