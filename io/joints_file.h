// io/joints_file.h: the joints CSV of a run (`frontier run --joints`, docs/files.md), long format.
//
// Format (io/csv_output.h: comment line, header, 17 significant digits, atomic):
//   # frontier joints: scene=<path> dt=<s> ... (the trajectory's key=value pairs)
//   time,joint,coordinate,position,velocity,effort,fx,fy,fz,tx,ty,tz
//   0,pivot,angle,0,0,,,,,,,
//   0.001,pivot,angle,8.4872219891360952e-06,0.0084872219891360956,0,-4.2436109945682476,0,2.4598501498502334,0,0,0
// Per recorded state, one row per joint coordinate (core::jointCoordinates order): `angle` (rad,
// rad/s) of revolute joints, `slide` (m, m/s) of prismatic ones, both for cylindrical ones; a
// joint without a coordinate (ball, nail, angle, fixed) has one row `none` with position and
// velocity empty. position: Joint::initialPosition + the coordinate from the start pose (the model
// file's own convention); velocity: its rate. effort: the joint's actuator's force or torque (N or
// N m), 0 without one. fx..tz: the force (N) and the torque about the joint's anchor on the child
// (N m) that the joint applied to its child body over the step that ended at `time` (its impulse
// divided by dt, core::Simulator::jointChildImpulses; world frame; the parent received the
// opposite), the same on each row of a joint. At time 0 no step has been taken: effort and fx..tz
// are empty there. Empty fields read as NaN (pandas.read_csv(f, comment='#')).
#pragma once

#include "core/model.h"
#include "core/state.h"
#include "io/csv_output.h"

#include <array>
#include <span>
#include <string>

namespace frontier::io
{

inline constexpr const char* cJointsHeader =
    "time,joint,coordinate,position,velocity,effort,fx,fy,fz,tx,ty,tz";

// What one step did at one joint.
struct JointStepLoad
{
    core::Vec3 force_W = core::Vec3::Zero();  // N, on the child
    core::Vec3 torque_W = core::Vec3::Zero(); // N m, on the child, about the joint's anchor on it
    std::array<double, 2> effort{};           // per coordinate (jointCoordinates order), N or N m
};

class JointsWriter : public CsvWriter
{
  public:
    // Creates PATH.tmp-XXXXXX next to `path` and writes the comment and header lines; without
    // commit() (io/csv_output.h) the temporary file is removed. Throws OutputError
    // (io/atomic_file.h).
    JointsWriter(const std::string& path, const FileMetadata& metadata);

    // The rows at state.time. `loads`: per joint (Model::joints order), of the step that produced
    // `state`; empty for the initial state.
    void writeState(const core::Model& model, const core::State& state, std::span<const JointStepLoad> loads);
};

} // namespace frontier::io
