// run/actuator_efforts.h: what the actuators did in a step, as the run's outputs read it (the
// joints file's effort column, the stats' max_actuator_effort, actuator_limit_steps and
// `actuators`). Every such reading goes through lastActuatorEfforts, every tracking error through
// trackingError.
#pragma once

#include "core/joints/coordinates.h"
#include "core/simulator.h"

#include <array>
#include <span>
#include <vector>

namespace frontier::run
{

// One actuator in the last step.
struct CoordinateEffort
{
    int joint = 0; // Model::joints index
    core::JointCoordinate coordinate = core::JointCoordinate::Rotation;
    double effort = 0.0;  // N or N m, along the coordinate
    bool atLimit = false; // it sat at its effort limit
};

// The actuators of the model with what each did in the simulator's last step (Model::actuators
// order); empty for a model without actuators.
void lastActuatorEfforts(const core::Model& model, const core::Simulator& simulator,
                         std::vector<CoordinateEffort>& out);

// Per joint (Model::joints order) and coordinate (core::jointCoordinates order), the effort of
// the actuator that drives it (N or N m), 0 where none does.
void effortsByCoordinate(const core::Model& model, std::span<const CoordinateEffort> efforts,
                         std::vector<std::array<double, 2>>& out);

// How far actuator `a` (Model::actuators index) is from its target at a state, target minus
// actual: for a position servo its target at state.time minus the coordinate in the model file's
// convention (core::fileCoordinate; rad or m), for a velocity motor its target speed minus the
// coordinate's rate (rad/s or m/s). NaN for an effort actuator, which follows no target.
double trackingError(const core::Model& model, const core::State& state, std::size_t a);

} // namespace frontier::run
