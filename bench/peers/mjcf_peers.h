// bench/peers/mjcf_peers.h: one MJCF file in MuJoCo, compiled by MuJoCo from the file itself, beside
// the same file in Frontier through its import (io::loadScene): masses and inertias, passive motion
// and time per step (frontier_peers --mjcf FILE; docs/benchmarks.md).
//
// MuJoCo's side never goes through Frontier's io code: mj_loadXML reads the file (its includes from
// disk) with one change, the one Frontier's import makes: autolimits="true" unless the file sets
// it. The harness gives the compiler the file's text with <compiler autolimits="true"/> just after
// the <mujoco> start tag; a <compiler autolimits="..."/> of the file (or of a file it includes)
// comes later and so overrides it.
//
// Bodies: each moving Frontier body stands for a MuJoCo weld group (a body and the bodies welded to
// it, named as its root body); its frames ("BODY:JOINT", in front of it) are summed into it. MuJoCo's
// group is merged here from body_mass, xipos, ximat and body_inertia after mj_forward at qpos0, by
// the parallel axis theorem. Frontier adds a joint's armature to the inertia of the body it moves
// (a hinge's as a disc on its axis: the armature about it, half about each axis across; a ball's
// about every axis; a slide's into a frame as mass; docs/mjcf.md): that term
// is subtracted from Frontier's figures before they are compared. A difference is relative to the
// larger of MuJoCo's figure and what Frontier stores (with the armature): a joint's armature of
// 0.75 kg m^2 on a link of 1e-12 kg m^2 (Debian's gym thrower) leaves only round-off of the armature
// from the link's own inertia.
#pragma once

#include "core/model.h"
#include "io/mujoco_util.h"

#include <memory>
#include <string>
#include <vector>

namespace frontier::peers
{

using io::detail::MujocoModel;

// MuJoCo's compiled model of the file (see above). Throws std::runtime_error with MuJoCo's message.
MujocoModel loadMujocoModel(const std::string& path);

// One moving body (MuJoCo weld group) in both engines, at the start, world frame.
struct MjcfBodyInertia
{
    std::string name;
    double mujocoMass = 0.0, frontierMass = 0.0;                                           // kg
    core::Vec3 mujocoCentre_W = core::Vec3::Zero(), frontierCentre_W = core::Vec3::Zero(); // m
    core::Mat3 mujocoInertia_W = core::Mat3::Zero(),
               frontierInertia_W = core::Mat3::Zero(); // about the centre
    double massDifference = 0.0;                       // |difference| / MuJoCo's mass (see above)
    double centreDifferenceM = 0.0;                    // m
    // The largest |element| of the difference over the largest eigenvalue of MuJoCo's inertia (see
    // above).
    double inertiaDifference = 0.0;
};

struct MjcfInertia
{
    double mujocoMass = 0.0, frontierMass = 0.0; // kg, the moving bodies'
    double staticMass = 0.0; // kg, MuJoCo's bodies welded to the world (Frontier's static body)
    std::vector<MjcfBodyInertia> bodies;
    double largestDifference = 0.0; // the largest of the bodies' and the total mass's relative differences
    std::string largestAt;          // "BODY mass", "BODY inertia" or "total mass"
};

// Both engines' masses, centres and inertias of `path` (Frontier: io::loadScene). Throws
// std::runtime_error (MuJoCo refused the file) or io::InputError (Frontier did).
MjcfInertia compareInertia(const std::string& path);

// How a passive run (no control, contacts off in both) is taken.
struct MjcfMotionSettings
{
    double duration = 1.0;    // s
    double mujocoDt = 1e-4;   // s, MuJoCo's RK4
    double frontierDt = 1e-4; // s
    core::IntegratorKind integrator = core::IntegratorKind::Rattle4;
    double sampleEvery = 0.01; // s, a multiple of both steps
};

struct MjcfMotion
{
    bool contactsPossible = false; // some geoms of different bodies may collide (contype/conaffinity)
    double maxPositionM = 0.0;     // the largest distance of a body's centre of mass between the engines
    double maxAngleRad = 0.0;      // the largest angle between a body's orientations
    std::string worstBody;         // where the largest distance was
    double worstTime = 0.0;        // s, when
    double travelM = 0.0;          // the largest distance of a body's centre from its start (MuJoCo)
    double turnRad = 0.0;          // the largest angle of a body from its start orientation (MuJoCo)
};

// Both engines' passive motion of `path` from its start (MuJoCo: RK4 with contacts disabled by
// mjDSBL_CONTACT; Frontier: no contact detection), compared at every sample time.
MjcfMotion compareMotion(const std::string& path, const MjcfMotionSettings& settings = {});

// Time per step of both engines on the file as loaded, each with its own settings: Frontier
// (euler, the file's timestep, contacts on), MuJoCo (the file's integrator and timestep): the
// median of `rounds` rounds of `duration` s each, the engines alternating.
struct MjcfTiming
{
    double frontierDt = 0.0, mujocoDt = 0.0;                     // s
    std::string mujocoIntegrator;                                // "Euler", "RK4", ...
    double frontierMicroseconds = 0.0, mujocoMicroseconds = 0.0; // per step, median
    std::string frontierFailure; // why Frontier's run stopped early ("" when it ran)
    std::string mujocoWarnings;  // MuJoCo's warning counters that rose, "" when none did
};
MjcfTiming timeSteps(const std::string& path, double duration = 2.0, int rounds = 5);

// frontier_peers --mjcf FILE: the three comparisons as markdown on `out` (the motion only when no
// geoms may collide or `noContacts`). Returns the exit code (2: a file either engine refuses).
int runMjcfComparison(const std::string& path, const MjcfMotionSettings& motion, bool noContacts, int rounds,
                      std::ostream& out);

} // namespace frontier::peers
