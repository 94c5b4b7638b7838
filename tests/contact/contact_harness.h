// tests/contact/contact_harness.h: a scene driven like `frontier run` drives it (a
// collision::ContactDetector with the app's margin feeding core::Simulator), and independent
// measurements of the state (penetration into static planes, speeds) for the contact tests.
#pragma once

#include "collision/contacts.h"
#include "core/simulator.h"
#include "io/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace frontier::test
{

inline std::string scenePath(const std::string& file)
{
    return std::string(FRONTIER_SOURCE_DIR) + "/scenes/" + file;
}

// A model with its detector, simulator and state; not copyable (the simulator and the detector
// keep references to the model).
struct SceneRun
{
    explicit SceneRun(core::Model m, const core::StepOptions& options = {})
        : model(std::move(m)), detector(model, collision::contactMargin(model.simulation.dt)),
          simulator(model, options, &detector), state(core::initialState(model))
    {
        detector.setStepTime(model.simulation.dt); // fast bodies swept, as `frontier run` does
    }
    SceneRun(const SceneRun&) = delete;
    SceneRun& operator=(const SceneRun&) = delete;

    void step() { simulator.step(state); }
    const core::BodyState& body(const std::string& name) const
    {
        return state.bodies[static_cast<std::size_t>(model.findBody(name))];
    }
    long stepsFor(double seconds) const
    {
        return static_cast<long>(std::llround(seconds / model.simulation.dt));
    }

    core::Model model;
    collision::ContactDetector detector;
    core::Simulator simulator;
    core::State state;
};

// Largest depth (m) by which any shape of a moving body reaches into the solid side of any
// static plane, computed from the geometry alone (not from the detector): box vertices, the
// lowest point of spheres, capsules and cylinders (closed form), mesh vertices. 0 if none.
double planePenetration(const core::Model& model, const core::State& state);

// Largest linear speed of a body's points: |v| + |w| * (bounding radius of its shapes) (m/s).
double maxPointSpeed(const core::Model& model, const core::State& state);

// Largest centre-of-mass speed and angular speed of the moving bodies.
double maxLinearSpeed(const core::Model& model, const core::State& state);
double maxAngularSpeed(const core::Model& model, const core::State& state);

bool allFinite(const core::State& state);

using Vec3 = core::Vec3;

} // namespace frontier::test
