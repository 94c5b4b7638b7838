// app/step_outputs.h: the joints and contacts files of a run (`--joints`, `--contacts`;
// io/joints_file.h, io/contacts_file.h), filled from the simulator after each recorded step.
#pragma once

#include "core/simulator.h"
#include "io/contacts_file.h"
#include "io/joints_file.h"
#include "run/actuator_efforts.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace frontier::app
{

class StepOutputs
{
  public:
    // Opens the files named (an empty path: that file is not written), each with the run's
    // metadata line. Throws io::OutputError.
    StepOutputs(const std::string& jointsPath, const std::string& contactsPath,
                const io::FileMetadata& metadata);

    // The rows of a recorded state; `lastStep`: the simulator whose last step produced it, null
    // for the initial state.
    void record(const core::Model& model, const core::State& state, const core::Simulator* lastStep);
    // Renames the files into place.
    void commit();
    // A failed run's rows up to the failure, under failedPath names (app/outputs.h); returns them.
    std::vector<std::string> commitFailed();

  private:
    std::string mJointsPath;
    std::string mContactsPath;
    std::unique_ptr<io::JointsWriter> mJoints;
    std::unique_ptr<io::ContactsWriter> mContacts;
    // Scratch, kept between steps.
    std::vector<core::Vec6> mChildImpulses;
    std::vector<run::CoordinateEffort> mEfforts;
    std::vector<std::array<double, 2>> mEffortsByCoordinate;
    std::vector<io::JointStepLoad> mLoads;
    std::vector<core::ContactImpulse> mContactImpulses;
};

} // namespace frontier::app
