// io/trajectory.h: the trajectory CSV (docs/files.md): write atomically, read back exactly.
//
// Format:
//   # frontier trajectory: scene=<path> dt=<s> solver=<name> ... (key=value pairs)
//   time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
//   0,pelvis,0,0,1,1,0,0,0,0,0,0,0,0,0
// One row per moving body per recorded step; numbers with 17 significant digits, so they read back
// bit for bit. In metadata values, '%', ' ', '=', ',' and control characters are written as %XX
// (io/csv_output.h: what the trajectory, joints and contacts files share).
#pragma once

#include "core/model.h"
#include "core/state.h"
#include "io/csv_output.h"
#include "io/scene.h"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace frontier::io
{

// Ordered key=value pairs of the comment line (also of the joints and contacts files of a run).
using TrajectoryMetadata = FileMetadata;

// The standard pairs: scene dt solver pgs_iterations integrator steps record_every duration.
TrajectoryMetadata makeTrajectoryMetadata(const std::string& scenePath,
                                          const core::SimulationSettings& settings, long steps,
                                          int recordEvery);

// The contact tolerance flags given (contact_tolerance, contact_relative_tolerance), so `check`
// solves contacts as the run did; readTrajectorySettings reads them back.
void addContactTolerances(TrajectoryMetadata& metadata, const core::ContactTolerances& contact);

// The robot flags as key=value pairs of the header (only those given), so `check` and `render`
// load the scene as the run did (urdfOptionsFrom reads them back).
void addUrdfOptions(TrajectoryMetadata& metadata, const UrdfOptions& options);

inline constexpr const char* cTrajectoryHeader = "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

class TrajectoryWriter : public CsvWriter
{
  public:
    // Creates PATH.tmp-XXXXXX next to `path` and writes the comment and header lines; without
    // commit() (io/csv_output.h) the temporary file is removed. Throws OutputError
    // (io/atomic_file.h) when the file cannot be created.
    TrajectoryWriter(const std::string& path, const TrajectoryMetadata& metadata);

    // One row per non-static body at state.time.
    void writeState(const core::Model& model, const core::State& state);
};

struct TrajectoryRow
{
    double time = 0.0; // s
    std::string body;
    // px py pz (m), qw qx qy qz, vx vy vz (m/s), wx wy wz (rad/s), world frame
    std::array<double, 13> values{};
    int line = 0; // 1-based line in the file it was read from (0 when not read from a file)

    core::BodyState state() const;
};

struct Trajectory
{
    std::map<std::string, std::string> metadata; // from the "# frontier trajectory:" line (decoded)
    int metadataLine = 1;                        // that line's number (1-based)
    std::vector<TrajectoryRow> rows;
};

// Throws InputError (file, line, column of the offending field) on malformed content: a missing
// or misnamed header column, a wrong number of fields, a field that is not a finite number, a
// position farther than 1e6 m from the origin, an orientation quaternion whose norm is not 1
// (within 1e-6), a time earlier than the row before or not after the same body's previous one;
// and in the comment line a dt that is not positive, or a pgs_iterations (1 to 1e6), steps or
// record_every (>= 1) that is not a whole number in range.
Trajectory readTrajectory(const std::string& path);

// The settings a trajectory was recorded with, read back from its header line (the pairs
// makeTrajectoryMetadata writes).
struct TrajectorySettings
{
    core::SimulationSettings simulation; // dt, solver, pgsIterations, integrator; the rest default
    long steps = 0;                      // steps of the run
    int recordEvery = 1;                 // a row block every recordEvery steps
    core::ContactTolerances contact;     // the run's contact tolerance flags (absent: the scene's)
};

// Throws InputError (path, the comment line) when a pair is missing or its value cannot be read.
TrajectorySettings readTrajectorySettings(const Trajectory& trajectory, const std::string& path);

// The robot flags addUrdfOptions wrote (absent ones keep UrdfOptions' defaults). Throws InputError
// naming path when a value cannot be read.
UrdfOptions urdfOptionsFrom(const std::map<std::string, std::string>& metadata, const std::string& path);

} // namespace frontier::io
