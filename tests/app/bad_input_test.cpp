// tests/app/bad_input_test.cpp: bad scenes and bad usage exit with code 2 and a message that names
// the file and line (scenes) or the flag (usage), and write nothing.
#include "app_test_util.h"
#include "io/file_util.h"
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

// Links a, b and c, b and c on continuous joints j and k from a; `collisionOrigin` goes into b's
// <collision> (line 8), `jointOrigin` is j's <origin xyz> (line 16).
std::string threeLinkUrdf(const std::string& collisionOrigin, const std::string& jointOrigin)
{
    const std::string inertial =
        "    <inertial><mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" "
        "iyz=\"0\" izz=\"1\"/></inertial>\n";
    const std::string sphere = "<geometry><sphere radius=\"0.1\"/></geometry></collision>\n  </link>\n";
    return "<robot name=\"r\">\n  <link name=\"a\">\n" + inertial + "    <collision>" + sphere +
           "  <link name=\"b\">\n" + inertial + "    <collision>" + collisionOrigin + sphere +
           "  <link name=\"c\">\n" + inertial + "    <collision>" + sphere +
           "  <joint name=\"j\" type=\"continuous\">\n    <parent link=\"a\"/><child link=\"b\"/>\n"
           "    <origin xyz=\"" +
           jointOrigin +
           "\"/>\n  </joint>\n"
           "  <joint name=\"k\" type=\"continuous\">\n    <parent link=\"a\"/><child link=\"c\"/>\n"
           "    <origin xyz=\"0 1 0\"/>\n  </joint>\n</robot>\n";
}

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
            6, "link 'b' has no mass (no <inertial> with a positive mass) but continuous joint 'j' moves it"},
        // Positions, sizes and starting speeds lie in the ranges of core/model.h, in YAML and URDF
        // alike: a body or an origin 1e308 m away used to crash the collision detection's set-up.
        BadScene{"FarBodyPosition", "far.yaml",
                 "bodies:\n"
                 "  - {name: ball, mass: 1, shape: {type: sphere, radius: 0.1}, position: [1.0e308, 0, 1]}\n"
                 "  - {name: b2, mass: 1, shape: {type: sphere, radius: 0.1}, position: [0, 0, 1]}\n"
                 "  - {name: b3, mass: 1, shape: {type: sphere, radius: 0.1}, position: [0, 3, 1]}\n"
                 "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1]}}\n",
                 2, "expected a point within 1e6 m of the origin for 'position' in body 'ball'"},
        BadScene{"FarShapeOffset", "far_shape.yaml",
                 "bodies:\n  - name: ball\n    mass: 1\n"
                 "    shape: {type: sphere, radius: 0.1, position: [0, 0, -1.0e250]}\n",
                 4, "expected a point within 1e6 m of the origin for 'position' in sphere shape of body"},
        BadScene{"HugeRadius", "huge_radius.yaml",
                 "bodies:\n  - name: ball\n    mass: 1\n    shape: {type: sphere, radius: 1.0e300}\n", 4,
                 "expected a length in (0, 1e6] m for 'radius'"},
        BadScene{"HugeBoxSide", "huge_box.yaml",
                 "bodies:\n  - name: box\n    mass: 1\n    shape: {type: box, size: [1, 1.0e200, 1]}\n", 4,
                 "expected a length in (0, 1e6] m for the full extents of 'size'"},
        BadScene{
            "FarJointAnchor", "far_anchor.yaml",
            std::string("bodies:\n") + cBall +
                "joints:\n  - {name: j, type: ball, parent: world, child: ball, anchor: [0, 1.0e300, 0]}\n",
            4, "expected a point within 1e6 m of the origin for 'anchor'"},
        BadScene{"FastBody", "fast.yaml",
                 "bodies:\n  - name: ball\n    mass: 1\n    velocity: [1.0e150, 0, 0]\n"
                 "    shape: {type: sphere, radius: 0.1}\n",
                 4, "expected a velocity of at most 1e5 m/s for 'velocity' in body 'ball'"},
        BadScene{"HugeTimeStep", "huge_dt.yaml", std::string("simulation: {dt: 1.0e308}\nbodies:\n") + cBall,
                 1, "expected a number of seconds in (0, 1e+06] for 'dt' in 'simulation', got 1e+308"},
        // Three links (and the floor) make the collision detection build a tree: the crash.
        BadScene{"UrdfFarJointOrigin", "far_joint.urdf", threeLinkUrdf("", "1e308 0 0"), 16,
                 "the <origin xyz> of joint 'j' is (1e+308, 0, 0) m; expected a point within 1e6 m"},
        BadScene{"UrdfFarCollisionOrigin", "far_collision.urdf",
                 threeLinkUrdf("<origin xyz=\"1e308 0 0\"/>", "0 0 0"), 8,
                 "the <origin xyz> of a collision of link 'b' is (1e+308, 0, 0) m"},
        BadScene{"UrdfHugeCylinder", "huge_cylinder.urdf",
                 "<robot name=\"r\">\n"
                 "  <link name=\"a\">\n"
                 "    <inertial><mass value=\"1\"/>"
                 "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>\n"
                 "    <collision>\n"
                 "      <geometry><cylinder radius=\"0.1\" length=\"1e250\"/></geometry>\n"
                 "    </collision>\n"
                 "  </link>\n"
                 "</robot>\n",
                 5,
                 "cylinder radius and length of a collision of link 'a' are 0.1 and 1e+250; expected each"}),
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

// A body whose initial energy overflows (a mass of 1e308 kg 10 m up: m g z is inf) is refused at
// load, by name and at its line, instead of running with a null initial energy and a -nan% change.
TEST(BadInput, InfiniteInitialEnergyIsRefusedNamingTheBody)
{
    const TestDir dir;
    const std::string scene = dir.write("deep.yaml", R"(
simulation: {dt: 0.001, duration: 0.01}
bodies:
  - {name: ok, mass: 1, shape: {type: sphere, radius: 0.1}}
  - {name: abyss, mass: 1.0e308, shape: {type: sphere, radius: 0.1}, position: [0, 0, 10]}
)");
    const Result r = dir.run("run " + shellQuote(scene) + " --stats " + shellQuote(dir.out("s.json")));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(scene + ":5:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("body 'abyss': its initial energy is not finite (mass 1e+308 kg"), std::string::npos)
        << r.err;
    EXPECT_TRUE(dir.outputs().empty());
}

// A body that passes the ranges of core/model.h during a run stops it (a blow-up naming the step,
// the body and the quantity) before the next step's collision detection sees it: here one leaving
// the 1e6 m the scenes and trajectories keep to. Its trajectory rows are all readable.
TEST(BadInput, BodyLeavingTheRangeStopsTheRunNamingIt)
{
    const TestDir dir;
    const std::string scene = dir.write("away.yaml", R"(
simulation: {dt: 0.001, duration: 0.01, gravity: [0, 0, 0]}
bodies:
  - {name: probe, mass: 1, shape: {type: sphere, radius: 0.1}, position: [999995, 0, 0], velocity: [1.0e4, 0, 0]}
)");
    const Result r = dir.run("run " + shellQuote(scene) + " --trajectory " + shellQuote(dir.out("t.csv")));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_NE(r.err.find("simulation blew up at step 1"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("body 'probe' has a non-finite or runaway position (limits 1e+06 m from the origin"),
              std::string::npos)
        << r.err;
    EXPECT_NO_THROW(io::readTrajectory(dir.out("t.failed.csv")));
}

// scenes/README.md and README.md say the size limit of input files that the code enforces.
TEST(BadInput, DocumentsSayTheInputSizeLimit)
{
    const std::string limit = std::to_string(io::detail::cDefaultMaxInputBytes >> 20) + " MiB";
    for (const char* document : {"scenes/README.md", "README.md"})
    {
        const std::string text = readText(sourcePath(document));
        std::size_t at = 0;
        int mentions = 0;
        while ((at = text.find(" MiB", at + 1)) != std::string::npos)
        {
            const std::size_t start = text.find_last_of(' ', at - 1) + 1;
            const std::string said = text.substr(start, at + 4 - start);
            EXPECT_EQ(said, limit) << document;
            ++mentions;
        }
        EXPECT_GE(mentions, 1) << document;
    }
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
