// tests/io/trajectory_test.cpp: trajectory CSV round trip (bit-exact), atomic writing, errors.
#include "io/atomic_file.h"
#include "io/trajectory.h"
#include "io_test_util.h"

#include <bit>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <sys/stat.h>

namespace frontier::io::test
{
namespace
{

core::Model twoBodyModel()
{
    core::Model model;
    core::Body a;
    a.name = "a";
    a.mass = 1;
    core::Body floor;
    floor.name = "floor";
    floor.isStatic = true;
    core::Body b;
    b.name = "b b"; // spaces are fine in CSV
    b.mass = 1;
    model.bodies = {a, floor, b};
    return model;
}

TEST(Trajectory, RoundTripIsBitExact)
{
    TempDir dir;
    const core::Model model = twoBodyModel();
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> uniform(-1e3, 1e3);
    std::vector<core::State> states;
    for (int step = 0; step < 5; ++step)
    {
        core::State s = core::initialState(model);
        s.time = step * 0.1; // 0.30000000000000004 and friends
        for (auto& body : s.bodies)
        {
            // One draw per statement (argument order is the compiler's), in the order g++ took them.
            const double py = uniform(rng), px = uniform(rng);
            body.position_W = core::Vec3(px, py * 1e-300, std::nextafter(1.0, 2.0));
            const double qz = uniform(rng), qy = uniform(rng), qx = uniform(rng), qw = uniform(rng);
            body.orientation_WB = core::Quat(qw, qx, qy, qz).normalized();
            body.velocity_W = core::Vec3(uniform(rng), -0.0, 5e-324);
            body.angularVelocity_W = core::Vec3(std::numeric_limits<double>::max(), 1.0 / 3.0, uniform(rng));
        }
        states.push_back(s);
    }
    core::SimulationSettings settings;
    settings.dt = 0.1;
    const std::string path = dir.file("run.csv");
    TrajectoryWriter writer(path, makeTrajectoryMetadata("scenes/my scene=1.yaml", settings, 4, 1));
    for (const core::State& s : states)
    {
        writer.writeState(model, s);
    }
    EXPECT_EQ(writer.rowsWritten(), 10);
    writer.commit();

    const Trajectory t = readTrajectory(path);
    EXPECT_EQ(t.metadata.at("scene"), "scenes/my scene=1.yaml");
    EXPECT_EQ(t.metadata.at("dt"), "0.10000000000000001");
    EXPECT_EQ(t.metadata.at("solver"), "linear");
    EXPECT_EQ(t.metadata.at("pgs_iterations"), "20");
    EXPECT_EQ(t.metadata.at("integrator"), "euler");
    EXPECT_EQ(t.metadata.at("steps"), "4");
    EXPECT_EQ(t.metadata.at("record_every"), "1");
    EXPECT_EQ(t.metadata.count("duration"), 1u);
    ASSERT_EQ(t.rows.size(), 10u);
    for (std::size_t k = 0; k < states.size(); ++k)
    {
        for (std::size_t j = 0; j < 2; ++j)
        {
            const TrajectoryRow& row = t.rows[2 * k + j];
            const std::size_t bodyIndex = j == 0 ? 0 : 2;
            EXPECT_EQ(row.body, model.bodies[bodyIndex].name);
            EXPECT_EQ(std::bit_cast<std::uint64_t>(row.time), std::bit_cast<std::uint64_t>(states[k].time));
            const core::BodyState expected = states[k].bodies[bodyIndex];
            const core::BodyState got = row.state();
            const double e[13] = {
                expected.position_W.x(),       expected.position_W.y(),        expected.position_W.z(),
                expected.orientation_WB.w(),   expected.orientation_WB.x(),    expected.orientation_WB.y(),
                expected.orientation_WB.z(),   expected.velocity_W.x(),        expected.velocity_W.y(),
                expected.velocity_W.z(),       expected.angularVelocity_W.x(), expected.angularVelocity_W.y(),
                expected.angularVelocity_W.z()};
            for (std::size_t i = 0; i < 13; ++i)
            {
                EXPECT_EQ(std::bit_cast<std::uint64_t>(row.values[i]), std::bit_cast<std::uint64_t>(e[i]))
                    << "row " << 2 * k + j << " value " << i << ": " << row.values[i] << " vs " << e[i];
            }
            EXPECT_EQ(got.position_W, expected.position_W);
        }
    }
}

// The settings and robot flags the header carries read back as written; a missing pair or an
// unreadable value is an error on line 1.
TEST(Trajectory, HeaderSettingsReadBack)
{
    TempDir dir;
    const core::Model model = twoBodyModel();
    core::SimulationSettings settings;
    settings.dt = 1.0 / 3.0;
    settings.solver = core::SolverKind::Pgs;
    settings.pgsIterations = 37;
    settings.integrator = core::IntegratorKind::Rattle;
    UrdfOptions urdf;
    urdf.fixedBase = true;
    urdf.dropHeight = 0.25;
    urdf.selfCollision = false;
    urdf.packagePaths = {"/a", "b=/c"};
    TrajectoryMetadata metadata = makeTrajectoryMetadata("s.yaml", settings, 12, 3);
    addUrdfOptions(metadata, urdf);
    const std::string path = dir.file("run.csv");
    TrajectoryWriter writer(path, metadata);
    writer.writeState(model, core::initialState(model));
    writer.commit();

    Trajectory t = readTrajectory(path);
    const TrajectorySettings read = readTrajectorySettings(t, path);
    EXPECT_EQ(read.simulation.dt, settings.dt);
    EXPECT_EQ(read.simulation.solver, core::SolverKind::Pgs);
    EXPECT_EQ(read.simulation.pgsIterations, 37);
    EXPECT_EQ(read.simulation.integrator, core::IntegratorKind::Rattle);
    EXPECT_EQ(read.steps, 12);
    EXPECT_EQ(read.recordEvery, 3);
    const UrdfOptions back = urdfOptionsFrom(t.metadata, path);
    EXPECT_TRUE(back.fixedBase);
    EXPECT_FALSE(back.freeBase);
    EXPECT_EQ(back.dropHeight, 0.25);
    EXPECT_EQ(back.selfCollision, false);
    EXPECT_EQ(back.packagePaths, urdf.packagePaths);

    t.metadata.erase("integrator");
    EXPECT_THROW(readTrajectorySettings(t, path), InputError);
    t.metadata["integrator"] = "verlet";
    EXPECT_THROW(readTrajectorySettings(t, path), InputError);
    t.metadata["integrator"] = "euler";
    t.metadata["record_every"] = "0";
    EXPECT_THROW(readTrajectorySettings(t, path), InputError);
    t.metadata["drop_height"] = "high";
    EXPECT_THROW(urdfOptionsFrom(t.metadata, path), InputError);
}

TEST(Trajectory, FileStartsWithCommentAndHeader)
{
    TempDir dir;
    const std::string path = dir.file("run.csv");
    {
        TrajectoryWriter writer(path, {{"scene", "a.yaml"}, {"dt", "0.001"}});
        writer.commit();
    }
    std::ifstream in(path);
    std::string first, second;
    std::getline(in, first);
    std::getline(in, second);
    EXPECT_EQ(first, "# frontier trajectory: scene=a.yaml dt=0.001");
    EXPECT_EQ(second, "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
}

TEST(Trajectory, UnfinishedWriterLeavesNoFile)
{
    TempDir dir;
    const std::string path = dir.file("run.csv");
    {
        const core::Model model = twoBodyModel();
        TrajectoryWriter writer(path, {});
        writer.writeState(model, core::initialState(model));
        EXPECT_EQ(filesIn(dir.path()), 1u); // the temporary file
        EXPECT_FALSE(std::filesystem::exists(path));
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_EQ(filesIn(dir.path()), 0u);
}

TEST(Trajectory, CommitReplacesAnExistingFile)
{
    TempDir dir;
    const std::string path = dir.write("run.csv", "old contents\n");
    TrajectoryWriter writer(path, {});
    EXPECT_EQ(readTextOf(path), "old contents\n");
    writer.commit();
    EXPECT_EQ(readTrajectory(path).rows.size(), 0u);
    EXPECT_EQ(filesIn(dir.path()), 1u);
}

TEST(Trajectory, UnwritableDirectoryIsAnOutputError)
{
    EXPECT_THROW(TrajectoryWriter("/nonexistent/dir/run.csv", {}), OutputError);
}

InputError trajectoryError(const TempDir& dir, const std::string& content)
{
    const std::string path = dir.write("t.csv", content);
    return captureInputError([&] { readTrajectory(path); });
}

TEST(Trajectory, ReadErrorsAreLocated)
{
    TempDir dir;
    const std::string header = "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
    EXPECT_INPUT_ERROR_AT(
        trajectoryError(dir, "# frontier trajectory: dt=1\ntime,body,px,py,pz,qw,qx,qy,qz\n"),
        dir.file("t.csv"), 2, 31, "missing column 'vx' in the header");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, "time,body,px,py,pz,qx,qw,qy,qz,vx,vy,vz,wx,wy,wz\n"),
                          dir.file("t.csv"), 1, 20, "expected column 'qw' in the header, got 'qx'");
    EXPECT_INPUT_ERROR_AT(
        trajectoryError(dir, header + "0,a,1,2,3,1,0,0,0,0,0,0,0,0,0\n0,a,1,2,3,1,0,0,0,0,0,0,0,0\n"),
        dir.file("t.csv"), 3, 28, "expected 15 fields, got 14");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2,3,1,0,0,0,0,0,0,0,0,0,9\n"),
                          dir.file("t.csv"), 2, 31, "expected 15 fields, got 16");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2.5x,3,1,0,0,0,0,0,0,0,0,0\n"),
                          dir.file("t.csv"), 2, 7, "expected a finite number for 'py', got '2.5x'");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,,3,1,0,0,0,0,0,0,0,0,0\n"), dir.file("t.csv"),
                          2, 7, "expected a finite number for 'py', got ''");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, "# just a comment\n"), dir.file("t.csv"), 1, 0,
                          "no header line");
    EXPECT_INPUT_ERROR_AT(captureInputError([] { readTrajectory("/nonexistent/t.csv"); }),
                          "/nonexistent/t.csv", 0, 0, "cannot open file");
}

// Values no run writes are located errors: `check` and `render` would otherwise compare against or
// draw garbage (a NaN passes every tolerance test as false, a zero quaternion has no rotation).
TEST(Trajectory, CorruptRowsAreLocated)
{
    TempDir dir;
    const std::string file = dir.file("t.csv");
    const std::string header = "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
    const std::string good = "0,a,1,2,3,1,0,0,0,0,0,0,0,0,0\n";
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,nan,3,1,0,0,0,0,0,0,0,0,0\n"), file, 2, 7,
                          "expected a finite number for 'py', got 'nan'");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2,3,1,0,0,0,0,0,0,0,0,-inf\n"), file, 2, 29,
                          "expected a finite number for 'wz', got '-inf'");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2,3,1e999,0,0,0,0,0,0,0,0,0\n"), file, 2, 11,
                          "expected a finite number for 'qw', got '1e999'");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2,3,0,0,0,0,0,0,0,0,0,0\n"), file, 2, 11,
                          "orientation quaternion has norm 0; expected a unit quaternion");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2,3,1.00001,0,0,0,0,0,0,0,0,0\n"), file, 2, 11,
                          "orientation quaternion has norm 1.00001");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "0,a,1,2,2e6,1,0,0,0,0,0,0,0,0,0\n"), file, 2, 5,
                          "position (1, 2, 2000000) m is farther than 1000000 m from the origin");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + "1,a,1,2,3,1,0,0,0,0,0,0,0,0,0\n" + good), file, 3, 1,
                          "time 0 s is earlier than the row before (1 s)");
    EXPECT_INPUT_ERROR_AT(trajectoryError(dir, header + good + good), file, 3, 1,
                          "body 'a' has a second row at time 0 s");
    // Several bodies share a time; within 1e-6 of norm 1 is a unit quaternion.
    const std::string path = dir.write("ok.csv", header + good + "0,b,1,2,3,0.9999995,0,0,0,0,0,0,0,0,0\n" +
                                                     "0.5,a," + good.substr(4));
    EXPECT_EQ(readTrajectory(path).rows.size(), 3u);
}

// The settings of the comment line (what `check` re-runs with) are checked as they are read.
TEST(Trajectory, CorruptHeaderSettingsAreLocated)
{
    TempDir dir;
    const std::string file = dir.file("t.csv");
    const std::string columns = "\ntime,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
    const auto headerError = [&](const std::string& pairs)
    { return trajectoryError(dir, "# frontier trajectory: scene=s.yaml " + pairs + columns); };
    // The column is that of the value (the comment prefix is 23 characters, "scene=s.yaml " 13).
    EXPECT_INPUT_ERROR_AT(
        headerError("pgs_iterations=0"), file, 1, 52,
        "'pgs_iterations' in the trajectory comment is '0'; expected a whole number from 1 to "
        "1000000");
    EXPECT_INPUT_ERROR_AT(headerError("pgs_iterations=2.5"), file, 1, 52, "expected a whole number from 1");
    EXPECT_INPUT_ERROR_AT(headerError("pgs_iterations=99999999999999999999"), file, 1, 52,
                          "expected a whole number from 1");
    EXPECT_INPUT_ERROR_AT(headerError("dt=0.01 steps=1.5"), file, 1, 51,
                          "'steps' in the trajectory comment is '1.5'; expected a whole number of steps");
    EXPECT_INPUT_ERROR_AT(headerError("dt=0"), file, 1, 40,
                          "'dt' in the trajectory comment is '0'; expected a positive");
    EXPECT_INPUT_ERROR_AT(headerError("dt=nan"), file, 1, 40, "expected a positive number of seconds");
    EXPECT_INPUT_ERROR_AT(headerError("record_every=0"), file, 1, 50,
                          "expected a whole number of steps >= 1");
    // A trajectory without the settings reads, but cannot be checked against: the comment line is named.
    const std::string blank = dir.write("blank.csv", "\n# frontier trajectory: scene=s.yaml" + columns);
    EXPECT_INPUT_ERROR_AT(captureInputError([&] { readTrajectorySettings(readTrajectory(blank), blank); }),
                          blank, 2, 0, "the reference's header line has no 'dt'");
}

// Like every input file, a trajectory is read only when it is a regular file.
TEST(Trajectory, OnlyRegularFilesAreRead)
{
    TempDir dir;
    const std::string fifo = dir.file("pipe.csv");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_INPUT_ERROR_AT(captureInputError([&] { readTrajectory(fifo); }), fifo, 0, 0,
                          "is not a regular file (a FIFO), expected a trajectory file");
    EXPECT_INPUT_ERROR_AT(captureInputError([] { readTrajectory("/dev/zero"); }), "/dev/zero", 0, 0,
                          "is not a regular file (a device), expected a trajectory file");
}

} // namespace
} // namespace frontier::io::test
