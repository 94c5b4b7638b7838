// io/trajectory.h: the trajectory CSV (PRODUCT.md "Files"): write atomically, read back exactly.
//
// Format:
//   # frontier trajectory: scene=<path> dt=<s> solver=<name> ... (key=value pairs)
//   time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
//   0,pelvis,0,0,1,1,0,0,0,0,0,0,0,0,0
// One row per moving body per recorded step; numbers with 17 significant digits, so they read back
// bit for bit. In metadata values, '%', ' ', '=', ',' and control characters are written as %XX.
#pragma once

#include "core/model.h"
#include "core/state.h"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace frontier::io
{

class AtomicFile;

// Ordered key=value pairs of the comment line.
using TrajectoryMetadata = std::vector<std::pair<std::string, std::string>>;

// The standard pairs: scene dt solver pgs_iterations integrator steps record_every duration.
TrajectoryMetadata makeTrajectoryMetadata(const std::string& scenePath,
                                          const core::SimulationSettings& settings, long steps,
                                          int recordEvery);

inline constexpr const char* cTrajectoryHeader = "time,body,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";

class TrajectoryWriter
{
  public:
    // Creates PATH.tmp-XXXXXX next to `path` and writes the comment and header lines.
    // Throws OutputError (io/atomic_file.h) when the file cannot be created.
    TrajectoryWriter(const std::string& path, const TrajectoryMetadata& metadata);
    ~TrajectoryWriter(); // without commit(): removes the temporary file
    TrajectoryWriter(const TrajectoryWriter&) = delete;
    TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;

    // One row per non-static body at state.time.
    void writeState(const core::Model& model, const core::State& state);
    // Flushes and renames the file into place (atomic); throws OutputError.
    void commit();
    long rowsWritten() const { return mRows; }

  private:
    std::unique_ptr<AtomicFile> mFile;
    long mRows = 0;
};

struct TrajectoryRow
{
    double time = 0.0; // s
    std::string body;
    // px py pz (m), qw qx qy qz, vx vy vz (m/s), wx wy wz (rad/s), world frame
    std::array<double, 13> values{};

    core::BodyState state() const;
};

struct Trajectory
{
    std::map<std::string, std::string> metadata; // from the "# frontier trajectory:" line (decoded)
    std::vector<TrajectoryRow> rows;
};

// Throws InputError (file, line, column of the offending field) on malformed content: a missing
// or misnamed header column, a wrong number of fields, an unreadable number.
Trajectory readTrajectory(const std::string& path);

} // namespace frontier::io
