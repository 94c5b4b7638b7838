// study/stability_criteria.cpp: a scene's own pass criteria, watched over a run.
#include "study/stability_criteria.h"

#include "core/joints/coordinates.h"
#include "core/time_function.h"
#include "study/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace frontier::study
{

namespace
{

std::string format(const char* pattern, double value)
{
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// The joint's angle from its bodies' orientations, in [-pi, pi] (0 at the initial pose).
double wrappedAngle(const core::State& state, const core::Joint& joint)
{
    const core::Mat3 R_a =
        joint.parent == core::cWorld
            ? core::Mat3::Identity()
            : state.bodies[static_cast<std::size_t>(joint.parent)].orientation_WB.toRotationMatrix();
    const core::Mat3 R_b =
        state.bodies[static_cast<std::size_t>(joint.child)].orientation_WB.toRotationMatrix();
    return core::wrappedJointAngle(joint, R_a, R_b);
}

} // namespace

CriteriaWatch::CriteriaWatch(const core::Model& model, const io::SceneStabilityCriteria& criteria)
    : mModel(model), mCriteria(criteria)
{
    for (const io::StabilityJointCheck& check : criteria.joints)
    {
        Watched watched;
        watched.check = check;
        for (const core::Actuator& actuator : model.actuators)
        {
            if (actuator.joint == check.joint && actuator.kind == core::ActuatorKind::Position)
            {
                watched.servo = &actuator;
            }
        }
        mWatched.push_back(watched);
    }
}

void CriteriaWatch::observe(const core::State& state, StabilityCell& cell)
{
    for (std::size_t i = 0; i < mModel.bodies.size(); ++i)
    {
        if (mModel.bodies[i].isStatic)
        {
            continue;
        }
        const double speed = state.bodies[i].velocity_W.norm();
        if (speed > cell.maxSpeedMps)
        {
            cell.maxSpeedMps = speed;
            cell.fastestBody = mModel.bodies[i].name;
        }
        if (mCriteria.maxSpeed && speed > *mCriteria.maxSpeed && mTooFast.empty())
        {
            mTooFast = "'" + mModel.bodies[i].name + "' at " + format("%.3g", speed) +
                       " m/s at t = " + format("%.4g", state.time) + " s (bound " +
                       format("%g", *mCriteria.maxSpeed) + " m/s)";
        }
    }
    for (Watched& w : mWatched)
    {
        const core::Joint& joint = mModel.joints[static_cast<std::size_t>(w.check.joint)];
        const double wrapped = wrappedAngle(state, joint);
        // A step turns a joint by far less than pi: the nearest whole turn continues the angle.
        w.previous = mFirst ? wrapped : core::continuedAngle(wrapped, w.previous);
        const double angle = joint.initialPosition + w.previous; // the model file's convention (rad)
        w.low = mFirst ? angle : std::min(w.low, angle);
        w.high = mFirst ? angle : std::max(w.high, angle);
        const std::string at = " at t = " + format("%.4g", state.time) + " s";
        if (w.check.range && w.broke.empty() && (angle < (*w.check.range)[0] || angle > (*w.check.range)[1]))
        {
            w.broke = "joint '" + joint.name + "' at " + format("%.3g", angle) + " rad" + at + ", outside [" +
                      format("%g", (*w.check.range)[0]) + ", " + format("%g", (*w.check.range)[1]) + "]";
        }
        if (w.servo != nullptr)
        {
            const double error = std::abs(angle - core::valueAt(w.servo->target, state.time));
            w.worstTracking = std::max(w.worstTracking, error);
            if (w.check.maxTrackingError && error > *w.check.maxTrackingError && w.broke.empty())
            {
                w.broke = "joint '" + joint.name + "' " + format("%.2g", error) + " rad off its target" + at +
                          " (bound " + format("%g", *w.check.maxTrackingError) + " rad)";
            }
        }
    }
    mFirst = false;
}

void CriteriaWatch::judge(StabilityCell& cell) const
{
    for (const Watched& w : mWatched)
    {
        cell.angleLowRad = std::min(cell.angleLowRad.value_or(w.low), w.low);
        cell.angleHighRad = std::max(cell.angleHighRad.value_or(w.high), w.high);
        if (w.servo != nullptr)
        {
            cell.maxTrackingErrorRad = std::max(cell.maxTrackingErrorRad.value_or(0.0), w.worstTracking);
        }
    }
    if (cell.outcome != StabilityOutcome::Survived)
    {
        return;
    }
    std::string broke;
    if (!mTooFast.empty())
    {
        broke = "too fast: " + mTooFast;
    }
    const double rise = cell.energyMaxJ - cell.energyInitialJ;
    if (broke.empty() && mCriteria.maxEnergyRise && rise > *mCriteria.maxEnergyRise)
    {
        broke = "energy rose " + format("%.3g", rise) + " J (bound " +
                format("%g", *mCriteria.maxEnergyRise) + " J)";
    }
    for (const Watched& w : mWatched)
    {
        const core::Joint& joint = mModel.joints[static_cast<std::size_t>(w.check.joint)];
        if (broke.empty() && !w.broke.empty())
        {
            broke = w.broke;
        }
        if (broke.empty() && w.check.reach && std::max(-w.low, w.high) <= *w.check.reach)
        {
            broke = "joint '" + joint.name + "' reached only " + format("%.3g", std::max(-w.low, w.high)) +
                    " rad (must pass " + format("%g", *w.check.reach) + " rad)";
        }
    }
    if (!broke.empty())
    {
        cell.outcome = StabilityOutcome::Failed;
        cell.note = broke;
    }
}

std::string criteriaText(const core::Model& model, const io::SceneStabilityCriteria& criteria)
{
    std::vector<std::string> parts;
    if (criteria.maxSpeed)
    {
        parts.push_back("speed <= " + format("%g", *criteria.maxSpeed) + " m/s");
    }
    if (criteria.maxEnergyRise)
    {
        parts.push_back("energy rise <= " + format("%g", *criteria.maxEnergyRise) + " J");
    }
    for (const io::StabilityJointCheck& check : criteria.joints)
    {
        const std::string name = "'" + model.joints[static_cast<std::size_t>(check.joint)].name + "'";
        if (check.maxTrackingError)
        {
            parts.push_back(name + " within " + format("%g", *check.maxTrackingError) + " rad of its target");
        }
        if (check.range)
        {
            parts.push_back(name + " within [" + format("%g", (*check.range)[0]) + ", " +
                            format("%g", (*check.range)[1]) + "] rad");
        }
        if (check.reach)
        {
            parts.push_back(name + " past " + format("%g", *check.reach) + " rad");
        }
    }
    std::string text;
    for (const std::string& part : parts)
    {
        text += (text.empty() ? "" : "; ") + part;
    }
    return text;
}

} // namespace frontier::study
