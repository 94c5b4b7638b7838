// app/batch/jobs.cpp: a batch job's files, its completeness, and the shard of this process.
#include "app/batch/jobs.h"

#include "app/frames.h"
#include "io/file_util.h"
#include "io/scene.h"
#include "io/stats.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

// The whole number in [low, high] of the environment variable `name`; nullopt when it is not set (or
// set to ""). Any other value is refused: a shard index of -1 is no shard.
std::optional<long long> envNumber(const std::string& name, long long low = 0, long long high = 1000000000)
{
    const char* text = std::getenv(name.c_str());
    if (text == nullptr || *text == '\0')
    {
        return std::nullopt;
    }
    const std::optional<long long> value = io::detail::parseWholeNumber(text, low, high);
    if (!value)
    {
        const std::string shown = std::string(text).substr(0, 40);
        throw io::InputError("--shard-from-env", 0, 0,
                             "expected a whole number from " + std::to_string(low) + " to " +
                                 std::to_string(high) + " in the environment variable " + name + ", got '" +
                                 shown + (shown.size() < std::strlen(text) ? "...'" : "'"));
    }
    return value;
}

// The stats of a complete job (see JobState), else nullopt.
std::optional<io::RunStats> completeStats(const BatchPlan& plan, const JobOutputs& files)
{
    std::error_code error;
    if (!fs::is_regular_file(files.stats, error))
    {
        return std::nullopt;
    }
    io::RunStats stats;
    try
    {
        stats = io::readStats(files.stats);
    }
    catch (const io::InputError&)
    {
        return std::nullopt;
    }
    if (!stats.completed)
    {
        return std::nullopt;
    }
    for (const std::string* file : {&files.trajectory, &files.joints, &files.contacts})
    {
        if (!file->empty() && !fs::is_regular_file(*file, error))
        {
            return std::nullopt;
        }
    }
    const bool framesDone =
        !plan.outputs.frames ||
        (fs::is_directory(files.frames, error) &&
         !fs::exists(fs::symlink_status(fs::path(files.frames) / cIncompleteMarker, error)));
    return framesDone ? std::optional<io::RunStats>(std::move(stats)) : std::nullopt;
}
} // namespace

std::string jobFolder(const std::string& out, const PlanJob& job)
{
    return (fs::path(out) / "jobs" / job.id).string();
}

JobOutputs jobOutputs(const BatchPlan& plan, const std::string& out, const PlanJob& job)
{
    const fs::path folder = jobFolder(out, job);
    JobOutputs files;
    files.stats = (folder / "stats.json").string();
    files.trajectory = plan.outputs.trajectory ? (folder / "trajectory.csv").string() : "";
    files.frames = plan.outputs.frames ? (folder / "frames").string() : "";
    files.joints = plan.outputs.joints ? (folder / "joints.csv").string() : "";
    files.contacts = plan.outputs.contacts ? (folder / "contacts.csv").string() : "";
    return files;
}

JobState jobState(const BatchPlan& plan, const JobOutputs& files, const std::string& inputsDigest)
{
    const std::optional<io::RunStats> stats = completeStats(plan, files);
    if (!stats)
    {
        return JobState::NotComplete;
    }
    const bool same = !inputsDigest.empty() && stats->inputsDigest == inputsDigest; // "": not known
    return same ? JobState::Complete : JobState::InputsChanged;
}

Shard parseShard(const std::string& text)
{
    const std::size_t slash = text.find('/');
    const std::optional<long long> index =
        slash == std::string::npos ? std::nullopt
                                   : io::detail::parseWholeNumber(text.substr(0, slash), 0, 1000000);
    const std::optional<long long> count =
        slash == std::string::npos ? std::nullopt
                                   : io::detail::parseWholeNumber(text.substr(slash + 1), 1, 1000000);
    if (!index || !count || *index >= *count)
    {
        throw io::InputError("--shard", 0, 0,
                             "expected I/N with 0 <= I < N (shard I of N), got '" + text + "'");
    }
    return {static_cast<int>(*index), static_cast<int>(*count)};
}

namespace
{
// The shard count when the environment gives only the index (named `indexName`): --shards, the
// plan's `shards:`, FRONTIER_SHARD_COUNT.
int shardCount(const std::string& indexName, std::optional<int> shards, std::optional<int> planShards)
{
    if (shards)
    {
        return *shards;
    }
    if (planShards)
    {
        return *planShards;
    }
    if (const std::optional<long long> n = envNumber("FRONTIER_SHARD_COUNT", 1, 1000000))
    {
        return static_cast<int>(*n);
    }
    throw io::InputError("--shard-from-env", 0, 0,
                         indexName + " gives the shard's index; the shard count comes from --shards N, the "
                                     "plan's 'shards:' or FRONTIER_SHARD_COUNT, and none is set");
}

// Shard `index` of `count`, as `from` gives them.
Shard envShard(long long index, long long count, const std::string& from)
{
    if (index < 0 || count < 1 || index >= count)
    {
        throw io::InputError("--shard-from-env", 0, 0,
                             from + " gives shard " + std::to_string(index) + " of " + std::to_string(count) +
                                 "; expected 0 <= index < count");
    }
    return {static_cast<int>(index), static_cast<int>(count)};
}

// A Slurm array task: its id less the array's first, of the array's count (from _COUNT, or _MIN
// and _MAX; else as shardCount).
Shard slurmShard(long long task, std::optional<int> shards, std::optional<int> planShards)
{
    const long long low = envNumber("SLURM_ARRAY_TASK_MIN").value_or(0);
    std::optional<long long> count = envNumber("SLURM_ARRAY_TASK_COUNT");
    if (const std::optional<long long> high = envNumber("SLURM_ARRAY_TASK_MAX"); !count && high)
    {
        count = *high - low + 1;
    }
    if (!count)
    {
        return envShard(task - low, shardCount("SLURM_ARRAY_TASK_ID", shards, planShards),
                        "SLURM_ARRAY_TASK_ID");
    }
    return envShard(task - low, *count, "SLURM_ARRAY_TASK_ID");
}
} // namespace

Shard shardFromEnvironment(const std::string& variable, std::optional<int> shards,
                           std::optional<int> planShards)
{
    if (!variable.empty())
    {
        const std::optional<long long> index = envNumber(variable);
        if (!index)
        {
            throw io::InputError("--shard-from-env", 0, 0,
                                 "expected a whole number >= 0 in the environment variable " + variable +
                                     ", which is not set");
        }
        return envShard(*index, shardCount(variable, shards, planShards), variable);
    }
    if (const std::optional<long long> task = envNumber("SLURM_ARRAY_TASK_ID"))
    {
        return slurmShard(*task, shards, planShards);
    }
    if (const std::optional<long long> index = envNumber("JOB_COMPLETION_INDEX"))
    {
        return envShard(*index, shardCount("JOB_COMPLETION_INDEX", shards, planShards),
                        "JOB_COMPLETION_INDEX");
    }
    throw io::InputError("--shard-from-env", 0, 0,
                         "no shard in the environment: expected SLURM_ARRAY_TASK_ID (a Slurm array job), "
                         "JOB_COMPLETION_INDEX (a Kubernetes Indexed Job) or --shard-from-env VAR");
}

} // namespace frontier::app
