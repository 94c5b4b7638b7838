// app/actuator_efforts.cpp: the actuators' efforts of a step, looked up by joint coordinate.
#include "app/actuator_efforts.h"

namespace frontier::app
{

void lastActuatorEfforts(const core::Model& model, const core::Simulator& simulator,
                         std::vector<CoordinateEffort>& out)
{
    out.clear();
    // actuators: wired at merge. Fill `out` index by index from core::Model::actuators (joint,
    // coordinate) and core::Simulator::actuatorEfforts() (effort, atLimit), which come with the
    // actuators; until then a model has none.
    static_cast<void>(model);
    static_cast<void>(simulator);
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

} // namespace frontier::app
