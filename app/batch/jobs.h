// app/batch/jobs.h: a batch job's folder and files, when a job is complete, and which shard this
// process runs.
#pragma once

#include "app/batch/plan.h"
#include "app/commands.h"
#include "app/outputs.h"

#include <string>

namespace frontier::app
{

// DIR/jobs/ID
std::string jobFolder(const std::string& out, const PlanJob& job);
// The job's files in its folder: stats.json always, trajectory.csv, frames/, joints.csv,
// contacts.csv when the plan asks for them.
JobOutputs jobOutputs(const BatchPlan& plan, const std::string& out, const PlanJob& job);
// Whether a job's results stand. Complete: its stats say "completed": true and every other output
// is in place (a frames folder without the INCOMPLETE marker).
enum class JobState
{
    NotComplete,   // not run, failed, stopped, or an output missing
    Complete,      // complete, from the inputs it has now
    InputsChanged, // complete, but its stats' inputs_digest differs from the inputs' digest now (an
                   // edited scene, URDF, mesh or table, another frontier binary; or no digest)
};
// `inputsDigest`: the digest of the job's inputs now (BatchScene::inputsDigest; "" when its scene
// does not load, which no result matches).
JobState jobState(const BatchPlan& plan, const JobOutputs& files, const std::string& inputsDigest);

// Which shard this process runs.
struct Shard
{
    int index = 0; // 0-based
    int count = 1;
};
// "I/N" with 0 <= I < N; throws io::InputError naming --shard.
Shard parseShard(const std::string& text);
// From the environment: `variable` when given (the count from --shards, the plan's `shards:` or
// FRONTIER_SHARD_COUNT); else SLURM_ARRAY_TASK_ID with SLURM_ARRAY_TASK_COUNT (or _MIN and _MAX);
// else JOB_COMPLETION_INDEX (a Kubernetes Indexed Job) with the count as for `variable`. Throws
// io::InputError saying what is missing.
Shard shardFromEnvironment(const std::string& variable, std::optional<int> shards,
                           std::optional<int> planShards);

} // namespace frontier::app
