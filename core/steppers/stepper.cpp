// core/steppers/stepper.cpp: the stepper of each integrator.
#include "core/steppers/stepper.h"

#include "core/steppers/euler_stepper.h"
#include "core/steppers/rattle4_stepper.h"
#include "core/steppers/rattle_stepper.h"

#include <stdexcept>

namespace frontier::core
{

std::unique_ptr<Stepper> makeStepper(IntegratorKind integrator, StepStages& stages)
{
    switch (integrator)
    {
    case IntegratorKind::Euler:
        return std::make_unique<EulerStepper>(stages);
    case IntegratorKind::Rattle:
        return std::make_unique<RattleStepper>(stages);
    case IntegratorKind::Rattle4:
        return makeRattle4Stepper(stages);
    }
    throw std::invalid_argument("unknown integrator");
}

} // namespace frontier::core
