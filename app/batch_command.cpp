// app/batch_command.cpp: `frontier batch`: the plan's jobs of this shard, each in DIR/jobs/ID/
// under a lock, complete ones skipped; or --list, --merge, --slurm.
#include "app/batch/batch.h"
#include "app/cli_options.h"
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
#include <tuple>
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

// The plan and the shard of this process. Throws io::InputError.
std::pair<BatchPlan, Shard> readPlanAndShard(const BatchOptions& options)
{
    BatchPlan plan = readBatchPlan(options.plan);
    Shard shard;
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
    return {std::move(plan), shard};
}

// The shard's jobs: fixed by index mod count, whatever is complete.
std::vector<const PlanJob*> shardJobs(const BatchPlan& plan, const Shard& shard)
{
    std::vector<const PlanJob*> selected;
    for (const PlanJob& job : plan.jobs)
    {
        if (static_cast<int>(job.index % static_cast<std::size_t>(shard.count)) == shard.index)
        {
            selected.push_back(&job);
        }
    }
    return selected;
}

// How one job of this process ended.
struct JobEnd
{
    Outcome outcome = Outcome::Failed;
    JobState state = JobState::NotComplete; // before it ran
    std::string message;                    // why it failed

    // Run again because its inputs changed.
    bool redone() const
    {
        return state == JobState::InputsChanged && (outcome == Outcome::Done || outcome == Outcome::Failed);
    }
};

// Rows a failed attempt kept (failedPath names) would outlive this one, and so would the temporary
// files of an attempt killed outright (SIGKILL).
void clearEarlierAttempt(const JobOutputs& files, const std::string& folder)
{
    for (const std::string* file : {&files.trajectory, &files.joints, &files.contacts})
    {
        if (!file->empty())
        {
            fs::remove(failedPath(*file));
        }
    }
    io::removeStaleTemporaries(folder);
    if (!files.frames.empty())
    {
        io::removeStaleTemporaries(files.frames);
    }
}

// Runs a job that is not complete, its scene loaded already.
JobEnd runIncompleteJob(const BatchPlan& plan, const PlanJob& job, const BatchOptions& options,
                        const JobOutputs& files, PreparedScene& prepared)
{
    clearEarlierAttempt(files, jobFolder(options.out, job));
    RunRequest request{runOptionsOf(plan, job, options), job.scenePath, files, 1, {}, {}};
    request.options.inputsDigest = prepared.inputsDigest();
    request.load = [&]() { return prepared.take(); };
    const JobResult result = runOne(request);
    if (result.exitCode == cExitBadInput)
    {
        writeFailedStats(job, files, result.error);
    }
    JobEnd end;
    end.message = result.error;
    end.outcome = result.exitCode == cExitOk ? Outcome::Done : Outcome::Failed;
    if (result.exitCode != cExitOk && run::interruptSignal() != 0)
    {
        end.outcome = Outcome::NotStarted; // stopped by the signal: redone next time
    }
    return end;
}

// One job under its lock: skipped when another process holds it or its results stand, else run.
JobEnd runBatchJob(const BatchPlan& plan, const PlanJob& job, const BatchOptions& options)
{
    const JobOutputs files = jobOutputs(plan, options.out, job);
    JobEnd end;
    try
    {
        fs::create_directories(jobFolder(options.out, job));
        const JobLock lock(jobFolder(options.out, job));
        if (!lock.held())
        {
            end.outcome = Outcome::Locked;
            return end;
        }
        PreparedScene prepared = prepareScene(plan, job, options.urdf);
        end.state = jobState(plan, files, prepared.inputsDigest());
        if (end.state == JobState::Complete)
        {
            end.outcome = Outcome::Complete; // also when another process finished it meanwhile
            return end;
        }
        const JobState state = end.state;
        end = runIncompleteJob(plan, job, options, files, prepared);
        end.state = state;
    }
    catch (const std::exception& e) // an output or folder error, ...: this job fails
    {
        end.outcome = Outcome::Failed;
        end.message = e.what();
    }
    return end;
}

// "[3/12] ID: done", as each job ends.
void printJobEnd(std::size_t ended, std::size_t total, const PlanJob& job, const JobEnd& end)
{
    const Outcome outcome = end.outcome;
    const char* word = outcome == Outcome::Done       ? "done"
                       : outcome == Outcome::Complete ? "complete before, skipped"
                       : outcome == Outcome::Locked   ? "running elsewhere (locked), skipped"
                       : outcome == Outcome::Failed   ? "FAILED"
                                                      : "interrupted";
    std::fprintf(stderr, "[%zu/%zu] %s: %s%s%s%s\n", ended, total, job.id.c_str(), word,
                 end.redone() ? " (redone: its inputs changed since its last run)" : "",
                 outcome == Outcome::Failed ? ": " : "",
                 outcome == Outcome::Failed ? end.message.c_str() : "");
}

// Runs the shard's jobs, `options.jobs` at a time, until done or a signal arrives.
std::vector<JobEnd> runShard(const BatchPlan& plan, const std::vector<const PlanJob*>& selected,
                             const BatchOptions& options)
{
    std::vector<JobEnd> ends(selected.size(), JobEnd{Outcome::NotStarted, JobState::NotComplete, {}});
    std::mutex printing;
    std::size_t ended = 0;
    runJobs(selected.size(), options.jobs,
            [&](std::size_t k)
            {
                if (run::interruptSignal() != 0)
                {
                    return 0;
                }
                ends[k] = runBatchJob(plan, *selected[k], options);
                const std::lock_guard<std::mutex> guard(printing);
                ++ended;
                if (!options.quiet)
                {
                    printJobEnd(ended, selected.size(), *selected[k], ends[k]);
                }
                return 0;
            });
    return ends;
}

// The shard's count line, each failed job's message, and the exit code.
int reportShard(const std::vector<const PlanJob*>& selected, const std::vector<JobEnd>& ends,
                const Shard& shard, bool quiet)
{
    std::size_t counts[5] = {};
    std::size_t redoneCount = 0; // of the jobs run or failed
    for (const JobEnd& end : ends)
    {
        ++counts[static_cast<int>(end.outcome)];
        redoneCount += end.redone() ? 1 : 0;
    }
    if (!quiet)
    {
        const std::string redoneText =
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
        if (ends[k].outcome == Outcome::Failed)
        {
            std::cerr << "frontier: job " << selected[k]->id << " (" << selected[k]->scene << " "
                      << describeVariation(*selected[k]) << ") failed: " << ends[k].message << "\n";
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
} // namespace

int batchCommand(const BatchOptions& options)
{
    BatchPlan plan;
    Shard shard;
    try
    {
        std::tie(plan, shard) = readPlanAndShard(options);
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
    const std::vector<const PlanJob*> selected = shardJobs(plan, shard);
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
    const std::vector<JobEnd> ends = runShard(plan, selected, options);
    return reportShard(selected, ends, shard, options.quiet);
}

namespace
{
void addBatchOptions(CLI::App& batch, BatchOptions& o)
{
    batch.add_option("plan", o.plan, "the batch plan .yaml (README \"Batches\", docs/batch.md)")->required();
    batch.add_option("--out", o.out, "folder of the batch: jobs/ID/ per job, batch.csv, summary.md, slurm/")
        ->required()
        ->check(cPath);
    batch.add_flag("--list", o.list, "print the jobs (of this shard): id, scene, variation; run nothing");
    auto* shard = batch.add_option("--shard", o.shard,
                                   "run only shard I of N: the jobs whose index mod N is I (0-based)");
    batch
        .add_option_function<std::string>(
            "--shard-from-env",
            [&o](const std::string& value)
            {
                o.shardFromEnv = true;
                o.shardVariable = value;
            },
            "the shard from SLURM_ARRAY_TASK_ID/_COUNT, JOB_COMPLETION_INDEX (count from --shards or the "
            "plan's shards:), or the variable VAR (give it after the plan, or as --shard-from-env=VAR)")
        ->expected(0, 1)
        ->excludes(shard);
    batch
        .add_option("--shards", o.shards, "shard count: the Slurm array's size (default: jobs, at most 100)")
        ->transform(numberIn(1.0, 100000.0, false, true));
    batch.add_option("--jobs", o.jobs, "jobs at a time on this machine")->transform(cJobs);
    auto* merge =
        batch.add_flag("--merge", o.merge, "write DIR/batch.csv and DIR/summary.md from the jobs' stats");
    batch
        .add_option("--chart", o.chart,
                    "with --merge (or --slurm): DIR/chart.png of column Y against column X")
        ->delimiter(',')
        ->expected(2)
        ->allow_extra_args(false);
    auto* slurm =
        batch.add_flag("--slurm", o.slurm, "write DIR/slurm/batch.sbatch (an array job) and merge.sbatch")
            ->excludes(merge);
    batch.add_option("--partition", o.partition, "#SBATCH --partition")->needs(slurm);
    batch.add_option("--time", o.time, "#SBATCH --time (a shard's time limit)")->needs(slurm);
    batch.add_option("--cpus", o.cpus, "#SBATCH --cpus-per-task, and each shard's --jobs")
        ->transform(cJobs)
        ->needs(slurm);
    batch.add_flag("--submit", o.submit, "sbatch both scripts, the merge after the array (afterok)")
        ->needs(slurm);
    batch.add_flag("--quiet", o.quiet, "no line per job");
    addPackagePathOption(batch, o.urdf.packagePaths);
    batch.footer(
        "Jobs go to DIR/jobs/ID/; complete jobs are skipped, each job is locked while it runs. Exit "
        "codes: 0 every job of the shard is done; 1 a job failed (--merge: a job failed or is "
        "missing); 2 a bad plan or flags (PLAN:LINE:COLUMN); 128 + the signal after SIGINT, SIGTERM, "
        "SIGHUP (run again to finish).");
}
} // namespace

Command addBatchCommand(CLI::App& app)
{
    return addCommand<BatchOptions>(
        app, "batch",
        "many runs from a plan (scenes x variations): resumable, sharded (Slurm), merged into one CSV",
        addBatchOptions, batchCommand);
}

} // namespace frontier::app
