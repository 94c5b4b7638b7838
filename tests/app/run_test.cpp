// tests/app/run_test.cpp: `frontier run`: trajectory rows, stats JSON against the printed summary
// and against the energy recomputed from the trajectory, recording options, a failed run's rows
// under .failed names, singular joints in run and check, a passive scene that gains energy,
// SIGINT/SIGTERM/SIGHUP during the run and while rendering, byte-identical repeated runs.
#include "app_test_util.h"
#include "core/state.h"
#include "io/scene.h"
#include "io/stats.h"
#include "io/trajectory.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <set>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace frontier::app::test
{
namespace
{

// The numbers of the summary line `run` prints (app/run_command.cpp printSummary).
struct Summary
{
    long steps = 0;
    int bodies = 0;
    int joints = 0;
    int constraintRows = 0;
    double maxJointErrorM = 0.0;
    double energyInitialJ = 0.0;
    double energyFinalJ = 0.0;
};

// The number that ends just before `suffix` in `text` (NaN when absent). No std::regex: GCC 12
// warns inside <regex> under the sanitizers, and the CI builds them with -Werror.
double numberBefore(const std::string& text, const std::string& suffix)
{
    const std::size_t end = text.find(suffix);
    if (end == std::string::npos)
    {
        return std::nan("");
    }
    std::size_t begin = end;
    while (begin > 0 && std::string("0123456789.eE+-").find(text[begin - 1]) != std::string::npos)
    {
        --begin;
    }
    return begin == end ? std::nan("") : std::strtod(text.substr(begin, end - begin).c_str(), nullptr);
}

// The number that starts just after `prefix` in `text` (NaN when absent).
double numberAfter(const std::string& text, const std::string& prefix)
{
    const std::size_t at = text.find(prefix);
    if (at == std::string::npos)
    {
        return std::nan("");
    }
    const char* begin = text.c_str() + at + prefix.size();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    return end == begin ? std::nan("") : value;
}

// "NAME: 1000 steps of 0.001 s (...) ...; 1 bodies, 1 joints, 5 constraint rows; largest joint error
// 3.12e-11 m, 0 rad; energy 14.715 J -> 14.7177 J (+0.0185%); ..."
bool parseSummary(const std::string& text, Summary& s)
{
    const double values[] = {numberBefore(text, " steps of "),
                             numberBefore(text, " bodies, "),
                             numberBefore(text, " joints, "),
                             numberBefore(text, " constraint rows; "),
                             numberAfter(text, "largest joint error "),
                             numberAfter(text, "; energy "),
                             numberBefore(text, " J (")};
    for (double v : values)
    {
        if (!std::isfinite(v))
        {
            return false;
        }
    }
    s.steps = std::lround(values[0]);
    s.bodies = static_cast<int>(std::lround(values[1]));
    s.joints = static_cast<int>(std::lround(values[2]));
    s.constraintRows = static_cast<int>(std::lround(values[3]));
    s.maxJointErrorM = values[4];
    s.energyInitialJ = values[5];
    s.energyFinalJ = values[6];
    return true;
}

bool namesAStep(const std::string& text)
{
    for (std::size_t at = text.find("step "); at != std::string::npos; at = text.find("step ", at + 1))
    {
        if (at + 5 < text.size() && std::isdigit(static_cast<unsigned char>(text[at + 5])))
        {
            return true;
        }
    }
    return false;
}

// |a - b| within `digits` significant digits of printing (%.{digits}g rounds to half a unit).
void expectPrintedAs(double exact, double printed, int digits, const char* what)
{
    const double tol = 0.5 * std::pow(10.0, 1 - digits) * std::abs(exact) * 1.0000001 + 1e-300;
    EXPECT_NEAR(printed, exact, tol) << what;
}

// m g z + 1/2 m v^2 + 1/2 w . I_W w of one trajectory row (gravity along -z, SI).
double energyOfRow(const core::Body& body, const io::TrajectoryRow& row, double g)
{
    const core::BodyState s = row.state();
    const core::Mat3 r = s.orientation_WB.normalized().toRotationMatrix();
    const core::Mat3 inertia = r * body.inertia_B * r.transpose();
    return body.mass * g * s.position_W.z() + 0.5 * body.mass * s.velocity_W.squaredNorm() +
           0.5 * s.angularVelocity_W.dot(inertia * s.angularVelocity_W);
}

TEST(Run, PendulumTrajectoryStatsAndSummaryAgree)
{
    const TestDir dir;
    const std::string traj = dir.out("pendulum.csv");
    const std::string stats = dir.out("pendulum.json");
    const Result r = dir.run("run scenes/pendulum.yaml --duration 1 --trajectory " + shellQuote(traj) +
                             " --stats " + shellQuote(stats));
    ASSERT_EQ(r.exitCode, 0) << r.err;

    const io::Trajectory t = io::readTrajectory(traj);
    ASSERT_EQ(t.rows.size(), 1001u);
    for (std::size_t k = 0; k < t.rows.size(); ++k)
    {
        ASSERT_EQ(t.rows[k].body, "bob");
        ASSERT_NEAR(t.rows[k].time, 1e-3 * static_cast<double>(k), 1e-12) << "row " << k;
    }
    EXPECT_EQ(t.rows.front().time, 0.0);
    EXPECT_NEAR(t.rows.back().time, 1.0, 1e-12);
    EXPECT_EQ(t.metadata.at("solver"), "linear");

    const io::RunStats s = io::readStats(stats);
    Summary printed;
    ASSERT_TRUE(parseSummary(r.out, printed)) << "summary line not found in:\n" << r.out;
    EXPECT_EQ(s.steps, 1000);
    EXPECT_EQ(s.bodies, 1);
    EXPECT_EQ(s.joints, 1);
    EXPECT_EQ(s.constraintRows, 5);
    EXPECT_TRUE(s.finite);
    EXPECT_EQ(s.solver, "linear");
    EXPECT_DOUBLE_EQ(s.dt, 0.001);
    EXPECT_EQ(printed.steps, s.steps);
    EXPECT_EQ(printed.bodies, s.bodies);
    EXPECT_EQ(printed.joints, s.joints);
    EXPECT_EQ(printed.constraintRows, s.constraintRows);
    expectPrintedAs(s.maxJointErrorM, printed.maxJointErrorM, 3, "max_joint_error_m");
    expectPrintedAs(s.energyInitialJ, printed.energyInitialJ, 6, "energy_initial_j");
    expectPrintedAs(s.energyFinalJ, printed.energyFinalJ, 6, "energy_final_j");
    EXPECT_LT(s.maxJointErrorM, 1e-6);
    // No contacts, loops or limits: no contact problem was solved.
    for (const char* key :
         {"contact_steps_carried", "contact_steps_reused", "contact_steps_built", "contact_sweeps"})
    {
        ASSERT_EQ(s.extra.count(key), 1u) << key;
        EXPECT_EQ(s.extra.at(key), 0.0) << key;
    }

    // The energies, recomputed from the first and last rows and the scene's mass properties.
    const core::Model model = io::loadScene(sourcePath("scenes/pendulum.yaml"));
    const double g = -model.simulation.gravity.z();
    const double e0 = energyOfRow(model.bodies[0], t.rows.front(), g);
    const double e1 = energyOfRow(model.bodies[0], t.rows.back(), g);
    EXPECT_NEAR(s.energyInitialJ, e0, 1e-12 * std::abs(e0));
    EXPECT_NEAR(s.energyFinalJ, e1, 1e-12 * std::abs(e0));
    EXPECT_NEAR(e0, 9.81 * 1.5, 1e-9); // at rest 1.5 m up
    // The bob has swung: kinetic energy in the last row.
    EXPECT_GT(t.rows.back().state().velocity_W.norm(), 0.5);
}

struct RowCase
{
    const char* args;
    std::size_t rows;
    double lastTime;
};

class RowCount : public ::testing::TestWithParam<RowCase>
{
};

TEST_P(RowCount, RecordingOptionsGiveTheRowsAsked)
{
    const TestDir dir;
    const std::string traj = dir.out("t.csv");
    const Result r = dir.run("run scenes/pendulum.yaml --quiet " + std::string(GetParam().args) +
                             " --trajectory " + shellQuote(traj));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const io::Trajectory t = io::readTrajectory(traj);
    EXPECT_EQ(t.rows.size(), GetParam().rows);
    ASSERT_FALSE(t.rows.empty());
    EXPECT_EQ(t.rows.front().time, 0.0);
    EXPECT_NEAR(t.rows.back().time, GetParam().lastTime, 1e-12);
    EXPECT_TRUE(r.out.empty()) << "--quiet printed: " << r.out;
}

INSTANTIATE_TEST_SUITE_P(Run, RowCount,
                         ::testing::Values(RowCase{"--duration 1 --record-every 10", 101, 1.0},
                                           RowCase{"--steps 5", 6, 0.005},
                                           RowCase{"--dt 0.002 --duration 1", 501, 1.0}));

// A ball under 2e6 m/s^2 passes the simulator's runaway speed within ~50 steps: exit 1, the
// message names the step and the body, and neither the trajectory, the joints and contacts files
// nor a temporary file remains.
// A run that blows up keeps its rows up to the failure under names that cannot pass for a complete
// run's (out.failed.csv), writes the stats with "completed": false and the message, names the
// files, and leaves no temporary file and nothing under the final names.
TEST(Run, FailedRunKeepsItsRowsUnderFailedNames)
{
    const TestDir dir;
    const std::string scene = dir.write("runaway.yaml", R"(
simulation: {dt: 0.001, duration: 1.0, gravity: [0, 0, -2.0e6]}
bodies:
  - {name: cannonball, mass: 1, shape: {type: sphere, radius: 0.1}, position: [0, 0, 1]}
  - {name: bob, mass: 1, shape: {type: sphere, radius: 0.1}, position: [1, 0, 1]}
joints:
  - {name: pivot, type: ball, parent: world, child: bob, anchor: [1, 0, 2]}
)");
    const std::string traj = dir.out("runaway.csv");
    const Result r = dir.run("run " + shellQuote(scene) + " --trajectory " + shellQuote(traj) + " --joints " +
                             shellQuote(dir.out("j.csv")) + " --contacts " + shellQuote(dir.out("c.csv")) +
                             " --stats " + shellQuote(dir.out("s.json")));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(namesAStep(r.err)) << r.err;
    EXPECT_NE(r.err.find("'cannonball'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("velocity"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(dir.out("runaway.failed.csv")), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(dir.out("s.json")), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(traj));
    const std::vector<std::string> names = dir.outputs();
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()),
              (std::set<std::string>{"runaway.failed.csv", "j.failed.csv", "c.failed.csv", "s.json"}));
    const io::Trajectory rows = io::readTrajectory(dir.out("runaway.failed.csv"));
    ASSERT_FALSE(rows.rows.empty());
    EXPECT_LT(rows.rows.back().time, 1.0) << "the rows end at the failure";
    const io::RunStats stats = io::readStats(dir.out("s.json"));
    EXPECT_FALSE(stats.completed);
    EXPECT_FALSE(stats.finite);
    EXPECT_NE(stats.failure.find("cannonball"), std::string::npos) << stats.failure;
}

// A joint that turns singular is a failure of the run, exit 1 in `run` and in `check` alike: a
// 1e-320 kg link cannot be pivoted (its hinge's rows degenerate at the first step). `run` keeps
// the stats with the message; `check` of a clean reference reports FAILED.
TEST(Run, SingularJointFailsTheRunInRunAndCheck)
{
    const TestDir dir;
    const std::string sceneText = R"(
simulation: {dt: 0.001, duration: 0.05}
bodies:
  - {name: a, mass: 1, shape: {type: sphere, radius: 0.1}, position: [1, 0, 1]}
  - {name: bob, mass: MASS, shape: {type: sphere, radius: 0.1}, position: [1, 0, 0.5]}
joints:
  - {name: pivot, type: ball, parent: world, child: a, anchor: [1, 0, 2]}
  - {name: hinge, type: revolute, parent: a, child: bob, anchor: [1, 0, 0.75], axis: [0, 1, 0]}
)";
    auto withMass = [&](const std::string& mass)
    {
        std::string text = sceneText;
        text.replace(text.find("MASS"), 4, mass);
        return text;
    };
    const std::string good = dir.write("good.yaml", withMass("1"));
    const std::string bad = dir.write("bad.yaml", withMass("1e-320"));
    const std::string ref = dir.out("ref.csv");
    ASSERT_EQ(dir.run("run " + shellQuote(good) + " --quiet --trajectory " + shellQuote(ref)).exitCode, 0);

    const Result run = dir.run("run " + shellQuote(bad) + " --stats " + shellQuote(dir.out("s.json")));
    EXPECT_EQ(run.exitCode, 1) << run.err;
    EXPECT_NE(run.err.find("'hinge'"), std::string::npos) << run.err;
    const io::RunStats stats = io::readStats(dir.out("s.json"));
    EXPECT_FALSE(stats.completed);
    EXPECT_TRUE(stats.finite);
    EXPECT_NE(stats.failure.find("'hinge'"), std::string::npos) << stats.failure;

    const Result check = dir.run("check " + shellQuote(bad) + " --quiet --reference " + shellQuote(ref));
    EXPECT_EQ(check.exitCode, 1) << check.out << check.err;
    EXPECT_NE(check.out.find("FAILED"), std::string::npos) << check.out;
    EXPECT_NE(check.out.find("'hinge'"), std::string::npos) << check.out;
}

// A passive scene cannot gain energy. The T-handle (one body spinning near its intermediate axis,
// no gravity) at dt 0.5 s with euler gains several times its energy: the summary warns, the stats
// list the warning and the rise; --strict fails the run (exit 1, rows under .failed names). With
// rattle at the scene's dt the energy holds: no warning.
TEST(Run, PassiveSceneThatGainsEnergyIsWarnedAndFailsWithStrict)
{
    const TestDir dir;
    const std::string stats = dir.out("s.json");
    const Result warned = dir.run("run scenes/stability/t_handle.yaml --dt 0.5 --integrator euler --stats " +
                                  shellQuote(stats));
    ASSERT_EQ(warned.exitCode, 0) << warned.err;
    EXPECT_NE(warned.out.find("Warning: the energy of this passive scene"), std::string::npos) << warned.out;
    io::RunStats s = io::readStats(stats);
    EXPECT_EQ(s.warnings.size(), 1u);
    EXPECT_GT(s.extra.at("energy_rise_fraction"), 1.0);
    EXPECT_TRUE(s.completed);

    const Result strict = dir.run("run scenes/stability/t_handle.yaml --dt 0.5 --integrator euler --strict "
                                  "--trajectory " +
                                  shellQuote(dir.out("t.csv")) + " --stats " + shellQuote(stats));
    EXPECT_EQ(strict.exitCode, 1) << strict.err;
    EXPECT_NE(strict.err.find("--strict"), std::string::npos) << strict.err;
    EXPECT_TRUE(std::filesystem::exists(dir.out("t.failed.csv")));
    EXPECT_FALSE(std::filesystem::exists(dir.out("t.csv")));
    s = io::readStats(stats);
    EXPECT_FALSE(s.completed);
    EXPECT_NE(s.failure.find("energy"), std::string::npos) << s.failure;

    const Result held =
        dir.run("run scenes/stability/t_handle.yaml --integrator rattle --duration 2 --strict --stats " +
                shellQuote(stats));
    EXPECT_EQ(held.exitCode, 0) << held.out << held.err;
    EXPECT_EQ(held.out.find("Warning"), std::string::npos) << held.out;
    s = io::readStats(stats);
    EXPECT_TRUE(s.warnings.empty());
    EXPECT_LT(s.extra.at("energy_rise_fraction"), 0.01);
}

// Files anywhere under out/ whose name holds ".tmp-" (io/atomic_file.h temporaries).
std::vector<std::string> temporaries(const TestDir& dir)
{
    std::vector<std::string> found;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path() / "out"))
    {
        if (entry.path().filename().string().find(".tmp-") != std::string::npos)
        {
            found.push_back(entry.path().string());
        }
    }
    return found;
}

// SIGINT, SIGTERM and SIGHUP stop a long run between steps: exit 128 + the signal, one line naming
// the signal, the time and the step; no temporary file left, nothing under the final names, the
// rows so far under .failed names and the stats with "completed": false.
TEST(Run, SignalStopsTheRunAndRemovesTemporaries)
{
    const std::pair<int, const char*> signals[] = {
        {SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGHUP, "SIGHUP"}};
    for (const auto& [signal, name] : signals)
    {
        const TestDir dir;
        const pid_t pid = spawnFrontier(dir, {"run", "scenes/pendulum.yaml", "--duration", "1e6", "--quiet",
                                              "--trajectory", dir.out("t.csv"), "--joints", dir.out("j.csv"),
                                              "--stats", dir.out("s.json")});
        ASSERT_GT(pid, 0);
        // The run has started (its handlers are installed) once its temporary files exist.
        const auto start = std::chrono::steady_clock::now();
        while (temporaries(dir).size() < 2 &&
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 60.0)
        {
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        ::kill(pid, signal);
        EXPECT_EQ(waitForExit(pid, 30.0), 128 + signal) << name;
        const std::string err = readText(dir.path() / "stderr.txt");
        EXPECT_EQ(err.rfind(std::string("frontier: interrupted by ") + name + " at t = ", 0), 0u) << err;
        EXPECT_NE(err.find("(step "), std::string::npos) << err;
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        EXPECT_TRUE(temporaries(dir).empty()) << temporaries(dir).front();
        const std::vector<std::string> names = dir.outputs();
        EXPECT_EQ(std::set<std::string>(names.begin(), names.end()),
                  (std::set<std::string>{"t.failed.csv", "j.failed.csv", "s.json"}))
            << name;
        const io::RunStats stats = io::readStats(dir.out("s.json"));
        EXPECT_FALSE(stats.completed);
        EXPECT_TRUE(stats.finite);
        EXPECT_GT(stats.steps, 0);
        EXPECT_LT(stats.steps, 1000000000L);
        EXPECT_EQ(io::readTrajectory(dir.out("t.failed.csv")).rows.size(),
                  static_cast<std::size_t>(stats.steps + 1));
    }
}

// A signal while the frames are written stops the renderers; the folder keeps its INCOMPLETE
// marker (written before the first frame, removed after the last), so it does not look complete.
TEST(Run, SignalWhileRenderingLeavesTheFramesFolderMarkedIncomplete)
{
    const TestDir dir;
    const std::string frames = dir.out("frames");
    const pid_t pid = spawnFrontier(dir, {"run", "scenes/pendulum.yaml", "--duration", "30", "--fps", "1000",
                                          "--jobs", "1", "--quiet", "--frames", frames});
    ASSERT_GT(pid, 0);
    const auto start = std::chrono::steady_clock::now();
    while (!std::filesystem::exists(frames + "/frame_00000.png") &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 60.0)
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(pid, SIGINT);
    EXPECT_EQ(waitForExit(pid, 60.0), 130);
    const std::string err = readText(dir.path() / "stderr.txt");
    EXPECT_NE(err.find("interrupted by SIGINT after "), std::string::npos) << err;
    EXPECT_TRUE(std::filesystem::exists(frames + "/INCOMPLETE"));
    EXPECT_FALSE(std::filesystem::exists(frames + "/frame_30000.png"));
    EXPECT_TRUE(temporaries(dir).empty());
}

// The stats count how each step's contact problem was solved: the five boxes touch from the first
// step, so every step took one of the three routes; the carried-over impulses hold on some (the
// stack at rest) and the first step must build its matrix.
TEST(Run, BoxStackStatsCountTheContactRoutes)
{
    const TestDir dir;
    const std::string stats = dir.out("stack.json");
    const Result r = dir.run("run scenes/box_stack.yaml --quiet --duration 0.5 --stats " + shellQuote(stats));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const io::RunStats s = io::readStats(stats);
    const double carried = s.extra.at("contact_steps_carried");
    const double reused = s.extra.at("contact_steps_reused");
    const double built = s.extra.at("contact_steps_built");
    EXPECT_EQ(carried + reused + built, static_cast<double>(s.steps));
    EXPECT_GT(carried, 0.0);
    EXPECT_GE(built, 1.0);
    EXPECT_GE(s.extra.at("contact_sweeps"), built);
}

// The same run twice, with contacts: the same bytes.
TEST(Run, FallingDollTwiceGivesByteIdenticalTrajectories)
{
    const TestDir dir;
    const std::string a = dir.out("a.csv");
    const std::string b = dir.out("b.csv");
    const Result ra =
        dir.run("run scenes/falling_doll.yaml --quiet --duration 0.5 --trajectory " + shellQuote(a));
    const Result rb =
        dir.run("run scenes/falling_doll.yaml --quiet --duration 0.5 --trajectory " + shellQuote(b));
    ASSERT_EQ(ra.exitCode, 0) << ra.err;
    ASSERT_EQ(rb.exitCode, 0) << rb.err;
    const std::string textA = readText(a);
    const std::string textB = readText(b);
    EXPECT_EQ(io::readTrajectory(a).rows.size(), 501u * 15u);
    EXPECT_TRUE(textA == textB) << "the trajectories differ (" << textA.size() << " and " << textB.size()
                                << " bytes)";
}

} // namespace
} // namespace frontier::app::test
