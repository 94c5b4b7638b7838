// io/urdf_model.h: URDF models (urdfdom) turned into bodies and joints (private to io/).
#pragma once

#include "core/model.h"
#include "io/scene.h"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>

namespace frontier::io::detail
{

class PackagePaths;

// How a URDF is placed in a scene.
struct UrdfPlacement
{
    core::Vec3 position = core::Vec3::Zero();        // of the root link frame, world (m)
    core::Quat orientation = core::Quat::Identity(); // of the root link frame
    std::string prefix;                              // prepended to every body and joint name
    bool selfCollision = true;                       // false: every link goes into one collision group
    bool fixedRoot = false; // true: the root link is welded to the world (a static body) where it is
    bool freeRoot = false;  // true: a root link named 'world' is dropped; what it welded floats
    // The starting pose: URDF joint name -> its position (rad or m, the URDF's convention), for
    // revolute, continuous and prismatic joints, within their limits. Others start at 0 (or at
    // the nearest limit when 0 lies outside them).
    std::map<std::string, double> jointPositions;
};

// A jointPositions entry the URDF cannot take (no such joint, a fixed joint, outside the limits):
// the scene reader names the line of the entry, the CLI the flag.
class JointPositionError : public std::runtime_error
{
  public:
    JointPositionError(std::string joint, const std::string& message)
        : std::runtime_error(message), mJoint(std::move(joint))
    {
    }
    const std::string& joint() const { return mJoint; }

  private:
    std::string mJoint;
};

// A robot model read from its file (URDF, MJCF): its links as bodies (links joined by fixed joints
// welded into one) and its moving joints, body indices local to `model` (joints to the world use
// core::cWorld); model.name is the robot name.
struct ModelFragment
{
    core::Model model;
    RobotReport report;
    std::vector<std::string> warnings; // diagnostics, "FILE:LINE:COL: warning: ..."
};

// Numbers with 6 significant digits ("x, y, z" for a vector), for messages and reports.
std::string formatNumber(double value);
std::string formatVector(const core::Vec3& v);

// Throws InputError naming the URDF file and, where it can be found, the line.
ModelFragment loadUrdfFragment(const std::string& path, const UrdfPlacement& placement,
                               const PackagePaths& packages);

// Placing a robot (io/urdf_scene.cpp). The lowest point of the model's collision shapes along z
// (m; +infinity when it has none); every body (and every joint anchor held by the world) moved by
// `offset` (m); whether some body is static or some joint holds a body to the world.
double lowestPoint(const core::Model& model);
void translate(core::Model& model, const core::Vec3& offset);
bool heldByWorld(const core::Model& model);

// A robot file alone (a bare URDF, an SDF <model>): `model` (robot's bodies only, robot.name set)
// placed and given a static floor. Held by the world (heldByWorld), it stays where the file puts it
// (placement `heldBy`), the floor at z = 0 or under its lowest collision point if that is lower;
// free-floating, it is moved so that its lowest collision point is dropHeight (default 0) above the
// floor z = 0. fileKind names the file in messages ("URDF"). Then checkStartingState.
void placeOnFloor(core::Model& model, const std::string& path, std::optional<double> dropHeight,
                  const std::string& heldBy, const std::string& fileKind, RobotReport& robot,
                  std::vector<std::string>& warnings);
// Throws InputError(path, 0, 0, ...) naming a body whose starting state is out of range
// (core::startingStateDefect).
void checkStartingState(const core::Model& model, const std::string& path);

// A URDF alone: the robot on a static floor with the default simulation settings. A free-floating
// robot is moved so that its lowest collision point is options.dropHeight (default 0) above the
// floor z = 0; a fixed one stays where the URDF puts it, the floor at z = 0 or under its lowest
// collision point if that is lower.
core::Model loadUrdfScene(const std::string& path, const UrdfOptions& options, LoadReport* report);

// The end of a bare robot file's load: the fragment's report and warnings moved into `report` (when
// given).
void reportRobot(ModelFragment& fragment, LoadReport* report);

} // namespace frontier::io::detail
