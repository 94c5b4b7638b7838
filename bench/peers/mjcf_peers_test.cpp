// bench/peers/mjcf_peers_test.cpp: MJCF files in MuJoCo (from the file) and in Frontier (from its
// import) have the same bodies: on every MJCF file of Debian's dart-doc both load, masses and
// inertias equal MuJoCo's compiled values to 1e-9 relative; the gym pendulums' passive motion
// follows MuJoCo's RK4 (mjcf_peers.h).
#include "bench/peers/mjcf_peers.h"
#include "tests/decompressed_copy.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

namespace frontier::peers
{
namespace
{

namespace fs = std::filesystem;

const fs::path cDartMjcf = "/usr/share/doc/dart/data/mjcf";

// dart-doc's MJCF folder copied into a temporary folder, every .gz decompressed beside the rest, so
// that includes (robot.xml, shared.xml) and meshes resolve; the .xml files in it, sorted.
struct MjcfCopy
{
    fs::path folder;
    std::vector<std::string> files;

    MjcfCopy() = default;
    MjcfCopy(MjcfCopy&& other) noexcept : folder(std::move(other.folder)), files(std::move(other.files))
    {
        other.folder.clear();
    }
    MjcfCopy(const MjcfCopy&) = delete;
    MjcfCopy& operator=(const MjcfCopy&) = delete;
    MjcfCopy& operator=(MjcfCopy&&) = delete;
    ~MjcfCopy()
    {
        std::error_code ignored;
        if (!folder.empty())
            fs::remove_all(folder, ignored);
    }
};

const MjcfCopy& dartMjcfFiles()
{
    static const MjcfCopy copy = []
    {
        MjcfCopy out;
        out.folder = fs::temp_directory_path() / ("frontier_mjcf_peers_" + std::to_string(::getpid()));
        fs::remove_all(out.folder);
        for (const std::string& file : copyDecompressed(cDartMjcf, out.folder))
        {
            if (file.ends_with(".xml"))
                out.files.push_back((out.folder / file).string());
        }
        return out;
    }();
    return copy;
}

#define SKIP_WITHOUT_DART_DOC()                                                                              \
    if (!fs::exists(cDartMjcf))                                                                              \
    GTEST_SKIP() << cDartMjcf << " is missing (Debian's dart-doc: scripts/install-deps.sh --for-tests)"

std::string dartFile(const std::string& relative)
{
    return (dartMjcfFiles().folder / relative).string();
}

TEST(MjcfPeers, EveryDartDocMjcfHasMujocosMassesAndInertias)
{
    SKIP_WITHOUT_DART_DOC();
    int compared = 0;
    for (const std::string& file : dartMjcfFiles().files)
    {
        MjcfInertia inertia;
        try
        {
            inertia = compareInertia(file);
        }
        catch (const std::exception& e)
        {
            // A file either engine refuses (an include fragment, a model outside Frontier's scope).
            std::cout << "not compared: " << e.what() << "\n";
            continue;
        }
        // dart-doc's test files hold only bodies welded to the world: Frontier's static body.
        compared += inertia.bodies.empty() ? 0 : 1;
        EXPECT_LE(inertia.largestDifference, 1e-9) << file << ": " << inertia.largestAt;
        for (const MjcfBodyInertia& body : inertia.bodies)
            EXPECT_LE(body.centreDifferenceM, 1e-9 * std::max(1.0, body.mujocoCentre_W.norm()))
                << file << ": " << body.name;
    }
    // The gym models but walker2d (MuJoCo 2.2 refuses a `pos` of it) and the Fetch tasks: a file
    // list that shrank shows here.
    EXPECT_GE(compared, 17);
}

// The gym pendulums: every geom has contype 0 (the rail, the cart, the poles; the double pendulum's
// floor too), so nothing can collide; the runs turn contacts off in both all the same (mjcf_peers.h).
// MuJoCo RK4 and Frontier rattle4 at dt = 1e-4 s, compared every 0.01 s.
MjcfMotion pendulumMotion(const std::string& file, double duration)
{
    MjcfMotionSettings settings;
    settings.duration = duration;
    MjcfMotion motion = compareMotion(file, settings);
    EXPECT_FALSE(motion.contactsPossible) << file;
    return motion;
}

// The engines' bodies stayed within `metres` and `radians` of each other.
void expectAgreement(const MjcfMotion& motion, double metres, double radians, const std::string& file)
{
    EXPECT_LE(motion.maxPositionM, metres)
        << file << ": " << motion.worstBody << " at " << motion.worstTime << " s";
    EXPECT_LE(motion.maxAngleRad, radians) << file;
}

// A copy of a dart-doc file beside it (its folder keeps its includes), with every `from` replaced
// by `to` (each must occur).
std::string editedCopy(const std::string& relative, const std::string& name,
                       const std::vector<std::pair<std::string, std::string>>& edits)
{
    std::ifstream in(dartFile(relative));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const auto& [from, to] : edits)
    {
        EXPECT_NE(text.find(from), std::string::npos) << relative << ": " << from;
        for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        {
            text.replace(at, from.size(), to);
        }
    }
    const std::string path = (fs::path(dartFile(relative)).parent_path() / name).string();
    std::ofstream(path) << text;
    return path;
}

// The cart-pole falls from its tilted start (0.1 rad in 1 s, before its hinge reaches its 90
// degree limit at about 1.5 s, where MuJoCo's soft limit and Frontier's hard one part). The joints'
// damping (1 N s/m, N m s/rad) is what the engines do differently: MuJoCo's RK4 integrates it to
// fourth order, Frontier's damping rows are first order in dt, which leaves 1.9e-6 m at dt = 1e-3
// s and 2.1e-7 m (1.0e-6 rad) at 1e-4 s: bounds of 5 times that.
TEST(MjcfPeers, InvertedPendulumFallsAsInMujocoRk4)
{
    SKIP_WITHOUT_DART_DOC();
    const std::string file = dartFile("openai/inverted_pendulum.xml");
    const MjcfMotion motion = pendulumMotion(file, 1.0);
    EXPECT_GE(motion.turnRad, 0.05);
    expectAgreement(motion, 1e-6, 5e-6, file);
}

// Without damping both integrate the same equations to their order: they agree to round-off
// (1e-10 m measured), with or without the hinge's armature (MuJoCo's rotor inertia in joint space;
// Frontier's inertia of the pole about the hinge axis, the same term here because the cart only
// slides).
TEST(MjcfPeers, UndampedInvertedPendulumWithArmatureMovesExactlyAsInMujocoRk4)
{
    SKIP_WITHOUT_DART_DOC();
    for (const bool armature : {false, true})
    {
        std::vector<std::pair<std::string, std::string>> edits = {{"damping=\"1\"", "damping=\"0\""}};
        if (armature)
            edits.push_back({"name=\"hinge\" pos", "name=\"hinge\" armature=\"0.1\" pos"});
        const std::string file =
            editedCopy("openai/inverted_pendulum.xml",
                       armature ? "pendulum_armature.xml" : "pendulum_undamped.xml", edits);
        const MjcfMotion motion = pendulumMotion(file, 1.0);
        EXPECT_GE(motion.turnRad, 0.05) << file;
        expectAgreement(motion, 1e-9, 1e-9, file);
    }
}

// The double pendulum starts upright, an unstable equilibrium left through its joints' damping
// coupled to the 1e-5 m/s^2 sideways gravity: any difference grows about 1 500-fold per second, and in
// 3 s the poles fall (1.2 m, 2.5 rad). Frontier's first-order damping leaves 2.9e-5 m and 3.9e-5
// rad at dt = 1e-4 s (8e-5 m at 1e-3 s, 2.5e-4 m at 2.5e-5 s: an amplified difference does not
// shrink steadily with dt): bounds of 1e-4 m and 2e-4 rad.
TEST(MjcfPeers, InvertedDoublePendulumFallsAsInMujocoRk4)
{
    SKIP_WITHOUT_DART_DOC();
    const std::string file = dartFile("openai/inverted_double_pendulum.xml");
    const MjcfMotion motion = pendulumMotion(file, 3.0);
    EXPECT_GE(motion.travelM, 1.0);
    expectAgreement(motion, 1e-4, 2e-4, file);
}

// frontier_peers --mjcf: the three parts on a file both load; exit code 2 for one they refuse.
TEST(MjcfPeers, TheHarnessReportsMassesMotionAndTimeOrRefusesTheFile)
{
    SKIP_WITHOUT_DART_DOC();
    std::ostringstream out;
    EXPECT_EQ(runMjcfComparison(dartFile("openai/inverted_pendulum.xml"), {}, false, 1, out), 0);
    for (const char* part : {"| pole | 5.01859164 | 5.01859164 |", "largest centre-of-mass distance",
                             "Frontier euler at dt 0.02 s", "MuJoCo RK4 at dt 0.02 s"})
        EXPECT_NE(out.str().find(part), std::string::npos) << part << " not in\n" << out.str();
    std::ostringstream refused;
    EXPECT_EQ(runMjcfComparison(dartFile("openai/walker2d.xml"), {}, false, 1, refused), 2);
    EXPECT_EQ(refused.str(), "");
}

} // namespace
} // namespace frontier::peers
