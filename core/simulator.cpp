// core/simulator.cpp: the Simulator picks the stepper of the model's integrator (core/steppers/)
// and keeps the stages it takes with their data from step to step (core/step/step_stages.h).
#include "core/simulator.h"

#include "core/step/step_stages.h"
#include "core/steppers/stepper.h"

namespace frontier::core
{

struct Simulator::Impl
{
    Impl(const Model& model, const StepOptions& options, ContactSource* contacts)
        : stages(model, options, contacts), stepper(makeStepper(model.simulation.integrator, stages))
    {
    }
    StepStages stages;
    std::unique_ptr<Stepper> stepper;
};

Simulator::Simulator(const Model& model, const StepOptions& options, ContactSource* contacts)
    : mImpl(std::make_unique<Impl>(model, options, contacts))
{
}

Simulator::~Simulator() = default;

void Simulator::step(State& state)
{
    mImpl->stepper->step(state);
    mImpl->stages.finishActuation();
}

const FrontierLayout& Simulator::layout() const
{
    return mImpl->stages.layout();
}

const StepStats& Simulator::lastStep() const
{
    return mImpl->stages.stats();
}

std::pair<double, double> Simulator::jointErrors(const State& state)
{
    return mImpl->stages.jointErrors(state);
}

const LargeVector<Vec6>& Simulator::jointImpulses() const
{
    return mImpl->stages.jointImpulses();
}

std::span<const ActuatorEffort> Simulator::actuatorEfforts() const
{
    return mImpl->stages.actuation().efforts();
}

void Simulator::setActuatorTarget(std::size_t actuator, double value)
{
    mImpl->stages.actuation().setTarget(actuator, constantFunction(value));
}

void Simulator::setActuatorTarget(std::size_t actuator, TimeFunction target)
{
    mImpl->stages.actuation().setTarget(actuator, std::move(target));
}

void Simulator::applyWrench(int body, const Vec3& force_N, const Vec3& torque_Nm)
{
    mImpl->stages.actuation().addWrench(body, force_N, torque_Nm);
}

void Simulator::applyForceAtPoint(const State& state, int body, const Vec3& force_N, const Vec3& point_W)
{
    const std::size_t i = static_cast<std::size_t>(body);
    const bool known = body >= 0 && i < state.bodies.size();
    const Vec3 lever = point_W - (known ? state.bodies[i].position_W : Vec3::Zero()); // m
    applyWrench(body, force_N, lever.cross(force_N)); // refuses the index, a static body, a point not finite
}

StepMemory Simulator::memory() const
{
    return mImpl->stages.memory();
}

void Simulator::restoreMemory(const StepMemory& memory)
{
    mImpl->stages.restoreMemory(memory);
}

void Simulator::jointChildImpulses(const State& state, std::vector<Vec6>& out) const
{
    mImpl->stages.jointChildImpulses(state, out);
}

void Simulator::contactImpulses(std::vector<ContactImpulse>& out) const
{
    mImpl->stages.contactImpulses(out);
}

int Simulator::pushingLimitRows() const
{
    return mImpl->stages.pushingLimitRows();
}

} // namespace frontier::core
