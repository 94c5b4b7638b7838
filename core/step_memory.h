// core/step_memory.h: what core::Simulator carries from one step to the next besides the State.
//
// A step reads more than the State: the warm start of the contact problem (the last step's
// impulses), the parts of its Delassus matrix kept from recent steps, the actuators out of their
// joints' blocks (with their hysteresis) and the targets given to Simulator::setActuatorTarget, the
// external wrenches waiting for the next step, rattle4's last drive step, the position projection's
// recovery flag and the first step's record for failure messages. They change later results (at
// round-off level or more), so a rollout taken back to a State continues bit-identically only
// with this memory too: Simulator::memory() takes it, Simulator::restoreMemory() puts it back, into
// the same Simulator or another one of the same model. The caches valid only at one pose (the
// rows and factorization the last step left at its end pose) are not part of it: a restored
// simulator builds them again at the restored pose, which gives the same values bit for bit.
#pragma once

#include <cstddef>
#include <memory>

namespace frontier::core
{

class StepMemory
{
  public:
    StepMemory(); // empty: holds no simulator's memory (restoring it throws)
    ~StepMemory();
    StepMemory(const StepMemory& other);
    StepMemory& operator=(const StepMemory& other);
    StepMemory(StepMemory&& other) noexcept;
    StepMemory& operator=(StepMemory&& other) noexcept;

    bool empty() const { return mParts == nullptr; }

  private:
    friend class StepStages; // core/step/step_stages.h
    struct Parts;            // core/step_memory.cpp
    std::unique_ptr<Parts> mParts;
};

} // namespace frontier::core
