// io/hold_servos.cpp: servos holding a robot's joints at their start positions.
#include "io/hold_servos.h"

#include "core/joints/coordinate_inertia.h"
#include "core/joints/coordinates.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace frontier::io::detail
{

void addHoldServos(core::Model& model, int firstJoint, int endJoint)
{
    const double omega = 2.0 * std::numbers::pi * cHoldFrequency; // rad/s
    for (int k = firstJoint; k < endJoint; ++k)
    {
        const core::Joint& joint = model.joints[static_cast<std::size_t>(k)];
        for (const core::JointCoordinate coordinate : core::jointCoordinates(joint.type))
        {
            const bool driven = std::any_of(model.actuators.begin(), model.actuators.end(),
                                            [&](const core::Actuator& a)
                                            { return a.joint == k && a.coordinate == coordinate; });
            const double inertia = core::coordinateInertia(model, k, coordinate);
            if (driven || !(inertia > 0.0))
            {
                continue;
            }
            core::Actuator servo;
            servo.joint = k;
            servo.coordinate = coordinate;
            servo.kind = core::ActuatorKind::Position;
            servo.kp = inertia * omega * omega;
            if (std::isfinite(joint.effortLimit))
            {
                servo.kp = std::max(servo.kp, joint.effortLimit / cHoldError);
            }
            servo.kd = 2.0 * std::sqrt(servo.kp * inertia);
            servo.effortLimit = joint.effortLimit;
            servo.target = core::constantFunction(joint.initialPosition);
            model.actuators.push_back(std::move(servo));
        }
    }
}

} // namespace frontier::io::detail
