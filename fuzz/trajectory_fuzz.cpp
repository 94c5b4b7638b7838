// fuzz/trajectory_fuzz.cpp: libFuzzer target for the trajectory reader as `check` and `render`
// use it: the rows, the robot flags and the settings of the header line.
#include "fuzz/fuzz_input.h"
#include "io/trajectory.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace frontier;
    const std::string path = fuzz::writeInput(data, size, "reference.csv");
    return fuzz::expectInputErrorOnly(
        [&]
        {
            const io::Trajectory trajectory = io::readTrajectory(path);
            io::urdfOptionsFrom(trajectory.metadata, path);
            io::readTrajectorySettings(trajectory, path);
            for (const io::TrajectoryRow& row : trajectory.rows)
            {
                row.state();
            }
        });
}
