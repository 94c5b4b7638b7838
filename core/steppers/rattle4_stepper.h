// core/steppers/rattle4_stepper.h: the fourth-order scheme (`rattle4`, docs/method.md §11): RATTLE
// stages of c1 h, c2 h, c1 h (the triple jump; c2 < 0), each a whole RATTLE stage
// (RattleStepper::stage) at its own time. A step whose stage meets contact or limit rows
// (one-sided, not time-reversible) or stalls is taken again from its start as one rattle step.
#pragma once

#include "core/step/step_stages.h"
#include "core/steppers/rattle_stepper.h"
#include "core/steppers/stepper.h"

#include <vector>

namespace frontier::core
{

// A step composed of RATTLE stages of c h for each of `coefficients` (which add up to 1), in order.
class ComposedRattleStepper final : public Stepper
{
  public:
    ComposedRattleStepper(StepStages& stages, std::vector<double> coefficients);
    void step(State& state) override;

  private:
    bool takeStages(State& state); // false: a stage met one-sided rows or stalled

    StepStages& mStages;
    RattleStepper mRattle; // its stages, and a step taken again as one rattle step
    std::vector<double> mCoefficients;
    bool mHasBlockDrives = false; // some joint has drive rows in its block (damping, actuators)
};

// rattle4: the triple jump.
std::unique_ptr<Stepper> makeRattle4Stepper(StepStages& stages);

} // namespace frontier::core
