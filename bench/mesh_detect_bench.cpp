// bench/mesh_detect_bench.cpp: contact detection (ContactDetector::detect) on a pile of moving
// meshes, with the meshes colliding as their convex hulls (the default) and as triangle meshes
// (FCL's BVH, collision::MovingMeshes::Triangles), on the same states.
//
// The scene: 16 rocks (tests/collision/test_models.h rockMesh: jittered spheres, non-convex) dropped in a 4 x
// 2 x 2 block onto a floor. The states: one second of that run, simulated once with hulls and recorded at
// every step; both detectors then detect on every recorded state, so they see exactly the same poses. Two
// mesh resolutions: 8 x 12 (98 vertices, 192 triangles, like a robot's collision mesh) and 32 x 48 (1490
// vertices, 2976 triangles, like a visual mesh). Time and CPU per detect() in microseconds; counter
// contacts_per_detect. On a loaded machine compare the CPU column.
//
//   mesh_detect_bench --benchmark_min_time=0.5
#include "collision/contacts.h"
#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"
#include "tests/collision/test_models.h" // rockMesh, movingMesh, floorBody

#include <benchmark/benchmark.h>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace
{

using namespace frontier;
using core::Vec3;

constexpr double cDt = 0.001;     // s
constexpr double cMargin = 0.005; // m, what `frontier run` uses at this dt (5 dt)

core::Model pile(int rings, int segments)
{
    using namespace collision::test;
    core::Model model;
    model.simulation.dt = cDt;
    model.bodies.push_back(floorBody());
    for (int k = 0; k < 16; ++k)
    {
        model.bodies.push_back(movingMesh("rock" + std::to_string(k),
                                          rockMesh(0.08, rings, segments, 0.2, static_cast<unsigned>(k)),
                                          Vec3(0.17 * (k % 4), 0.17 * ((k / 4) % 2), 0.12 + 0.18 * (k / 8)),
                                          1000.0, rotation(0.5 * k, Vec3(1, 0.3 * k, 0.2))));
    }
    return model;
}

struct Recorded
{
    core::Model model;
    std::vector<core::State> states; // every step of the first second
};

const Recorded& recorded(int rings, int segments)
{
    static std::map<int, Recorded> cache;
    auto [it, inserted] = cache.try_emplace(rings * 1000 + segments);
    if (inserted)
    {
        it->second.model = pile(rings, segments);
        const core::Model& model = it->second.model;
        collision::ContactDetector detector(model, cMargin);
        core::Simulator simulator(model, {}, &detector);
        core::State state = core::initialState(model);
        for (int k = 0; k < 1000; ++k)
        {
            simulator.step(state);
            it->second.states.push_back(state);
        }
    }
    return it->second;
}

void BM_Detect(benchmark::State& bench, collision::MovingMeshes mode, int rings, int segments)
{
    const Recorded& run = recorded(rings, segments);
    collision::ContactDetector detector(run.model, cMargin, mode);
    std::vector<collision::Contact> contacts;
    long calls = 0;
    long found = 0;
    std::size_t next = 0;
    for (auto _ : bench)
    {
        detector.detect(run.states[next], contacts);
        found += static_cast<long>(contacts.size());
        ++calls;
        next = (next + 1) % run.states.size();
    }
    bench.counters["contacts_per_detect"] = static_cast<double>(found) / static_cast<double>(calls);
}

BENCHMARK_CAPTURE(BM_Detect, hulls_98_vertices, collision::MovingMeshes::ConvexHulls, 8, 12)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Detect, triangles_98_vertices, collision::MovingMeshes::Triangles, 8, 12)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Detect, hulls_1490_vertices, collision::MovingMeshes::ConvexHulls, 32, 48)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Detect, triangles_1490_vertices, collision::MovingMeshes::Triangles, 32, 48)
    ->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();
