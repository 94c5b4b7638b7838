// collision/convex_hull.cpp: the convex hull of a mesh's vertices, computed with qhull's
// reentrant library (libqhull_r) once per shape when the detector is built.
//
// Why hulls: a moving mesh collides as its convex hull (what MuJoCo does for every mesh geom and
// Bullet for dynamic meshes). Triangle soup against triangle soup (FCL's BVHModel) returns one
// contact per pair of touching triangles, each with that triangle's normal and an edge-crossing
// depth, so two moving links get normals that disagree within one step and depths of a
// centimetre; the solver then pushes them apart along the wrong directions and adds energy.
// A convex polytope has one well-defined deepest penetration (GJK/EPA), an exact signed
// distance (the largest of its face-plane distances inside), and its vertices are the only
// points that can touch a plane or a face first.
//
// qhull reports errors by longjmp to a point inside qh_new_qhull, which then returns a non-zero
// code: it never exits the process as long as we call nothing else of qhull that can fail
// afterwards (we only read its facet and vertex lists, then free them). Its messages go to a
// memory stream, never to stderr; the first line becomes the reason returned to the caller.
#include "collision/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <libqhull_r/libqhull_r.h>
#include <limits>
#include <string>

namespace frontier::collision
{

using core::Vec3;

namespace
{

bool lexicographicLess(const Vec3& p, const Vec3& q)
{
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
}

// A facet of qhull's result: its outward unit normal and its vertices (indices into the input).
struct Facet
{
    Vec3 normal = Vec3::UnitZ();
    std::vector<int> vertices;
};

// A memory stream for qhull's messages (POSIX open_memstream), closed and freed on destruction.
class MessageStream
{
  public:
    MessageStream() : mFile(open_memstream(&mBuffer, &mSize)) {}
    ~MessageStream()
    {
        if (mFile)
            std::fclose(mFile);
        std::free(mBuffer);
    }
    MessageStream(const MessageStream&) = delete;
    MessageStream& operator=(const MessageStream&) = delete;

    FILE* file() const { return mFile; }

    // The first non-empty line written so far, or a fallback.
    std::string firstLine()
    {
        if (!mFile)
            return "qhull failed (no message stream)";
        std::fflush(mFile);
        std::string text(mBuffer ? mBuffer : "", mSize);
        const std::size_t start = text.find_first_not_of(" \n");
        if (start == std::string::npos)
            return "qhull failed without a message";
        return text.substr(start, text.find('\n', start) - start);
    }

  private:
    char* mBuffer = nullptr;
    std::size_t mSize = 0;
    FILE* mFile = nullptr;
};

// Runs qhull on the points (x, y, z per point, m). Returns its exit code (0 on success) and,
// on success, its facets. Nothing of qhull outlives this function.
int runQhull(std::vector<double>& coordinates, std::vector<Facet>& facets, std::string& message,
             const char* extraOptions = "")
{
    MessageStream messages;
    qhT context;
    qhT* qh = &context;
    qh_zero(qh, messages.file());
    // "Pp": no precision warnings. The default merging of coplanar facets ('C-0') stays on, so a
    // cube gives six square faces, not twelve triangles. No joggling, no random rotation: the
    // same points give the same hull on every run. extraOptions: capConvexHull's.
    char options[96];
    std::snprintf(options, sizeof options, "qhull Pp%s", extraOptions);
    const int pointCount = static_cast<int>(coordinates.size() / 3);
    const int code =
        qh_new_qhull(qh, 3, pointCount, coordinates.data(), False, options, nullptr, messages.file());
    if (code == 0)
    {
        facetT* facet = nullptr;
        vertexT* vertex = nullptr;
        vertexT** vertexp = nullptr;
        FORALLfacets
        {
            Facet f;
            f.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]);
            FOREACHvertex_(facet->vertices)
            {
                f.vertices.push_back(static_cast<int>((vertex->point - coordinates.data()) / 3));
            }
            facets.push_back(std::move(f));
        }
    }
    else
    {
        message = messages.firstLine();
    }
    qh_freeqhull(qh, !qh_ALL);
    int stillLong = 0;
    int totalLong = 0;
    qh_memfreeshort(qh, &stillLong, &totalLong);
    return code;
}

// Orders a facet's vertices counter-clockwise seen from outside (along -normal): by their angle
// about the facet's centroid in the plane spanned by u and v = normal x u.
void orderCounterClockwise(const std::vector<Vec3>& points, Facet& f)
{
    Vec3 centroid = Vec3::Zero();
    for (const int i : f.vertices)
        centroid += points[static_cast<std::size_t>(i)];
    centroid /= static_cast<double>(f.vertices.size());
    const Vec3 u = f.normal.unitOrthogonal();
    const Vec3 v = f.normal.cross(u);
    std::vector<std::pair<double, int>> byAngle;
    for (const int i : f.vertices)
    {
        const Vec3 d = points[static_cast<std::size_t>(i)] - centroid;
        byAngle.emplace_back(std::atan2(d.dot(v), d.dot(u)), i);
    }
    std::sort(byAngle.begin(), byAngle.end());
    for (std::size_t k = 0; k < byAngle.size(); ++k)
        f.vertices[k] = byAngle[k].second;
}

// The point of face k of h nearest to p, which lies `height` (> 0) above the face's plane.
Vec3 nearestOnFace(const ConvexHull& h, std::size_t k, const Vec3& p, double height)
{
    const Vec3& n = h.normals[k];
    const Vec3 q = p - height * n; // p projected onto the plane
    bool inside = true;
    double best = std::numeric_limits<double>::infinity();
    Vec3 nearest = q;
    const auto start = static_cast<std::size_t>(h.faceStart[k]);
    const auto count = static_cast<std::size_t>(h.faces[start]);
    for (std::size_t i = 0; i < count; ++i)
    {
        const Vec3& a = h.vertices[static_cast<std::size_t>(h.faces[start + 1 + i])];
        const Vec3& b = h.vertices[static_cast<std::size_t>(h.faces[start + 1 + (i + 1) % count])];
        const Vec3 e = b - a;
        if (n.cross(e).dot(q - a) < 0.0) // outside this edge (n x e points inwards)
            inside = false;
        const double t = std::clamp(e.dot(q - a) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
        const Vec3 onEdge = a + t * e;
        if ((q - onEdge).squaredNorm() < best)
        {
            best = (q - onEdge).squaredNorm();
            nearest = onEdge;
        }
    }
    return inside ? q : nearest;
}

} // namespace

bool computeConvexHull(const std::vector<Vec3>& points, ConvexHull& out, std::string& reason)
{
    out = ConvexHull{};
    std::vector<Vec3> unique = points;
    std::sort(unique.begin(), unique.end(), lexicographicLess);
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    for (const Vec3& p : unique)
    {
        if (!p.allFinite())
        {
            reason = "a vertex is not finite";
            return false;
        }
    }
    if (unique.size() < 4)
    {
        reason = "fewer than 4 distinct vertices";
        return false;
    }

    std::vector<double> coordinates;
    coordinates.reserve(3 * unique.size());
    for (const Vec3& p : unique)
        coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
    std::vector<Facet> facets;
    if (runQhull(coordinates, facets, reason) != 0)
        return false; // flat or collinear input ("initial simplex is flat"), or another qhull error

    // Keep only the vertices the facets use, renumbered in the points' lexicographic order.
    std::vector<int> newIndex(unique.size(), -1);
    for (const Facet& f : facets)
        for (const int i : f.vertices)
            newIndex[static_cast<std::size_t>(i)] = 0;
    for (std::size_t i = 0; i < unique.size(); ++i)
    {
        if (newIndex[i] == 0)
        {
            newIndex[i] = static_cast<int>(out.vertices.size());
            out.vertices.push_back(unique[i]);
        }
    }
    for (Facet& f : facets)
    {
        orderCounterClockwise(unique, f);
        // The supporting plane through the face's outermost vertex: every hull vertex is on or
        // below it (to round-off), as FCL's Convex expects.
        double offset = -std::numeric_limits<double>::infinity();
        out.faceStart.push_back(static_cast<int>(out.faces.size()));
        out.faces.push_back(static_cast<int>(f.vertices.size()));
        for (const int i : f.vertices)
        {
            out.faces.push_back(newIndex[static_cast<std::size_t>(i)]);
            offset = std::max(offset, f.normal.dot(unique[static_cast<std::size_t>(i)]));
        }
        out.normals.push_back(f.normal);
        out.offsets.push_back(offset);
    }
    return true;
}

bool capConvexHull(const ConvexHull& full, int maxCorners, ConvexHull& out, std::string& reason)
{
    if (maxCorners < 4)
    {
        out = ConvexHull{};
        reason = "a hull needs at least 4 corners";
        return false;
    }
    if (full.vertices.size() <= static_cast<std::size_t>(maxCorners))
    {
        out = full;
        return true;
    }
    // qhull starts from a simplex of 4 corners and adds one at a time; Q9 takes the point farthest
    // above any facet next (Qf puts each point in the outside set of the facet it is farthest
    // above), TA stops after maxCorners - 4 additions. Its facets then span the corners picked.
    std::vector<double> coordinates;
    coordinates.reserve(3 * full.vertices.size());
    for (const Vec3& p : full.vertices)
        coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
    char options[32];
    std::snprintf(options, sizeof options, " Qf Q9 TA%d", maxCorners - 4);
    std::vector<Facet> facets;
    if (runQhull(coordinates, facets, reason, options) != 0)
    {
        out = ConvexHull{};
        return false;
    }
    std::vector<char> picked(full.vertices.size(), 0);
    for (const Facet& f : facets)
        for (const int i : f.vertices)
            picked[static_cast<std::size_t>(i)] = 1;
    std::vector<Vec3> corners;
    for (std::size_t i = 0; i < full.vertices.size(); ++i)
        if (picked[i])
            corners.push_back(full.vertices[i]);
    // The hull of the picked corners, from scratch: faces merged and ordered as every hull's.
    return computeConvexHull(corners, out, reason);
}

double hullSignedDistance(const ConvexHull& h, const Vec3& p, Vec3& grad, double exactBelow)
{
    std::size_t best = 0;
    double planeDistance = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < h.normals.size(); ++k)
    {
        const double d = h.normals[k].dot(p) - h.offsets[k];
        if (d > planeDistance)
        {
            planeDistance = d;
            best = k;
        }
    }
    grad = h.normals[best];
    if (planeDistance <= 0.0 || planeDistance >= exactBelow)
        return planeDistance;
    double distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < h.normals.size(); ++k)
    {
        const double height = h.normals[k].dot(p) - h.offsets[k];
        if (height <= 0.0)
            continue; // p is behind this face: the nearest point is on a face p is in front of
        const Vec3 nearest = nearestOnFace(h, k, p, height);
        const double d = (p - nearest).norm();
        if (d < distance) // d >= height > 0
        {
            distance = d;
            grad = (p - nearest) / d;
        }
    }
    return std::max(distance, planeDistance); // the face `best` was visited: distance is finite
}

double hullDeviation(const ConvexHull& full, const ConvexHull& capped)
{
    double largest = 0.0;
    Vec3 grad;
    for (const Vec3& p : full.vertices)
        largest = std::max(largest, hullSignedDistance(capped, p, grad));
    return largest;
}

} // namespace frontier::collision
