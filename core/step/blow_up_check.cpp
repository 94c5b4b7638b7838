// core/step/blow_up_check.cpp: the checks that stop a run that blew up, and their messages' hints.
#include "core/step/blow_up_check.h"

#include <algorithm>
#include <utility>

namespace frontier::core
{

namespace
{
bool finite(const Vec3& v)
{
    return v.allFinite();
}
} // namespace

BlowUpCheck::BlowUpCheck(const Model& model, const StepOptions& options, double dt)
    : mModel(model), mOptions(options), mDt(dt)
{
}

void BlowUpCheck::recordStartDefects(const std::vector<Contact>& contacts,
                                     const std::vector<ExtraBlock>& blocks, const State& state)
{
    if (!mMemory.startRecorded)
    {
        mMemory.startDefects = findStartDefects(contacts, blocks, mModel, state);
        mMemory.startRecorded = true;
    }
}

// The hint of a failure at this state: the start defects while their recovery (at most
// penetrationMaxSpeed, penetrationMaxAngularSpeed) could still be under way, with some steps to
// spare, or while they are still there; else a smaller step when a body turned far within the
// failing step.
std::string BlowUpCheck::likelyCause(const State& state, const StepView& step) const
{
    constexpr double cSpareSteps = 10.0;
    const double recoverySteps =
        cSpareSteps + mMemory.startDefects.overlapM / (mOptions.penetrationMaxSpeed * mDt) +
        mMemory.startDefects.limitExcess /
            (std::min(mOptions.penetrationMaxSpeed, mOptions.penetrationMaxAngularSpeed) * mDt);
    bool stillThere = step.maxPenetrationM > cDeepOverlap;
    for (const ExtraBlock& block : step.blocks)
    {
        stillThere =
            stillThere || (block.kind == ExtraBlock::Kind::Limit &&
                           block.source == mMemory.startDefects.limitJoint && block.error(0) > cDeepOverlap);
    }
    double rotation = 0.0;
    int fastest = -1;
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        const double turn = step.start[i].angularVelocity_W.norm() * mDt;
        if (!mModel.bodies[i].isStatic && turn > rotation)
        {
            rotation = turn;
            fastest = static_cast<int>(i);
        }
    }
    const bool recovering = stillThere || static_cast<double>(state.step) <= recoverySteps;
    return failureHint(mModel, mMemory.startDefects, recovering, rotation, fastest);
}

void BlowUpCheck::checkState(const State& state, const char* where, const StepView& step) const
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        const BodyState& s = state.bodies[i];
        // A cheap screen first: a sum of finite numbers with no non-finite term is never NaN, and
        // finite sums may overflow only where the exact checks below then find nothing.
        const double sum = s.position_W.sum() + s.orientation_WB.coeffs().sum() + s.velocity_W.sum() +
                           s.angularVelocity_W.sum();
        // Anything beyond the ranges of core/model.h is a blow-up even while still finite: a body
        // farther than cMaxDistance would break the collision detection of the next step.
        if (std::isfinite(sum) && s.position_W.squaredNorm() < 0.25 * cMaxDistance * cMaxDistance &&
            s.velocity_W.squaredNorm() < 0.25 * cMaxSpeed * cMaxSpeed &&
            s.angularVelocity_W.squaredNorm() < 0.25 * cMaxAngularSpeed * cMaxAngularSpeed)
        {
            continue;
        }
        const char* quantity = nullptr;
        if (!isPosition(s.position_W))
        {
            quantity = "position";
        }
        else if (!s.orientation_WB.coeffs().allFinite())
        {
            quantity = "orientation";
        }
        else if (!finite(s.velocity_W) || s.velocity_W.norm() > cMaxSpeed)
        {
            quantity = "velocity";
        }
        else if (!finite(s.angularVelocity_W) || s.angularVelocity_W.norm() > cMaxAngularSpeed)
        {
            quantity = "angular velocity";
        }
        if (quantity != nullptr)
        {
            SimulationFailure failure;
            failure.step = state.step;
            failure.time = state.time;
            failure.where = where;
            failure.body = static_cast<int>(i);
            failure.bodyName = mModel.bodies[i].name;
            failure.quantity = quantity;
            failure.maxDistance = cMaxDistance;
            failure.maxSpeed = cMaxSpeed;
            failure.maxAngularSpeed = cMaxAngularSpeed;
            failure.hint = likelyCause(state, step);
            throw SimulationError(std::move(failure));
        }
    }
}

void BlowUpCheck::jointCameApart(const State& state, const JointErrors& errors, const StepView& step) const
{
    const Joint& joint = mModel.joints[static_cast<std::size_t>(errors.worstJoint)];
    SimulationFailure failure;
    failure.step = state.step;
    failure.time = state.time;
    failure.body = joint.child;
    failure.bodyName = mModel.bodies[static_cast<std::size_t>(joint.child)].name;
    failure.joint = errors.worstJoint;
    failure.jointName = joint.name;
    if (joint.parent != cWorld)
    {
        failure.parentName = mModel.bodies[static_cast<std::size_t>(joint.parent)].name;
    }
    failure.quantity = errors.maxM >= errors.maxRad ? "position" : "orientation";
    failure.gap = std::max(errors.maxM, errors.maxRad);
    failure.hint = likelyCause(state, step);
    throw SimulationError(std::move(failure));
}

} // namespace frontier::core
