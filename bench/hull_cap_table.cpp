// bench/hull_cap_table.cpp: what capping the corners of collision hulls changes (collision/README.md
// "Meshes"). For every mesh shape of the moving bodies of the scenes or URDF files given, its full
// convex hull against the hull of at most K of its corners (collision::capConvexHull) for each K
// asked: the largest distance of the full hull from the capped one (mm) and the volume the capped
// one keeps (% of the full hull's). One line per mesh that has more than the smallest K corners,
// then per K the largest distance and the smallest volume over all meshes.
//
//   hull_cap_table [--corners 16,24,32,48,64] FILE...
#include "collision/convex_hull.h"
#include "io/scene.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{

using namespace frontier;
using core::Vec3;

// Volume (m^3) enclosed by the faces, each a fan of triangles (counter-clockwise seen from outside).
double enclosedVolume(const collision::ConvexHull& h)
{
    double volume = 0.0;
    for (const int start : h.faceStart)
    {
        const auto corner = [&](int i)
        { return h.vertices[static_cast<std::size_t>(h.faces[static_cast<std::size_t>(start + 1 + i)])]; };
        const int n = h.faces[static_cast<std::size_t>(start)];
        for (int i = 1; i + 1 < n; ++i)
            volume += corner(0).dot(corner(i).cross(corner(i + 1))) / 6.0;
    }
    return volume;
}

std::vector<int> parseList(const std::string& text)
{
    std::vector<int> out;
    std::size_t at = 0;
    while (at < text.size())
    {
        const std::size_t comma = text.find(',', at);
        out.push_back(std::atoi(text.substr(at, comma - at).c_str()));
        at = comma == std::string::npos ? text.size() : comma + 1;
    }
    return out;
}

// Per K, over every mesh tabled: the largest distance (m), the smallest volume kept (%) and how
// many meshes have more than K corners.
struct Worst
{
    std::vector<double> distance;
    std::vector<double> volume;
    std::vector<int> capped;
    int meshes = 0;
};

// One mesh's line (if it has more than the smallest K corners), adding it to worst; false, with
// the reason on stderr, when a capped hull cannot be made.
bool tableMesh(const std::string& file, const core::Body& body, const core::Shape& shape,
               const std::vector<int>& caps, Worst& worst)
{
    collision::ConvexHull full;
    std::string reason;
    if (!collision::computeConvexHull(shape.vertices, full, reason))
        return true;
    ++worst.meshes;
    const double fullVolume = enclosedVolume(full);
    const bool shown = full.vertices.size() > static_cast<std::size_t>(caps.front());
    if (shown)
        std::printf("| %s | %s | %zu |", file.substr(file.find_last_of('/') + 1).c_str(), body.name.c_str(),
                    full.vertices.size());
    for (std::size_t c = 0; c < caps.size(); ++c)
    {
        collision::ConvexHull small;
        if (!collision::capConvexHull(full, caps[c], small, reason))
        {
            std::fprintf(stderr, "%s: %s: %s\n", file.c_str(), body.name.c_str(), reason.c_str());
            return false;
        }
        const double distance = collision::hullDeviation(full, small);
        const double volume = 100.0 * enclosedVolume(small) / fullVolume;
        worst.distance[c] = std::max(worst.distance[c], distance);
        worst.volume[c] = std::min(worst.volume[c], volume);
        worst.capped[c] += full.vertices.size() > static_cast<std::size_t>(caps[c]) ? 1 : 0;
        if (shown)
            std::printf(" %.2f, %.1f |", 1e3 * distance, volume);
    }
    if (shown)
        std::printf("\n");
    return true;
}

} // namespace

int main(int argc, char** argv)
{
    std::vector<int> caps{16, 24, 32, 48, 64};
    std::vector<std::string> files;
    for (int k = 1; k < argc; ++k)
    {
        const std::string arg = argv[k];
        if (arg == "--corners" && k + 1 < argc)
            caps = parseList(argv[++k]);
        else
            files.push_back(arg);
    }
    if (files.empty() || caps.empty() || *std::min_element(caps.begin(), caps.end()) < 4)
    {
        std::fprintf(stderr, "usage: hull_cap_table [--corners K1,K2,...] SCENE_OR_URDF...\n");
        return 2;
    }
    std::sort(caps.begin(), caps.end());
    Worst worst{std::vector<double>(caps.size(), 0.0), std::vector<double>(caps.size(), 100.0),
                std::vector<int>(caps.size(), 0), 0};
    std::printf("| file | body | corners |");
    for (const int k : caps)
        std::printf(" K=%d: mm, volume %% |", k);
    std::printf("\n");
    for (const std::string& file : files)
    {
        const core::Model model = io::loadScene(file);
        for (const core::Body& body : model.bodies)
        {
            if (body.isStatic)
                continue;
            for (const core::Shape& shape : body.shapes)
            {
                if (shape.type == core::ShapeType::Mesh && !tableMesh(file, body, shape, caps, worst))
                    return 1;
            }
        }
    }
    std::printf("\n%d meshes\n\n| K | meshes capped | largest distance (mm) | smallest volume kept (%%) "
                "|\n|---|---|---|---|\n",
                worst.meshes);
    for (std::size_t c = 0; c < caps.size(); ++c)
        std::printf("| %d | %d | %.2f | %.1f |\n", caps[c], worst.capped[c], 1e3 * worst.distance[c],
                    worst.volume[c]);
    return 0;
}
