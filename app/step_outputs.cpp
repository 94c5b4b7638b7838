// app/step_outputs.cpp: joint loads and contact forces of a step, to the joints and contacts files.
#include "app/step_outputs.h"

#include "app/outputs.h"

namespace frontier::app
{

StepOutputs::StepOutputs(const std::string& jointsPath, const std::string& contactsPath,
                         const io::FileMetadata& metadata)
    : mJointsPath(jointsPath), mContactsPath(contactsPath)
{
    if (!jointsPath.empty())
    {
        mJoints = std::make_unique<io::JointsWriter>(jointsPath, metadata);
    }
    if (!contactsPath.empty())
    {
        mContacts = std::make_unique<io::ContactsWriter>(contactsPath, metadata);
    }
}

void StepOutputs::record(const core::Model& model, const core::State& state, const core::Simulator* lastStep)
{
    // Forces, of joints and contacts, are the step's impulses over its duration: the mean force of
    // the step.
    const double dt = model.simulation.dt; // s
    if (mJoints)
    {
        mLoads.clear();
        if (lastStep != nullptr)
        {
            lastStep->jointChildImpulses(state, mChildImpulses);
            run::lastActuatorEfforts(model, *lastStep, mEfforts);
            run::effortsByCoordinate(model, mEfforts, mEffortsByCoordinate);
            mLoads.resize(model.joints.size());
            for (std::size_t k = 0; k < model.joints.size(); ++k)
            {
                mLoads[k].force_W = mChildImpulses[k].head<3>() / dt;
                mLoads[k].torque_W = mChildImpulses[k].tail<3>() / dt;
                mLoads[k].effort = mEffortsByCoordinate[k];
            }
        }
        mJoints->writeState(model, state, mLoads);
    }
    if (mContacts && lastStep != nullptr)
    {
        lastStep->contactImpulses(mContactImpulses);
        mContacts->writeStep(model, state.time, dt, mContactImpulses);
    }
}

std::vector<std::string> StepOutputs::commitFailed()
{
    std::vector<std::string> written;
    if (mJoints)
    {
        written.push_back(failedPath(mJointsPath));
        mJoints->commitAs(written.back());
    }
    if (mContacts)
    {
        written.push_back(failedPath(mContactsPath));
        mContacts->commitAs(written.back());
    }
    return written;
}

void StepOutputs::commit()
{
    if (mJoints)
    {
        mJoints->commit();
    }
    if (mContacts)
    {
        mContacts->commit();
    }
}

} // namespace frontier::app
