// tests/io/mesh_corpus_test.cpp: real robot meshes from Debian's dart-doc package: every file
// loads, a part's COLLADA file matches its STL, the invalid STL is refused.
#include "io/mesh_file.h"
#include "io/scene.h"
#include "io_test_util.h"

#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

const std::filesystem::path cDartData = "/usr/share/doc/dart/data";

// The test set-up installs dart-doc (scripts/install-deps.sh --for-tests): without it these fail.
#define REQUIRE_DART_DOC()                                                                              \
    ASSERT_TRUE(std::filesystem::is_directory(cDartData))                                                    \
        << "Debian's dart-doc package is not installed (" << cDartData << "): scripts/install-deps.sh --for-tests"

core::Shape loadCorpusMesh(const std::filesystem::path& path)
{
    return detail::loadMeshFile(path.string(), core::Vec3::Ones());
}

// Largest distance from a vertex of `a` to the nearest vertex of `b` (m).
double farthestFromNearest(const core::Shape& a, const core::Shape& b)
{
    double worst = 0.0;
    for (const core::Vec3& p : a.vertices)
    {
        double nearest = 1e300;
        for (const core::Vec3& q : b.vertices)
        {
            nearest = std::min(nearest, (p - q).squaredNorm());
        }
        worst = std::max(worst, nearest);
    }
    return std::sqrt(worst);
}

void expectSameSurface(const std::filesystem::path& first, const std::filesystem::path& second)
{
    const core::Shape a = loadCorpusMesh(first);
    const core::Shape b = loadCorpusMesh(second);
    EXPECT_EQ(a.triangles.size(), b.triangles.size());
    EXPECT_EQ(a.vertices.size(), b.vertices.size());
    EXPECT_LE(farthestFromNearest(a, b), 1e-6) << first << " vs " << second;
    EXPECT_LE(farthestFromNearest(b, a), 1e-6) << second << " vs " << first;
}

// The Atlas parts are COLLADA files with <up_axis>Z_UP</up_axis> next to STL files of the same
// triangles: read as URDF tools read them, the two agree (a y-up conversion would rotate the DAE
// 90 degrees about x; these parts are not symmetric under that).
TEST(MeshCorpus, AtlasZUpColladaMatchesItsStl)
{
    REQUIRE_DART_DOC();
    for (const char* part : {"head", "l_foot", "r_uleg", "utorso"})
    {
        SCOPED_TRACE(part);
        const std::filesystem::path dir = cDartData / "sdf/atlas";
        expectSameSurface(dir / (std::string(part) + ".dae"), dir / (std::string(part) + ".stl"));
    }
}

// The WAM base is a Y_UP COLLADA file with the same triangles as its STL.
TEST(MeshCorpus, WamYUpColladaMatchesItsStl)
{
    REQUIRE_DART_DOC();
    const std::filesystem::path dir = cDartData / "urdf/wam/meshes/wam";
    expectSameSurface(dir / "wam_base.dae", dir / "wam_base.STL");
}

TEST(MeshCorpus, EveryMeshFileLoadsAndEnclosesAPositiveVolume)
{
    REQUIRE_DART_DOC();
    int count = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(cDartData))
    {
        const std::string ext = [&]
        {
            std::string e = entry.path().extension().string();
            std::transform(e.begin(), e.end(), e.begin(),
                           [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
            return e;
        }();
        if (!entry.is_regular_file() || (ext != ".stl" && ext != ".dae" && ext != ".obj") ||
            entry.path().filename() == "invalid_mesh.stl")
        {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        const core::Shape shape = loadCorpusMesh(entry.path());
        EXPECT_GT(shape.triangles.size(), 0u);
        EXPECT_GT(core::shapeVolume(shape), 0.0); // outward faces: no mirroring lost or added
        ++count;
    }
    EXPECT_GE(count, 150); // dart-doc 6.12 ships 160 of them
}

TEST(MeshCorpus, InvalidStlIsRefusedWithItsName)
{
    REQUIRE_DART_DOC();
    const std::string path = (cDartData / "urdf/test/invalid_mesh.stl").string();
    const InputError e = captureInputError([&] { loadCorpusMesh(path); });
    EXPECT_INPUT_ERROR_AT(e, path, 0, 0, "Failed to determine STL storage representation");
}

} // namespace
} // namespace frontier::io::test
