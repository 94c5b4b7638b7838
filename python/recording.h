// python/recording.h: the trajectory and stats files of a run stepped from Python, the same files
// `frontier run --trajectory --stats` writes (so `frontier check` and `frontier render` read them).
#pragma once

#include "core/simulator.h"
#include "io/trajectory.h"
#include "run/run_tally.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace frontier::python
{

struct RecordingOptions
{
    // How the scene was loaded, written to the trajectory's header so that `check` and `render`
    // load it the same way.
    io::UrdfOptions urdf;
    core::ContactTolerances contact;
    std::string trajectory; // CSV path, empty: none
    std::string stats;      // JSON path, empty: none
    int every = 1;          // a row block every `every` steps
};

// Started at a state (its first rows), fed every step after it. The trajectory's header states the
// run's step count, known only at close(): rows are kept in memory until then (13 doubles per
// body and recorded step) and written through a temporary file renamed into place, as the
// command line writes them. A recording closed after a failed step writes its rows under
// io::failedPath names and stats with "completed": false. Destroyed without close(), it writes nothing.
class Recording
{
  public:
    // Throws io::OutputError when an output path cannot be written (checked before any step).
    Recording(const RecordingOptions& options, const std::string& scene, const core::Model& model,
              core::Simulator& simulator, const core::State& state);
    ~Recording();

    void addStep(const core::Simulator& simulator, const core::State& state);
    void fail(const core::SimulationError& error, const core::Simulator& simulator);
    // The run stopped for another reason (an exception in the caller's loop): `why`.
    void abandon(const std::string& why);
    // Writes the files; returns the paths written. Throws io::OutputError.
    std::vector<std::string> close(const core::State& state);
    bool failed() const { return mFailed; }

  private:
    void keep(const core::State& state);

    RecordingOptions mOptions;
    std::string mScene;
    const core::Model& mModel;
    run::RunTally mTally;
    std::vector<core::State> mRows; // the recorded states: time and moving bodies only
    long mFirstStep = 0;
    bool mFailed = false;
    std::string mFailure;      // abandon()'s reason
    double mStepSeconds = 0.0; // wall time of the recorded steps (s), their stages summed
};

} // namespace frontier::python
