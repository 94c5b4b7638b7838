// core/simulation_error.h: the errors a step throws, with what they name as fields.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace frontier::core
{

// What a run that blew up names: the step, the body and the quantity. Two kinds (docs/method.md §7
// for the second): a body's state ran away (`quantity` is "position", "orientation", "velocity" or
// "angular velocity", checked at `where`), or a joint came apart after the drift correction did
// not converge (`joint`, `gap` and `quantity` "position" (m) or "orientation" (rad)).
struct SimulationFailure
{
    long step = 0;                // State::step when it failed
    double time = 0.0;            // State::time when it failed (s)
    int body = -1;                // body index: the runaway body, or the joint's child
    std::string bodyName;         // its name
    std::string quantity;         // what ran away or came apart (see above)
    std::string where;            // a runaway: "start of step" or "end of step"; empty for a joint
    std::optional<int> joint;     // the joint that came apart (index)
    std::string jointName;        // its name
    std::string parentName;       // its parent body's name, empty for the world
    std::optional<double> gap;    // its error after the correction (m or rad, by quantity)
    double maxDistance = 0.0;     // a runaway: the distance from the origin checked (m)
    double maxSpeed = 0.0;        // and the speed limit (m/s)
    double maxAngularSpeed = 0.0; // and the angular speed limit (rad/s)
    std::string hint;             // "; ..." the likely cause (core/failure_hint.h), or empty
    bool gapInRadians() const { return quantity == "orientation"; }
};

// A run that blew up: names the step, the body and the quantity; what() is the English message.
class SimulationError : public std::runtime_error
{
  public:
    explicit SimulationError(SimulationFailure failure);
    const SimulationFailure& failure() const { return mFailure; }

  private:
    SimulationFailure mFailure;
};

// A joint block that cannot be eliminated: dependent rows or a degenerate configuration
// (core/impulse_solver.h).
class SingularJointError : public std::runtime_error
{
  public:
    SingularJointError(std::string jointName, const std::string& message);
    const std::string& jointName() const { return mJointName; }

  private:
    std::string mJointName;
};

// A model the solver cannot take (e.g. a loop it does not support): bad input, not a failed run.
class UnsupportedModelError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

} // namespace frontier::core
