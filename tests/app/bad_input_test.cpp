// tests/app/bad_input_test.cpp: bad scenes and bad usage exit with code 2 and a message that names
// the file and line (scenes) or the flag (usage), and write nothing.
#include "app_test_util.h"

#include <gtest/gtest.h>
#include <ostream>

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

} // namespace
} // namespace frontier::app::test
