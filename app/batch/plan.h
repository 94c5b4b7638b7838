// app/batch/plan.h: the plan of `frontier batch` (README "Batches", docs/batch.md): scenes (files or
// globs, relative to the plan) times a grid of variations, expanded into jobs with stable ids.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace frontier::app
{

// One setting of a job: a run setting (dt, duration, solver, integrator, pgs_iterations, seed) with
// its value's plain text as checked ("0.001", "pgs"; without a tag or quotes), or a scene path
// ("bodies.ball.position") with its value as YAML flow text ("0.001", "[0, 0, 2]").
struct BatchSetting
{
    std::string key;
    std::string value;
    int line = 0; // where the plan gives the value (1-based; 0: not known)
    int column = 0;
};

struct PlanJob
{
    std::size_t index = 0; // position in the plan's job order (scenes outer, last vary key fastest)
    std::string id;        // "0007-pendulum-3f2a9c1b": index, scene name, hash of scene and settings
    std::string scene;     // the scene's path as the plan names it (relative to the plan's folder)
    std::string scenePath; // the file to load
    std::vector<BatchSetting> variation; // one per `vary:` key, in the plan's key order
    std::vector<BatchSetting> settings;  // every setting of the job: the plan's fixed ones, then `vary:`
};

// Outputs a plan can ask for; stats are always written (they say whether a job is complete).
struct BatchOutputs
{
    bool trajectory = false;
    bool frames = false;
    bool joints = false;
    bool contacts = false;
};

struct BatchPlan
{
    std::string file; // the plan file
    std::vector<std::string> varyKeys;
    std::vector<PlanJob> jobs;
    BatchOutputs outputs;
    int recordEvery = 1; // trajectory rows every K steps
    double fps = 30.0;   // frames per simulated second
    int width = 640;     // frame size (pixels)
    int height = 480;
    std::optional<int> shards;       // `shards:`: the shard count for --shard-from-env without one
    double perturbPositionM = 1e-3;  // `perturb: {position}`: largest offset per axis (m) of a seed
    double perturbVelocityMps = 0.0; // `perturb: {velocity}`: largest velocity change per axis (m/s)
};

// Reads and expands a plan. Throws io::InputError with the plan's file:line:column and what was
// expected (also for a scene path that no scene of the plan has).
BatchPlan readBatchPlan(const std::string& path);

// The job's variation as "dt=0.001 solver=pgs" (its `vary:` settings, in the plan's key order).
std::string describeVariation(const PlanJob& job);

// The setting `key` of the job, or nullptr.
const BatchSetting* findSetting(const PlanJob& job, const std::string& key);
// The value of a numeric run setting of the job (dt, duration, pgs_iterations, seed) as
// readBatchPlan checked it, nullopt when the job has none; throws io::InputError at the plan's value
// when it is no finite number.
std::optional<double> numberSetting(const BatchPlan& plan, const PlanJob& job, const std::string& key);

// Settings that are not scene paths.
bool isRunSetting(const std::string& key);

// A 64-bit FNV-1a hash (the ids' hash: the same on every machine and build).
std::uint64_t fnv1a64(const std::string& text);

} // namespace frontier::app
