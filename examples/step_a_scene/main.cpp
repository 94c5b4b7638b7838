// examples/step_a_scene/main.cpp: Frontier used as a library (docs/library.md). Loads a scene with
// a position servo on a hinge (servo_arm.yaml beside this file unless a path is given), steps it,
// gives the servo a new target through core::Simulator::setActuatorTarget and steps on, printing
// the hinge angle, the arm's centre of mass and the servo's torque as it goes. It then checks that
// the printout makes physical sense and exits with status 1 when it does not (2: the scene could
// not be loaded or lacks the arm):
//   - held at target 0 the arm sags no more than its servo's stiffness allows against gravity;
//   - after the new target the angle moves towards it and settles there, at rest;
//   - the arm's centre of mass is where a rigid rotation about the hinge by that angle puts it;
//   - at rest the servo's torque and gravity's about the hinge sum to zero (static equilibrium).
#include "collision/contacts.h"
#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"
#include "io/scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <string>

namespace
{

using namespace frontier;

constexpr double cNewTarget = 0.8;         // rad: the servo's target after the hold
constexpr double cHoldSeconds = 0.5;       // s at the scene's own target (0: level)
constexpr double cMoveSeconds = 1.5;       // s at the new target
constexpr double cPrintEverySeconds = 0.1; // s

int findJoint(const core::Model& model, const std::string& name)
{
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        if (model.joints[k].name == name)
        {
            return static_cast<int>(k);
        }
    }
    return -1;
}

int findActuator(const core::Model& model, int joint)
{
    for (std::size_t a = 0; a < model.actuators.size(); ++a)
    {
        if (model.actuators[a].joint == joint && model.actuators[a].kind == core::ActuatorKind::Position)
        {
            return static_cast<int>(a);
        }
    }
    return -1;
}

struct Arm
{
    const core::Model& model;
    int body = -1;     // the arm
    int joint = -1;    // its hinge (parent: the world)
    int actuator = -1; // the servo on the hinge

    const core::Joint& hinge() const { return model.joints[static_cast<std::size_t>(joint)]; }
    double angle(const core::State& state) const
    {
        return state.jointAngles[static_cast<std::size_t>(joint)];
    } // rad
    const core::BodyState& bodyState(const core::State& state) const
    {
        return state.bodies[static_cast<std::size_t>(body)];
    }
    // Where a rigid rotation by `angle` (rad) about the hinge puts the arm's centre of mass (m).
    core::Vec3 rotatedCentre(double angle) const
    {
        const core::Vec3 anchor = hinge().anchorParent; // world frame: the parent is the world
        const core::Vec3 start = model.bodies[static_cast<std::size_t>(body)].position_W;
        return anchor + Eigen::AngleAxisd(angle, hinge().axisParent) * (start - anchor);
    }
    // Gravity's torque on the arm about the hinge axis at `state` (N m).
    double gravityTorque(const core::State& state) const
    {
        const double mass = model.bodies[static_cast<std::size_t>(body)].mass; // kg
        const core::Vec3 lever = bodyState(state).position_W - hinge().anchorParent;
        return hinge().axisParent.dot(lever.cross(mass * model.simulation.gravity));
    }
    double servoTorque(const core::Simulator& simulator) const // N m
    {
        return simulator.actuatorEfforts()[static_cast<std::size_t>(actuator)].effort;
    }
    void print(const core::State& state, const core::Simulator& simulator) const
    {
        const core::Vec3& p = bodyState(state).position_W;
        std::printf("t = %5.3f s  angle = %+8.5f rad  arm at (%+.5f, %+.5f, %+.5f) m  servo %+7.3f N m\n",
                    state.time, angle(state), p.x(), p.y(), p.z(), servoTorque(simulator));
    }
};

// Counts the checks that failed, each printed with what it found.
struct Checks
{
    int failed = 0;
    void expect(bool ok, const char* what, double found)
    {
        std::printf("%s: %s (%.6g)\n", ok ? "ok" : "FAILED", what, found);
        failed += ok ? 0 : 1;
    }
};

long stepsFor(double seconds, double dt)
{
    return std::lround(seconds / dt);
}

} // namespace

int main(int argc, char** argv)
{
    const std::string path = argc > 1 ? argv[1] : STEP_A_SCENE_FILE;
    core::Model model;
    try
    {
        model = io::loadScene(path);
    }
    catch (const std::exception& error) // io::InputError names the file, line and column
    {
        std::fprintf(stderr, "step_a_scene: %s\n", error.what());
        return 2;
    }
    const Arm arm{model, model.findBody("arm"), findJoint(model, "shoulder"),
                  findActuator(model, findJoint(model, "shoulder"))};
    if (arm.body < 0 || arm.joint < 0 || arm.actuator < 0 || arm.hinge().type != core::JointType::Revolute ||
        arm.hinge().parent != core::cWorld)
    {
        std::fprintf(stderr,
                     "step_a_scene: %s needs a body 'arm' on a revolute joint 'shoulder' to the "
                     "world with a position servo\n",
                     path.c_str());
        return 2;
    }

    collision::ContactDetector contacts(model);
    core::Simulator simulator(model, core::StepOptions{}, &contacts);
    core::State state = core::initialState(model);
    const double dt = model.simulation.dt; // s
    const long printEvery = stepsFor(cPrintEverySeconds, dt);
    Checks checks;
    try
    {
        for (long i = 1; i <= stepsFor(cHoldSeconds, dt); ++i)
        {
            simulator.step(state);
            if (i % printEvery == 0)
            {
                arm.print(state, simulator);
            }
        }
        const double kp = model.actuators[static_cast<std::size_t>(arm.actuator)].kp; // N m/rad
        const double sag = std::abs(arm.gravityTorque(state)) / kp;                   // rad
        checks.expect(std::abs(arm.angle(state)) < 1.5 * sag + 1e-4,
                      "held at target 0 the arm sags at most by gravity's torque / kp (rad)",
                      arm.angle(state));

        std::printf("new servo target: %.3f rad\n", cNewTarget);
        simulator.setActuatorTarget(static_cast<std::size_t>(arm.actuator), cNewTarget);
        const double startGap = std::abs(cNewTarget - arm.angle(state)); // rad
        double gapAfterFirstPrint = startGap;
        double largestGeometryError = 0.0; // m
        double overshoot = 0.0;            // rad beyond the target
        for (long i = 1; i <= stepsFor(cMoveSeconds, dt); ++i)
        {
            simulator.step(state);
            const double angle = arm.angle(state);
            largestGeometryError = std::max(
                largestGeometryError, (arm.bodyState(state).position_W - arm.rotatedCentre(angle)).norm());
            overshoot = std::max(overshoot, angle - cNewTarget);
            if (i % printEvery == 0)
            {
                arm.print(state, simulator);
                if (i == printEvery)
                {
                    gapAfterFirstPrint = std::abs(cNewTarget - angle);
                }
            }
        }
        const double angle = arm.angle(state);
        checks.expect(gapAfterFirstPrint < 0.5 * startGap,
                      "0.1 s after the new target the arm has gone more than half way (rad left)",
                      gapAfterFirstPrint);
        checks.expect(overshoot < 0.05, "the arm overshoots the target by less than 0.05 rad (rad)",
                      overshoot);
        checks.expect(std::abs(angle - cNewTarget) < 1.5 * std::abs(arm.gravityTorque(state)) / kp + 1e-4,
                      "it settles at the target, off by no more than gravity's sag (rad from the target)",
                      angle - cNewTarget);
        checks.expect(arm.bodyState(state).angularVelocity_W.norm() < 1e-2, "and comes to rest (rad/s)",
                      arm.bodyState(state).angularVelocity_W.norm());
        checks.expect(largestGeometryError < 1e-6,
                      "the centre of mass stays on its circle about the hinge (largest error, m)",
                      largestGeometryError);
        const double balance = arm.servoTorque(simulator) + arm.gravityTorque(state); // N m
        checks.expect(std::abs(balance) < 0.02 * std::abs(arm.gravityTorque(state)),
                      "at rest the servo's torque balances gravity's about the hinge (their sum, N m)",
                      balance);
    }
    catch (const core::SimulationError& error)
    {
        std::fprintf(stderr, "step_a_scene: %s\n", error.what());
        return 1;
    }
    std::printf("%s\n", checks.failed == 0 ? "all checks passed" : "some checks FAILED");
    return checks.failed == 0 ? 0 : 1;
}
