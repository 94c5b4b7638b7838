// run/names.h: bodies, joints and actuators by name, and joint positions as the model file counts
// them.
#pragma once

#include "core/joints/coordinates.h"
#include "core/model.h"
#include "core/state.h"

#include <stdexcept>
#include <string_view>

namespace frontier::run
{

// A name the model does not have; what() names the nearest one the model has.
class NameError : public std::invalid_argument
{
  public:
    using std::invalid_argument::invalid_argument;
};

// Indices into Model::bodies, Model::joints, Model::actuators. Throw NameError ("no joint 'hipp'
// in the model; did you mean 'hip'?").
int bodyIndex(const core::Model& model, std::string_view name);
int jointIndex(const core::Model& model, std::string_view name);
// The actuator on the named joint's coordinate (rotation of a revolute joint, slide of a prismatic
// one; a cylindrical joint's two by `coordinate`).
int actuatorIndex(const core::Model& model, std::string_view jointName,
                  std::optional<core::JointCoordinate> coordinate = std::nullopt);

// A joint's position as its model file counts it (rad or m): a URDF joint's position, in which
// actuator targets are given too; a YAML joint's from its initial pose (core::fileCoordinate).
double jointPosition(const core::Model& model, const core::State& state, std::string_view jointName,
                     std::optional<core::JointCoordinate> coordinate = std::nullopt);

} // namespace frontier::run
