// python/recording.cpp: a run stepped from Python written as `frontier run` writes it.
#include "python/recording.h"

#include "io/atomic_file.h"
#include "io/stats.h"
#include "run/run_stats.h"

namespace frontier::python
{

Recording::Recording(const RecordingOptions& options, const std::string& scene, const core::Model& model,
                     core::Simulator& simulator, const core::State& state)
    : mOptions(options), mScene(scene), mModel(model), mTally(model, simulator, state), mFirstStep(state.step)
{
    if (mOptions.every < 1)
    {
        throw std::invalid_argument("every must be a whole number >= 1, not " +
                                    std::to_string(mOptions.every));
    }
    for (const std::string* file : {&mOptions.trajectory, &mOptions.stats})
    {
        if (!file->empty())
        {
            io::makeFolderFor(*file);
            io::removeStaleTemporariesOf(*file);
            io::AtomicFile probe(*file); // the file can be written (removed again, never committed)
        }
    }
    keep(state);
}

Recording::~Recording() = default;

void Recording::keep(const core::State& state)
{
    if (mOptions.trajectory.empty() || (state.step - mFirstStep) % mOptions.every != 0)
    {
        return;
    }
    core::State row;
    row.time = state.time;
    row.step = state.step;
    row.bodies = state.bodies;
    mRows.push_back(std::move(row));
}

void Recording::addStep(const core::Simulator& simulator, const core::State& state)
{
    mTally.addStep(simulator, state);
    for (const double seconds : simulator.lastStep().seconds)
    {
        mStepSeconds += seconds;
    }
    keep(state);
}

void Recording::fail(const core::SimulationError& error, const core::Simulator& simulator)
{
    mTally.fail(error, simulator);
    mFailed = true;
}

void Recording::abandon(const std::string& why)
{
    mFailed = true;
    mFailure = why;
}

std::vector<std::string> Recording::close(const core::State& state)
{
    const run::RunSummary summary = mTally.finish(state, mStepSeconds);
    std::vector<std::string> written;
    if (!mOptions.trajectory.empty())
    {
        // As `frontier run --steps N` states it: the run's duration is the steps taken.
        core::SimulationSettings settings = mModel.simulation;
        settings.duration = static_cast<double>(summary.steps) * settings.dt;
        io::TrajectoryMetadata metadata =
            io::makeTrajectoryMetadata(mScene, settings, summary.steps, mOptions.every);
        io::addUrdfOptions(metadata, mOptions.urdf);
        io::addContactTolerances(metadata, mOptions.contact);
        io::TrajectoryWriter writer(mOptions.trajectory, metadata);
        for (const core::State& row : mRows)
        {
            writer.writeState(mModel, row);
        }
        written.push_back(mFailed ? io::failedPath(mOptions.trajectory) : mOptions.trajectory);
        writer.commitAs(written.back());
    }
    if (!mOptions.stats.empty())
    {
        io::RunStats stats = run::runStats(mScene, mModel, summary);
        stats.completed = !mFailed;
        stats.failure = mFailure.empty() ? summary.failure : mFailure;
        io::writeStats(mOptions.stats, stats);
        written.push_back(mOptions.stats);
    }
    return written;
}

} // namespace frontier::python
