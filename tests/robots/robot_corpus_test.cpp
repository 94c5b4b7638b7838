// tests/robots/robot_corpus_test.cpp: robot files nobody here wrote (Debian's dart-doc: KUKA KR5,
// Barrett WAM, DRC-Hubo, Atlas, and DART's own broken test files) and the robots of scenes/robots/,
// each run as a user would: `frontier run FILE.urdf [flags]`.
//
// A valid robot, dropped (or fixed, for arms), runs 2 s (0.25 s in the sanitizer build) and must
// exit 0, stay finite, hold its joints (gap <= 1e-6 m), never gain energy, and never sink more than
// 5 mm into the floor or into itself. A broken file exits 2 naming its file and line.
#include "app_test_util.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace frontier::app::test
{
namespace
{

const std::string cDart = "/usr/share/doc/dart/data/";

#ifdef FRONTIER_SANITIZED
constexpr const char* cDuration = "0.25"; // the same code paths, at a tenth of the cost
#else
constexpr const char* cDuration = "2";
#endif

constexpr double cMaxJointGapM = 1e-6;
constexpr double cMaxPenetrationM = 5e-3;

struct RobotRun
{
    const char* name;
    std::string file; // absolute, or relative to the source folder
    const char* flags;
};

std::ostream& operator<<(std::ostream& out, const RobotRun& r)
{
    return out << r.file << " " << r.flags;
}

std::string locate(const std::string& file)
{
    return file.front() == '/' ? file : sourcePath(file);
}

// Fails (does not skip) when the file is missing: the test set-up installs dart-doc.
void requireFile(const std::string& path)
{
    ASSERT_TRUE(std::filesystem::exists(path))
        << path << " is missing: install Debian's dart-doc package (scripts/install-deps.sh does)";
}

class ValidRobot : public ::testing::TestWithParam<RobotRun>
{
};

TEST_P(ValidRobot, RunsHoldingItsJointsWithoutGainingEnergyOrSinking)
{
    const RobotRun& c = GetParam();
    const std::string file = locate(c.file);
    requireFile(file);
    const TestDir dir;
    const Result r = dir.run("run " + shellQuote(file) + " " + c.flags + " --duration " + cDuration +
                             " --quiet --stats " + shellQuote(dir.out("stats.json")));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
    const nlohmann::json s = nlohmann::json::parse(readText(dir.out("stats.json")));
    EXPECT_TRUE(s["finite"].get<bool>());
    const double e0 = s["energy_initial_j"].get<double>();
    EXPECT_LE(s["max_joint_error_m"].get<double>(), cMaxJointGapM);
    EXPECT_LE(s["energy_max_j"].get<double>(), e0 + 1e-6 * std::max(1.0, std::abs(e0)))
        << "energy rose above its start " << e0 << " J";
    EXPECT_LE(s["max_penetration_m"].get<double>(), cMaxPenetrationM);
    RecordProperty("seconds_per_step", std::to_string(s["seconds_per_step"].get<double>()));
}

const std::string cKr5 = cDart + "urdf/KR5/KR5 sixx R650.urdf";
const std::string cWam = cDart + "urdf/wam/wam.urdf";
const std::string cArm6 = "scenes/robots/arm6_description/urdf/arm6.urdf";

INSTANTIATE_TEST_SUITE_P(
    Robots, ValidRobot,
    ::testing::Values(
        // Arms: fixed to the world by their URDF ('world' link), and dropped as free bodies.
        RobotRun{"KukaKr5", cKr5, ""}, RobotRun{"KukaKr5Dropped", cKr5, "--free-base"},
        RobotRun{"BarrettWam", cWam, ""}, RobotRun{"BarrettWamDropped", cWam, "--free-base"},
        RobotRun{"Arm6", cArm6, ""}, // its base has no mass: bolted down only
        // Humanoids and the rest, dropped; DRC-Hubo also bolted to the world where it stands.
        RobotRun{"DrcHubo", cDart + "urdf/drchubo/drchubo.urdf", ""},
        RobotRun{"DrcHuboFixedBase", cDart + "urdf/drchubo/drchubo.urdf", "--fixed-base"},
        RobotRun{"Atlas", cDart + "sdf/atlas/atlas_v3_no_head.urdf", ""},
        RobotRun{"AtlasFixedBase", cDart + "sdf/atlas/atlas_v3_no_head.urdf", "--fixed-base"},
        RobotRun{"DartIssue838", cDart + "urdf/test/issue838.urdf", ""},
        RobotRun{"DartKr5Ground", cDart + "urdf/KR5/ground.urdf", ""},
        RobotRun{"Quadruped", "scenes/robots/quadruped_description/urdf/quadruped.urdf", ""},
        RobotRun{"QuadrupedDropped", "scenes/robots/quadruped_description/urdf/quadruped.urdf", "--drop-height 0.3"},
        RobotRun{"Rover", "scenes/robots/rover_description/urdf/rover.urdf", ""}),
    [](const ::testing::TestParamInfo<RobotRun>& p) { return std::string(p.param.name); });

struct BrokenRobot
{
    const char* name;
    std::string file;
    const char* flags;
    int line;           // where the message points
    const char* needle; // what it says
    int exitCode;       // 2: refused; 0: loads, with a warning at that line
};

std::ostream& operator<<(std::ostream& out, const BrokenRobot& r)
{
    return out << r.file << " " << r.flags;
}

class BrokenFile : public ::testing::TestWithParam<BrokenRobot>
{
};

TEST_P(BrokenFile, IsNamedWithFileAndLine)
{
    const BrokenRobot& c = GetParam();
    requireFile(c.file);
    const TestDir dir;
    const Result r = dir.run("info " + shellQuote(c.file) + " " + c.flags);
    EXPECT_EQ(r.exitCode, c.exitCode) << r.err;
    const std::string where = c.file + ":" + std::to_string(c.line) + ":";
    EXPECT_NE(r.err.find(where), std::string::npos) << "expected '" << where << "' in: " << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << "expected '" << c.needle << "' in: " << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Dart, BrokenFile,
    ::testing::Values(
        BrokenRobot{"AtlasWithoutItsHead", cDart + "sdf/atlas/atlas_v3.urdf", "", 719,
                    "child link [head] of joint [neck_ry] not found", 2},
        BrokenRobot{"Empty", cDart + "urdf/test/invalid.urdf", "", 1, "invalid XML", 2},
        BrokenRobot{"NotARobot", cDart + "urdf/test/testWorld.urdf", "", 1, "expected a <robot> root element", 2},
        // One massless link and nothing else: it cannot float...
        BrokenRobot{"MasslessRoot", cDart + "urdf/test/primitive_geometry.urdf", "", 3, "has no mass", 2},
        BrokenRobot{"MasslessJointedLinks", cDart + "urdf/test/joint_properties.urdf", "--fixed-base", 17,
                    "joint '0_to_1' moves it", 2},
        // ... and bolted down, what is wrong with its visual mesh is a warning.
        BrokenRobot{"MissingMesh", cDart + "urdf/test/missing_mesh.urdf", "--fixed-base", 6,
                    "warning: visual mesh 'this_file_does_not_exist.stl' of link 'base_link' cannot be read", 0},
        BrokenRobot{"InvalidMesh", cDart + "urdf/test/invalid_mesh.urdf", "--fixed-base", 6,
                    "warning: visual mesh 'invalid_mesh.stl' of link 'base_link' cannot be read", 0},
        BrokenRobot{"MissingPackage", cDart + "urdf/test/missing_package.urdf", "--fixed-base", 6,
                    "package 'missing_package' not found", 0},
        BrokenRobot{"MissingMeshUnbolted", cDart + "urdf/test/missing_mesh.urdf", "", 3, "has no mass", 2}),
    [](const ::testing::TestParamInfo<BrokenRobot>& p) { return std::string(p.param.name); });

} // namespace
} // namespace frontier::app::test
