// app/batch_command.cpp: `frontier batch`: the plan's jobs of this shard, each in DIR/jobs/ID/
// under a lock, complete ones skipped; or --list, --merge, --slurm.
#include "app/batch_jobs.h"
#include "app/batch_plan.h"
#include "app/batch_scene.h"
#include "app/commands.h"
#include "app/job_board.h"
#include "app/run_one.h"
#include "io/atomic_file.h"
#include "io/scene.h"
#include "io/stats.h"
#include "run/run_loop.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <sys/file.h>
#include <unistd.h>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

enum class Outcome
{
    NotStarted, // an interrupt came first
    Done,
    Complete, // complete before this run: skipped
    Locked,   // another process holds its lock: skipped
    Failed,
};

// "dt=0.001 solver=pgs"
std::string describeVariation(const PlanJob& job)
{
    std::string text;
    for (const BatchSetting& s : job.variation)
    {
        text += (text.empty() ? "" : " ") + s.key + "=" + s.value;
    }
    return text;
}

// The flags of `frontier run` that the job's settings stand for (their values as the plan's reader
// checked them; throws io::InputError at the value otherwise).
RunOptions runOptionsOf(const BatchPlan& plan, const PlanJob& job, const BatchOptions& options)
{
    RunOptions run;
    run.scenes = {job.scenePath};
    run.dt = numberSetting(plan, job, "dt");
    run.duration = numberSetting(plan, job, "duration");
    if (const BatchSetting* s = findSetting(job, "solver"))
    {
        run.solver = s->value;
    }
    if (const BatchSetting* s = findSetting(job, "integrator"))
    {
        run.integrator = s->value;
    }
    if (const std::optional<double> n = numberSetting(plan, job, "pgs_iterations"))
    {
        run.pgsIterations = static_cast<int>(*n); // a whole number from 1 to 1000000 (readBatchPlan)
    }
    run.recordEvery = plan.recordEvery;
    run.fps = plan.fps;
    run.width = plan.width;
    run.height = plan.height;
    run.jobs = 1; // render threads: the batch runs jobs in parallel instead
    run.quiet = true;
    run.urdf = options.urdf;
    return run;
}

// A lock on DIR/jobs/ID/.lock (flock(2): the kernel releases it when the holder ends, even killed).
// Never through a symbolic link: one named .lock is refused (O_NOFOLLOW), so the file it points to
// is neither created nor locked.
class JobLock
{
  public:
    explicit JobLock(const std::string& folder)
    {
        const std::string path = (fs::path(folder) / ".lock").string();
        mFd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (mFd < 0)
        {
            throw io::OutputError(path + ": cannot open the job's lock: " + std::strerror(errno));
        }
        mHeld = ::flock(mFd, LOCK_EX | LOCK_NB) == 0;
    }
    ~JobLock() { ::close(mFd); }
    JobLock(const JobLock&) = delete;
    JobLock& operator=(const JobLock&) = delete;
    bool held() const { return mHeld; }

  private:
    int mFd = -1;
    bool mHeld = false;
};

// A job that failed before its run could write stats (bad input, an output error) says so in them.
void writeFailedStats(const PlanJob& job, const JobOutputs& files, const std::string& message)
{
    io::RunStats stats;
    stats.scene = job.scenePath;
    stats.completed = false;
    stats.failure = message;
    io::writeStats(files.stats, stats);
}

// A job's scene loaded before the job is judged complete or not (its inputs digest says whether
// its results stand), or what its load threw, thrown again when the job runs (runOne reports it).
struct PreparedScene
{
    std::optional<BatchScene> scene;
    std::exception_ptr loadError;

    std::string inputsDigest() const { return scene ? scene->inputsDigest : std::string(); }
    run::LoadedScene take()
    {
        if (loadError)
        {
            std::rethrow_exception(loadError);
        }
        return std::move(scene->loaded);
    }
};

PreparedScene prepareScene(const BatchPlan& plan, const PlanJob& job, const io::UrdfOptions& urdf)
{
    PreparedScene prepared;
    try
    {
        prepared.scene = loadBatchScene(plan, job, urdf);
    }
    catch (...)
    {
        prepared.loadError = std::current_exception();
    }
    return prepared;
}

int listJobs(const std::vector<const PlanJob*>& jobs)
{
    for (const PlanJob* job : jobs)
    {
        std::printf("%s  %s  %s\n", job->id.c_str(), job->scene.c_str(), describeVariation(*job).c_str());
    }
    return cExitOk;
}
} // namespace

int batchCommand(const BatchOptions& options)
{
    BatchPlan plan;
    Shard shard;
    try
    {
        plan = readBatchPlan(options.plan);
        if (options.shard)
        {
            shard = parseShard(*options.shard);
        }
        else if (options.shardFromEnv)
        {
            shard = shardFromEnvironment(options.shardVariable, options.shards, plan.shards);
        }
        if (!options.chart.empty() && !options.merge && !options.slurm)
        {
            throw io::InputError("--chart", 0, 0,
                                 "--chart X,Y draws the merge's chart: give it with --merge or --slurm");
        }
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    if (options.slurm)
    {
        return slurmBatch(plan, options);
    }
    if (options.merge)
    {
        return mergeBatch(plan, options);
    }
    std::vector<const PlanJob*> selected; // fixed: index mod count, whatever is complete
    for (const PlanJob& job : plan.jobs)
    {
        if (static_cast<int>(job.index % static_cast<std::size_t>(shard.count)) == shard.index)
        {
            selected.push_back(&job);
        }
    }
    if (options.list)
    {
        return listJobs(selected);
    }
    try
    {
        fs::create_directories(fs::path(options.out) / "jobs");
    }
    catch (const fs::filesystem_error& e)
    {
        std::cerr << "frontier: " << options.out << ": cannot create the batch folder: " << e.code().message()
                  << "\n";
        return cExitBadInput;
    }

    run::installInterruptHandlers();
    std::vector<Outcome> outcomes(selected.size(), Outcome::NotStarted);
    std::vector<std::string> messages(selected.size());
    // Run again because its inputs changed (char, not bool: each thread writes its own element).
    std::vector<char> redone(selected.size(), 0);
    std::mutex printing;
    std::size_t ended = 0;
    runJobs(selected.size(), options.jobs,
            [&](std::size_t k)
            {
                if (run::interruptSignal() != 0)
                {
                    return 0;
                }
                const PlanJob& job = *selected[k];
                const JobOutputs files = jobOutputs(plan, options.out, job);
                Outcome outcome = Outcome::Failed;
                JobState state = JobState::NotComplete;
                std::string& message = messages[k];
                try
                {
                    fs::create_directories(jobFolder(options.out, job));
                    const JobLock lock(jobFolder(options.out, job));
                    if (!lock.held())
                    {
                        outcome = Outcome::Locked;
                    }
                    else if (PreparedScene prepared = prepareScene(plan, job, options.urdf);
                             (state = jobState(plan, files, prepared.inputsDigest())) == JobState::Complete)
                    {
                        outcome = Outcome::Complete; // also when another process finished it meanwhile
                    }
                    else
                    {
                        // Rows a failed attempt kept (failedPath names) would outlive this one, and
                        // so would the temporary files of an attempt killed outright (SIGKILL).
                        for (const std::string* file : {&files.trajectory, &files.joints, &files.contacts})
                        {
                            if (!file->empty())
                            {
                                fs::remove(failedPath(*file));
                            }
                        }
                        io::removeStaleTemporaries(jobFolder(options.out, job));
                        if (!files.frames.empty())
                        {
                            io::removeStaleTemporaries(files.frames);
                        }
                        RunOptions runOptions = runOptionsOf(plan, job, options);
                        runOptions.inputsDigest = prepared.inputsDigest();
                        std::string summary;
                        const int code = runOne(
                            runOptions, job.scenePath, files, 1, [](const std::string&) {}, summary, message,
                            [&]() { return prepared.take(); });
                        if (code == cExitBadInput)
                        {
                            writeFailedStats(job, files, message);
                        }
                        outcome = code == cExitOk ? Outcome::Done : Outcome::Failed;
                        if (code != cExitOk && run::interruptSignal() != 0)
                        {
                            outcome = Outcome::NotStarted; // stopped by the signal: redone next time
                        }
                    }
                }
                catch (const std::exception& e) // an output or folder error, ...: this job fails
                {
                    message = e.what();
                }
                outcomes[k] = outcome;
                redone[k] = state == JobState::InputsChanged &&
                            (outcome == Outcome::Done || outcome == Outcome::Failed);
                const std::lock_guard<std::mutex> guard(printing);
                ++ended;
                if (!options.quiet)
                {
                    const char* word = outcome == Outcome::Done       ? "done"
                                       : outcome == Outcome::Complete ? "complete before, skipped"
                                       : outcome == Outcome::Locked   ? "running elsewhere (locked), skipped"
                                       : outcome == Outcome::Failed   ? "FAILED"
                                                                      : "interrupted";
                    std::fprintf(stderr, "[%zu/%zu] %s: %s%s%s%s\n", ended, selected.size(), job.id.c_str(),
                                 word, redone[k] ? " (redone: its inputs changed since its last run)" : "",
                                 outcome == Outcome::Failed ? ": " : "",
                                 outcome == Outcome::Failed ? message.c_str() : "");
                }
                return 0;
            });

    std::size_t counts[5] = {};
    for (const Outcome o : outcomes)
    {
        ++counts[static_cast<int>(o)];
    }
    if (!options.quiet)
    {
        const auto redoneCount = static_cast<std::size_t>(std::count(redone.begin(), redone.end(), 1));
        const std::string redoneText = // of the jobs run or failed
            redoneCount == 0 ? ""
                             : "; " + std::to_string(redoneCount) + " redone because their inputs changed";
        std::printf("batch: %zu jobs (shard %d of %d): %zu run, %zu complete before, %zu running elsewhere, "
                    "%zu failed, %zu not run%s\n",
                    selected.size(), shard.index, shard.count, counts[static_cast<int>(Outcome::Done)],
                    counts[static_cast<int>(Outcome::Complete)], counts[static_cast<int>(Outcome::Locked)],
                    counts[static_cast<int>(Outcome::Failed)], counts[static_cast<int>(Outcome::NotStarted)],
                    redoneText.c_str());
    }
    for (std::size_t k = 0; k < selected.size(); ++k)
    {
        if (outcomes[k] == Outcome::Failed)
        {
            std::cerr << "frontier: job " << selected[k]->id << " (" << selected[k]->scene << " "
                      << describeVariation(*selected[k]) << ") failed: " << messages[k] << "\n";
        }
    }
    if (const int signal = run::interruptSignal(); signal != 0)
    {
        std::cerr << "frontier: " << run::signalName(signal)
                  << ": the batch stopped; run it again to finish it\n";
        return run::interruptedExitCode(signal);
    }
    return counts[static_cast<int>(Outcome::Failed)] > 0 ? cExitFailed : cExitOk;
}

} // namespace frontier::app
