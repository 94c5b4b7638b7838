// run/actuator_efforts.cpp: the actuators' efforts of a step, looked up by joint coordinate.
#include "run/actuator_efforts.h"

#include "core/time_function.h"

#include <limits>

namespace frontier::run
{

void lastActuatorEfforts(const core::Model& model, const core::Simulator& simulator,
                         std::vector<CoordinateEffort>& out)
{
    out.clear();
    const std::span<const core::ActuatorEffort> efforts = simulator.actuatorEfforts();
    for (std::size_t a = 0; a < model.actuators.size() && a < efforts.size(); ++a)
    {
        const core::Actuator& actuator = model.actuators[a];
        out.push_back({actuator.joint, actuator.coordinate, efforts[a].effort, efforts[a].atLimit});
    }
}

void effortsByCoordinate(const core::Model& model, std::span<const CoordinateEffort> efforts,
                         std::vector<std::array<double, 2>>& out)
{
    out.assign(model.joints.size(), {0.0, 0.0});
    for (const CoordinateEffort& e : efforts)
    {
        const auto coordinates = core::jointCoordinates(model.joints[static_cast<std::size_t>(e.joint)].type);
        for (std::size_t c = 0; c < coordinates.size(); ++c)
        {
            if (coordinates[c] == e.coordinate)
            {
                out[static_cast<std::size_t>(e.joint)][c] = e.effort;
            }
        }
    }
}

double trackingError(const core::Model& model, const core::State& state, std::size_t a)
{
    const core::Actuator& actuator = model.actuators[a];
    switch (actuator.kind)
    {
    case core::ActuatorKind::Position:
        return core::valueAt(actuator.target, state.time) -
               core::fileCoordinate(model, state, actuator.joint, actuator.coordinate);
    case core::ActuatorKind::Velocity:
        return core::valueAt(actuator.target, state.time) -
               core::jointCoordinateVelocity(model, state, actuator.joint, actuator.coordinate);
    case core::ActuatorKind::Effort:
        break;
    }
    return std::numeric_limits<double>::quiet_NaN();
}

} // namespace frontier::run
