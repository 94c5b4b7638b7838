// app/batch/scene.h: a batch job's scene: the scene file with the job's scene paths set
// ("bodies.ball.position: [0, 0, 2]"), and its initial state perturbed by the job's seed.
#pragma once

#include "app/batch/plan.h"
#include "core/model.h"
#include "run/scene_loading.h"

#include <cstdint>
#include <string>
#include <yaml-cpp/yaml.h>

namespace frontier::app
{

// Sets `path` (keys joined by '.'; in a list, an entry is named by its `name:` or its 0-based
// index) in the scene's YAML tree to `value`; the last key may be new (the scene loader then
// checks it), and so may a first key that is a settings map (io::isSettingsMapKey: a scene without
// `contact:` takes `contact.friction`). Returns what did not fit, or "" when it was set.
std::string applySceneSetting(YAML::Node root, const std::string& path, const YAML::Node& value);

// Moves each free group of bodies (moving bodies joined to each other, none to the world or a
// static body) rigidly by a uniform random offset of at most positionM per axis (m) and changes
// its velocity by at most velocityMps per axis (m/s), both drawn from `seed` (the same numbers on
// every machine: splitmix64, not the standard library's distributions). A rigid move keeps the
// group's joints closed.
void perturbInitialState(core::Model& model, std::uint64_t seed, double positionM, double velocityMps);

// A batch job's scene, ready to run, and the digest of everything its results depend on beyond
// the job's id (docs/batch.md): the job's results are kept only while this digest is unchanged.
struct BatchScene
{
    run::LoadedScene loaded;  // loaded.report.inputFiles: every file read, the scene file first
    std::string inputsDigest; // io::inputsDigest: this program, the scene as run, the files read
};

// The job's scene as `frontier run` loads it, with its scene paths and seed applied, and its inputs
// digest. Throws io::InputError.
BatchScene loadBatchScene(const BatchPlan& plan, const PlanJob& job, const io::UrdfOptions& urdf);

} // namespace frontier::app
