// tests/app/bad_input_test.cpp: bad scenes and bad usage exit with code 2 and a message that names
// the file and line (scenes) or the flag (usage), and write nothing.
#include "app_test_util.h"

#include <chrono>
#include <filesystem>
#include <gtest/gtest.h>
#include <ostream>
#include <sys/stat.h>
#include <utility>

namespace frontier::app::test
{
namespace
{

struct BadScene
{
    const char* name;   // test name
    const char* file;   // file name in the test folder
    std::string text;   // its content
    int line;           // the line the message must name
    const char* needle; // and a part of its text
};

void PrintTo(const BadScene& c, std::ostream* os)
{
    *os << c.name;
}

class BadSceneFile : public ::testing::TestWithParam<BadScene>
{
};

TEST_P(BadSceneFile, ExitsWithTwoNamingFileAndLine)
{
    const BadScene& c = GetParam();
    const TestDir dir;
    const std::string scene = dir.write(c.file, c.text);
    const std::string traj = dir.out("t.csv");
    const Result r =
        dir.run("run " + shellQuote(scene) + " --duration 0.01 --trajectory " + shellQuote(traj));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    const std::string where = scene + ":" + std::to_string(c.line) + ":";
    EXPECT_NE(r.err.find(where), std::string::npos) << "expected '" << where << "' in: " << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << "expected '" << c.needle << "' in: " << r.err;
    EXPECT_TRUE(dir.outputs().empty());
    // `info` rejects it the same way.
    const Result info = dir.run("info " + shellQuote(scene));
    EXPECT_EQ(info.exitCode, 2) << info.err;
    EXPECT_NE(info.err.find(where), std::string::npos) << info.err;
}

const char* const cBall = "  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}\n";

INSTANTIATE_TEST_SUITE_P(
    App, BadSceneFile,
    ::testing::Values(
        BadScene{"UnknownKey", "unknown_key.yaml",
                 "bodies:\n  - name: ball\n    mas: 1.0\n    shape: {type: sphere, radius: 0.1}\n", 3,
                 "unknown key 'mas'"},
        BadScene{"BrokenYamlSyntax", "broken.yaml",
                 "bodies:\n  - name: ball\n    mass: 1.0: 2\n    shape: {type: sphere, radius: 0.1}\n", 3,
                 "invalid YAML"},
        BadScene{"UnknownJointType", "joint_type.yaml",
                 std::string("bodies:\n") + cBall +
                     "joints:\n  - {name: j, type: hinge, parent: world, child: ball, anchor: [0, 0, 0]}\n",
                 4, "hinge"},
        BadScene{"ZeroMass", "zero_mass.yaml",
                 "bodies:\n  - name: ball\n    mass: 0\n    shape: {type: sphere, radius: 0.1}\n", 3, "mass"},
        BadScene{"NegativeMass", "negative_mass.yaml",
                 "bodies:\n  - name: ball\n    mass: -2.5\n    shape: {type: sphere, radius: 0.1}\n", 3,
                 "mass"},
        BadScene{"NotANumber", "nan.yaml",
                 "bodies:\n  - name: ball\n    mass: 1\n    position: [0, .nan, 1]\n"
                 "    shape: {type: sphere, radius: 0.1}\n",
                 4, "position"},
        BadScene{
            "UrdfMasslessLinkOnAJoint", "robot.urdf",
            "<robot name=\"r\">\n"
            "  <link name=\"a\">\n"
            "    <inertial><mass value=\"1\"/>"
            "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>\n"
            "  </link>\n"
            "  <link name=\"b\"/>\n"
            "  <joint name=\"j\" type=\"continuous\">\n"
            "    <parent link=\"a\"/><child link=\"b\"/>\n"
            "  </joint>\n"
            "</robot>\n",
            6,
            "link 'b' has no mass (no <inertial> with a positive mass) but continuous joint 'j' moves it"}),
    [](const ::testing::TestParamInfo<BadScene>& p) { return std::string(p.param.name); });

TEST(BadInput, MissingSceneFileIsNamed)
{
    const TestDir dir;
    const std::string missing = (dir.path() / "no_such_scene.yaml").string();
    const Result r = dir.run("run " + shellQuote(missing) + " --trajectory " + shellQuote(dir.out("t.csv")));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;
    EXPECT_TRUE(dir.outputs().empty());
}

TEST(BadInput, UnknownSolverNameIsAUsageError)
{
    const TestDir dir;
    const Result r =
        dir.run("run scenes/pendulum.yaml --solver fastest --trajectory " + shellQuote(dir.out("t.csv")));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--solver"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("fastest"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.outputs().empty());
}

TEST(BadInput, DurationTogetherWithStepsIsAUsageError)
{
    const TestDir dir;
    const Result r = dir.run("run scenes/pendulum.yaml --duration 1 --steps 10 --trajectory " +
                             shellQuote(dir.out("t.csv")));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--steps"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--duration"), std::string::npos) << r.err;
    EXPECT_TRUE(dir.outputs().empty());
}

// Input that is not a file of text (a FIFO, /dev/zero, a URDF nested 40 000 deep, a joint loop)
// exits with 2 at once: no crash, no hang, no unbounded read. Each input is made here, at run time.
TEST(BadInput, UnreadableInputsExitWithTwoAtOnce)
{
    const TestDir dir;
    ASSERT_EQ(::mkfifo((dir.path() / "pipe.yaml").c_str(), 0600), 0);
    std::filesystem::create_symlink("/dev/zero", dir.path() / "zero.urdf");
    const std::string inertial =
        "<inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" "
        "iyz=\"0\" izz=\"1\"/></inertial>";
    std::string deep = "<robot name=\"r\">\n<link name=\"a\">" + inertial + "</link>\n";
    for (int i = 0; i < 40000; ++i)
    {
        deep += "<x>";
    }
    dir.write("deep.urdf", deep + "\n</robot>\n");
    dir.write("loop.urdf", "<robot name=\"r\">\n<link name=\"a\">" + inertial + "</link>\n<link name=\"b\">" +
                               inertial +
                               "</link>\n<joint name=\"j\" type=\"fixed\"><parent link=\"b\"/><child "
                               "link=\"b\"/></joint>\n</robot>\n");
    const std::pair<const char*, const char*> cases[] = {
        {"pipe.yaml", "pipe.yaml: error: is not a regular file (a FIFO)"},
        {"zero.urdf", "zero.urdf: error: is not a regular file (a device)"},
        {"deep.urdf", "deep.urdf:3:2998: error: elements nested more than 1000 levels deep"},
        {"loop.urdf", "loop.urdf:4:1: error: joint 'j' joins link 'b' to itself"}};
    for (const auto& [file, needle] : cases)
    {
        const auto start = std::chrono::steady_clock::now();
        const Result r = dir.run("info " + shellQuote((dir.path() / file).string()));
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_EQ(r.exitCode, 2) << file << ": " << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.err;
        EXPECT_LT(seconds, 5.0) << file; // a second on an idle machine; the bound catches a hang
    }
}

// `check` and `render` share the trajectory reader: a corrupt reference row is located in both.
TEST(BadInput, CorruptTrajectoryIsLocatedByCheckAndRender)
{
    const TestDir dir;
    const std::string ref = dir.write(
        "ref.csv",
        "# frontier trajectory: scene=scenes/pendulum.yaml dt=0.001 solver=linear pgs_iterations=50 "
        "integrator=rattle steps=10 record_every=1 duration=0.01\n"
        "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n"
        "0,bob,0,0,1,0,0,0,0,0,0,0,0,0,0\n");
    const std::string where = ref + ":3:13: error: orientation quaternion has norm 0";
    const Result check = dir.run("check scenes/pendulum.yaml --reference " + shellQuote(ref));
    EXPECT_EQ(check.exitCode, 2) << check.err;
    EXPECT_NE(check.err.find(where), std::string::npos) << check.err;
    const Result render = dir.run("render " + shellQuote(ref) + " --frames " + shellQuote(dir.out("frames")));
    EXPECT_EQ(render.exitCode, 2) << render.err;
    EXPECT_NE(render.err.find(where), std::string::npos) << render.err;
}

} // namespace
} // namespace frontier::app::test
