// core/step_memory.cpp: the memory a Simulator carries from step to step, taken and put back.
#include "core/step_memory.h"

#include "core/step/step_stages.h"

#include <stdexcept>
#include <string>

namespace frontier::core
{

struct StepMemory::Parts
{
    std::size_t bodies = 0; // the model's, checked on restore
    std::size_t joints = 0;
    std::size_t actuators = 0;
    Actuation::Memory actuation;
    ContactProblem::Memory contacts;
    BlowUpCheck::Memory blowUp;
    PenetrationProjection::Memory penetration;
    double driveStep = 0.0; // s: rattle4 keeps its last stage's from step to step
};

StepMemory::StepMemory() = default;
StepMemory::~StepMemory() = default;
StepMemory::StepMemory(StepMemory&& other) noexcept = default;
StepMemory& StepMemory::operator=(StepMemory&& other) noexcept = default;

StepMemory::StepMemory(const StepMemory& other)
    : mParts(other.mParts ? std::make_unique<Parts>(*other.mParts) : nullptr)
{
}

StepMemory& StepMemory::operator=(const StepMemory& other)
{
    if (this == &other)
    {
        return *this;
    }
    if (!other.mParts)
    {
        mParts.reset();
    }
    else if (mParts)
    {
        *mParts = *other.mParts; // reuses the vectors' storage
    }
    else
    {
        mParts = std::make_unique<Parts>(*other.mParts);
    }
    return *this;
}

StepMemory StepStages::memory() const
{
    StepMemory memory;
    memory.mParts = std::make_unique<StepMemory::Parts>(StepMemory::Parts{
        mModel.bodies.size(), mModel.joints.size(), mModel.actuators.size(), mActuation.memory(),
        mProblem.memory(), mBlowUp.memory(), mPenetration.memory(), mStep.driveStep});
    return memory;
}

void StepStages::restoreMemory(const StepMemory& memory)
{
    if (memory.empty())
    {
        throw std::invalid_argument("restoring a step memory that holds none");
    }
    const StepMemory::Parts& parts = *memory.mParts;
    if (parts.bodies != mModel.bodies.size() || parts.joints != mModel.joints.size() ||
        parts.actuators != mModel.actuators.size())
    {
        throw std::invalid_argument(
            "the step memory of a model of " + std::to_string(parts.bodies) + " bodies, " +
            std::to_string(parts.joints) + " joints and " + std::to_string(parts.actuators) +
            " actuators does not fit this one of " + std::to_string(mModel.bodies.size()) + ", " +
            std::to_string(mModel.joints.size()) + " and " + std::to_string(mModel.actuators.size()));
    }
    mActuation.restore(parts.actuation);
    mProblem.restore(parts.contacts);
    mBlowUp.restore(parts.blowUp);
    mPenetration.restore(parts.penetration);
    mStep.driveStep = parts.driveStep;
    // Valid at the pose the last step ended in: built again at the next step's start.
    mEndRowsValid = false;
    mRattle.forgetFactoredPose();
}

} // namespace frontier::core
