// core/steppers/stepper.h: one stepper per integrator (Model::simulation.integrator), each taking a
// whole step as a list of the named stages of core/step/step_stages.h in the order of its scheme.
//   euler    core/steppers/euler_stepper.h     first order, symplectic Euler with a SHAKE-type projection
//   rattle   core/steppers/rattle_stepper.h    second order, RATTLE (falls back to euler when it stalls)
//   rattle4  core/steppers/rattle4_stepper.h   fourth order, rattle stages composed (falls back to rattle)
#pragma once

#include "core/model.h"
#include "core/state.h"

#include <memory>

namespace frontier::core
{

class StepStages;

class Stepper
{
  public:
    virtual ~Stepper() = default;
    // Advances the state by one step of the model's dt (s). Throws SimulationError.
    virtual void step(State& state) = 0;
};

// The stepper of `integrator`, taking its stages from `stages` (which must outlive it).
std::unique_ptr<Stepper> makeStepper(IntegratorKind integrator, StepStages& stages);

} // namespace frontier::core
