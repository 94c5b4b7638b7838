// tests/app/run_test.cpp: `frontier run`: trajectory rows, stats JSON against the printed summary
// and against the energy recomputed from the trajectory, recording options, no trajectory left
// behind by a failed run, byte-identical repeated runs.
#include "app_test_util.h"
#include "core/state.h"
#include "io/scene.h"
#include "io/stats.h"
#include "io/trajectory.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>

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
TEST(Run, FailedRunLeavesNoTrajectory)
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
                             shellQuote(dir.out("j.csv")) + " --contacts " + shellQuote(dir.out("c.csv")));
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_TRUE(namesAStep(r.err)) << r.err;
    EXPECT_NE(r.err.find("'cannonball'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("velocity"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(traj));
    EXPECT_TRUE(dir.outputs().empty()) << "left behind: " << dir.outputs().front();
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
