// io/scene.h: public API of scene loading (YAML scenes with yaml-cpp, URDF models with urdfdom).
#pragma once

#include "core/model.h"
#include "io/input_digest.h"

#include <array>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace frontier::io
{

// Bad input: names the file, line and column (1-based, 0 when unknown) and what was expected.
// what() is the full message "FILE:LINE:COL: error: TEXT".
class InputError : public std::runtime_error
{
  public:
    InputError(std::string file, int line, int column, const std::string& message);
    const std::string& file() const { return mFile; }
    int line() const { return mLine; }
    int column() const { return mColumn; }
    // The text without the location prefix.
    const std::string& message() const { return mMessage; }

  private:
    std::string mFile;
    std::string mMessage;
    int mLine;
    int mColumn;
};

// How URDF models are read and placed: the robot flags of `frontier run` (README "Robots").
struct UrdfOptions
{
    // --package-path entries (a package, a folder of packages, or NAME=DIR), searched before
    // ROS_PACKAGE_PATH for package:// and model:// URIs.
    std::vector<std::string> packagePaths;
    // A bare .urdf only (a scene places its models itself):
    bool fixedBase = false;           // weld the root link to the world where it is
    bool freeBase = false;            // let the root float even if the URDF welds it to a 'world' link
    std::optional<double> dropHeight; // m: lowest collision point this high above the floor (default 0)
    // Joint name -> starting position (rad or m, the URDF's convention; --joint-position NAME=VALUE).
    std::map<std::string, double> jointPositions;
    // Every URDF: overrides the scene's self_collision (default on).
    std::optional<bool> selfCollision;
    // Every URDF: a position servo on each joint coordinate without an actuator, holding it where
    // it starts (--hold; a scene model's `hold: true`; io/hold_servos.h).
    bool hold = false;
    // A bare MJCF file only: the <key name="..."> whose qpos, qvel and ctrl start it (--keyframe).
    std::optional<std::string> keyframe;
};

// What loading did to a scene's robots beyond reading them (`frontier info` shows it).
struct RobotReport
{
    std::string name;   // the robot's bodies carry this prefix (bare URDF: none)
    std::string prefix; // prepended to its link and joint names
    std::string file;
    int links = 0;
    std::vector<std::pair<std::string, std::string>> welded;   // link -> the body it was welded into
    std::vector<std::string> repaired;                         // inertias replaced, and why
    std::string placement;                                     // where it was put and how it is held
    std::vector<std::pair<std::string, std::string>> excluded; // body pairs that overlap at the start
};
// A scene's `reference:` for `frontier sweep`: one body's positions that none of the simulator's
// methods made (measured, or from another program), as a CSV of rows t,x,y,z (study::readReferenceCsv).
struct SceneReference
{
    std::string csvPath; // resolved against the scene's folder
    std::string body;    // a body of the scene (checked when loading)
};

// A scene's `stability:`: what the stability suite (`frontier stability`, docs/stability.md)
// checks in it beyond what it checks everywhere (blow-up, joints apart, a singular joint,
// tunnelling). A run that breaks one of these fails.
struct StabilityJointCheck
{
    int joint = 0; // index into Model::joints: a revolute joint
    // rad: the angle never further than this from the target of the joint's position servo.
    std::optional<double> maxTrackingError;
    // rad, the model file's convention (as limits and servo targets): the angle stays within.
    std::optional<std::array<double, 2>> range;
    // rad: the angle's magnitude exceeds this at some time (a joint meant to pass +-pi does).
    std::optional<double> reach;
};
struct SceneStabilityCriteria
{
    std::optional<double> maxSpeed;      // m/s: of every moving body's centre of mass
    std::optional<double> maxEnergyRise; // J: the total energy above its initial value
    std::vector<StabilityJointCheck> joints;
};

struct LoadReport
{
    std::vector<std::string> warnings; // "FILE:LINE:COL: warning: TEXT"
    std::vector<RobotReport> robots;
    std::optional<SceneReference> reference;         // the scene's `reference:`, when it has one
    std::optional<SceneStabilityCriteria> stability; // the scene's `stability:`, when it has one
    // Every file the load read (the scene file, URDFs, meshes and the files they name, CSV tables,
    // ...), each once, in the order first read, with the SHA-256 of its bytes (io/input_digest.h).
    std::vector<InputFile> inputFiles;
};

// Loads a .yaml/.yml scene or a .urdf model (a URDF alone is dropped onto a floor with defaults).
// Throws InputError on any bad input (scenes/README.md lists the rules). `report`, when given,
// receives the warnings, what was welded, repaired and placed, and the files read.
core::Model loadScene(const std::string& path, const UrdfOptions& options = {}, LoadReport* report = nullptr);
// Parses scene YAML text; sourceName is used in messages and to resolve relative files.
core::Model loadSceneFromString(const std::string& yamlText, const std::string& sourceName,
                                const UrdfOptions& options = {}, LoadReport* report = nullptr);

// True for a scene's top-level key whose value is a map of settings with defaults (`simulation`,
// `contact`): a scene without it behaves as one with it empty.
bool isSettingsMapKey(std::string_view key);

} // namespace frontier::io
