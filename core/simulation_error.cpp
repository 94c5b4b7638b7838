// core/simulation_error.cpp: the English message of a SimulationError, from its fields.
#include "core/simulation_error.h"

#include <sstream>
#include <utility>

namespace frontier::core
{

namespace
{
std::string message(const SimulationFailure& f)
{
    std::ostringstream msg;
    if (f.joint)
    {
        msg << "simulation blew up at step " << f.step << " (t = " << f.time << " s): body '" << f.bodyName
            << "' came off " << (f.parentName.empty() ? std::string("the world") : "'" + f.parentName + "'")
            << " at joint '" << f.jointName << "': joint " << f.quantity << " error " << f.gap.value_or(0.0)
            << (f.gapInRadians() ? " rad" : " m") << " after the correction did not converge" << f.hint;
    }
    else
    {
        msg << "simulation blew up at step " << f.step << " (t = " << f.time << " s, " << f.where
            << "): body '" << f.bodyName << "' has a non-finite or runaway " << f.quantity << " (limits "
            << f.maxDistance << " m from the origin, " << f.maxSpeed << " m/s, " << f.maxAngularSpeed
            << " rad/s)" << f.hint;
    }
    return msg.str();
}
} // namespace

SimulationError::SimulationError(SimulationFailure failure)
    : std::runtime_error(message(failure)), mFailure(std::move(failure))
{
}

SingularJointError::SingularJointError(std::string jointName, const std::string& message)
    : std::runtime_error(message), mJointName(std::move(jointName))
{
}

} // namespace frontier::core
