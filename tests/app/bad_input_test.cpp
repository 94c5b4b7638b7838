// tests/app/bad_input_test.cpp: bad scenes and bad usage exit with code 2 and a message that names
// the file and line (scenes) or the flag (usage), and write nothing.
#include "app_test_util.h"
#include "io/trajectory.h"

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

// A first word that is no command is named, with the nearest command or the list of them; a
// choice flag's wrong value is named with its choices.
TEST(BadInput, UnknownCommandAndChoiceAreNamed)
{
    const TestDir dir;
    const Result typo = dir.run("runn scenes/pendulum.yaml");
    EXPECT_EQ(typo.exitCode, 2) << typo.err;
    EXPECT_NE(typo.err.find("unknown command 'runn'; did you mean 'run'?"), std::string::npos) << typo.err;
    const Result unknown = dir.run("simulate scenes/pendulum.yaml");
    EXPECT_EQ(unknown.exitCode, 2) << unknown.err;
    EXPECT_NE(unknown.err.find("unknown command 'simulate'"), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("run, info, render, check, stability, sweep, batch"), std::string::npos)
        << unknown.err;
    const Result choice =
        dir.run("sweep scenes/pendulum.yaml --out " + shellQuote(dir.out("s")) + " --chart-accuracy gap");
    EXPECT_EQ(choice.exitCode, 2) << choice.err;
    EXPECT_NE(choice.err.find("gap not in {error,joint-gap,penetration}"), std::string::npos) << choice.err;
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

// Every numeric flag of every command follows one rule: a finite number in its range, a whole
// number for a count. Each of these is refused with exit 2 naming the flag, before anything runs
// or is written (a nan used to pass the positive checks; 1e20 steps used to run forever).
TEST(BadInput, NumericFlagsAreFiniteInRangeAndWholeForCounts)
{
    const TestDir dir;
    const std::string t = " --trajectory " + shellQuote(dir.out("t.csv"));
    const std::string f = " --frames " + shellQuote(dir.out("f"));
    const std::pair<std::string, std::string> cases[] = {
        {"run scenes/pendulum.yaml --dt nan" + t, "--dt"},
        {"run scenes/pendulum.yaml --duration nan" + t, "--duration"},
        {"run scenes/pendulum.yaml --duration 1e16" + t, "--duration"},
        {"run scenes/pendulum.yaml --steps 99999999999999999999" + t, "--steps"},
        {"run scenes/pendulum.yaml --steps 2.5" + t, "--steps"},
        {"run scenes/pendulum.yaml --fps nan" + f, "--fps"},
        {"run scenes/pendulum.yaml --fps 1e308" + f, "--fps"},
        {"run scenes/pendulum.yaml --jobs 0.5" + t, "--jobs"},
        {"render x.csv --fps nan" + f, "--fps"},
        {"stability scenes/pendulum.yaml --dt nan --out " + shellQuote(dir.out("s.md")), "--dt"},
        {"check scenes/pendulum.yaml --reference x.csv --tol nan", "--tol"},
        {"sweep scenes/pendulum.yaml --duration nan --out " + shellQuote(dir.out("sw")), "--duration"},
    };
    for (const auto& [args, flag] : cases)
    {
        const Result r = dir.run(args);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(flag), std::string::npos) << args << "\n" << r.err;
        EXPECT_TRUE(dir.outputs().empty()) << args;
    }
    // A count given in exponent notation is a whole number all the same.
    const Result r = dir.run("run scenes/pendulum.yaml --quiet --steps 1e1" + t);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(io::readTrajectory(dir.out("t.csv")).rows.size(), 11u);
}

// duration / dt beyond 1e12 steps (or past a long's range, which used to wrap to one step) is
// refused, for the flags and for the scene's own settings alike.
TEST(BadInput, StepCountsBeyondTheBoundAreRefused)
{
    const TestDir dir;
    for (const std::string& args : {std::string("run scenes/pendulum.yaml --dt 1e-300"),
                                    std::string("run scenes/pendulum.yaml --duration 1e11 --dt 1e-3"),
                                    std::string("stability scenes/pendulum.yaml --dt 1e-300")})
    {
        const Result r = dir.run(args + " --quiet");
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("steps"), std::string::npos) << args << "\n" << r.err;
    }
    const std::string scene = dir.write("long.yaml", R"(
simulation: {dt: 1.0e-300, duration: 1.0}
bodies:
  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}}
)");
    const Result r = dir.run("run " + shellQuote(scene) + " --quiet");
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(scene), std::string::npos) << r.err;
}

// A body whose initial energy overflows (a position of -1e308 m: m g z is -inf) is refused at load,
// by name, instead of running with a null initial energy and a -nan% change.
TEST(BadInput, InfiniteInitialEnergyIsRefusedNamingTheBody)
{
    const TestDir dir;
    const std::string scene = dir.write("deep.yaml", R"(
simulation: {dt: 0.001, duration: 0.01}
bodies:
  - {name: ok, mass: 1, shape: {type: sphere, radius: 0.1}}
  - {name: abyss, mass: 1, shape: {type: sphere, radius: 0.1}, position: [0, 0, -1.0e308]}
)");
    const Result r = dir.run("run " + shellQuote(scene) + " --stats " + shellQuote(dir.out("s.json")));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("'abyss'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("energy"), std::string::npos) << r.err;
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
