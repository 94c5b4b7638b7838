// bench/solver_bench.cpp: factor + solve of one impulse problem (docs/method.md §3) with the
// `linear` (frontier-order elimination, O(n)), `dense` (Moore's dense solve, O(n^3)) and `pgs`
// (20 projected Gauss-Seidel sweeps) solvers, on chains (ball or revolute joints) and random
// trees (every joint type) of n bodies. The rows are assembled once, outside the timed loop
// (BM_LinearAssemble times that step separately). `linear` runs factor + solve as one call
// (ImpulseSolver::factorAndSolve: the forward sweep fused into the elimination); the others
// factor, then solve. Counter per_body: seconds per body per
// factor + solve (inverted iteration-invariant rate).
//
//   solver_bench --benchmark_min_time=0.2
#include "core/impulse_solver.h"

#include <benchmark/benchmark.h>
#include <cmath>
#include <memory>
#include <random>

namespace
{

using namespace frontier;
using core::JointType;
using core::Model;
using core::Vec3;

enum class Shape
{
    BallChain,
    RevoluteChain,
    RandomTree,
};

core::Body box(int index, double mass, const Vec3& size, const Vec3& position, const core::Quat& orientation)
{
    core::Body body;
    body.name = "b" + std::to_string(index);
    body.mass = mass;
    const Vec3 s2 = size.cwiseProduct(size);
    body.inertia_B = (mass / 12.0 * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
    body.position_W = position;
    body.orientation_WB = orientation;
    return body;
}

void joint(Model& model, JointType type, int parent, int child, const Vec3& anchor, const Vec3& axis)
{
    core::Joint j;
    j.name = "j" + std::to_string(model.joints.size());
    j.type = type;
    j.parent = parent;
    j.child = child;
    core::setJointFrames(model, j, anchor, axis);
    model.joints.push_back(j);
}

// n bodies: a straight chain nailed to the world at one end, or a random tree (parent uniform
// among earlier bodies, random poses, log-uniform masses 0.1..10 kg, every joint type) nailed at
// body 0. Random velocities that violate the joints.
Model makeModel(Shape shape, int n)
{
    std::mt19937 rng(12345);
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto vec = [&] { return Vec3(gauss(rng), gauss(rng), gauss(rng)); };
    Model model;
    model.bodies.reserve(static_cast<std::size_t>(n));
    if (shape != Shape::RandomTree)
    {
        const JointType type = shape == Shape::BallChain ? JointType::Ball : JointType::Revolute;
        for (int i = 0; i < n; ++i)
        {
            model.bodies.push_back(
                box(i, 1.0, Vec3(1.0, 0.1, 0.1), Vec3(i + 0.5, 0, 0), core::Quat::Identity()));
        }
        for (int i = 1; i < n; ++i)
        {
            joint(model, type, i - 1, i, Vec3(i, 0, 0), Vec3::UnitY());
        }
    }
    else
    {
        const JointType types[] = {JointType::Ball,        JointType::Revolute,  JointType::Angle,
                                   JointType::Cylindrical, JointType::Prismatic, JointType::Fixed};
        for (int i = 0; i < n; ++i)
        {
            const int parent = i == 0 ? -1 : std::uniform_int_distribution<int>(0, i - 1)(rng);
            const Vec3 position =
                parent < 0 ? Vec3::Zero()
                           : Vec3(model.bodies[static_cast<std::size_t>(parent)].position_W + vec());
            const double mass = std::exp(std::log(0.1) + unit(rng) * std::log(100.0));
            const Vec3 size(0.1 + unit(rng), 0.1 + unit(rng), 0.1 + unit(rng));
            model.bodies.push_back(
                box(i, mass, size, position,
                    core::Quat(gauss(rng), gauss(rng), gauss(rng), gauss(rng)).normalized()));
            if (parent >= 0)
            {
                const Vec3 anchor =
                    0.5 * (position + model.bodies[static_cast<std::size_t>(parent)].position_W);
                joint(model, types[std::uniform_int_distribution<int>(0, 5)(rng)], parent, i, anchor,
                      vec().normalized());
            }
        }
    }
    for (core::Body& body : model.bodies)
    {
        body.velocity_W = vec();
        body.angularVelocity_W = vec();
    }
    joint(model, JointType::Nail, core::cWorld, 0, model.bodies[0].position_W - Vec3(0.5, 0, 0),
          Vec3::UnitZ());
    return model;
}

// Everything a solve needs, built once per benchmark.
struct Problem
{
    Model model;
    core::FrontierLayout layout;
    core::State state;
    core::RowSystem system;
    core::BlockVector rhs, solution;

    Problem(Shape shape, int n) : model(makeModel(shape, n))
    {
        layout = core::buildFrontierLayout(model);
        state = core::initialState(model);
        core::assembleRows(model, layout, state, model.simulation.dt, system);
        rhs.resize(model.bodies.size(), model.joints.size());
        rhs.setZero();
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            rhs.body[i].head<3>() = system.mass[i] * state.bodies[i].velocity_W;
            rhs.body[i].tail<3>() = system.inertia_W[i] * state.bodies[i].angularVelocity_W;
        }
    }
};

void setCounters(benchmark::State& state, int n)
{
    state.counters["n"] = n;
    state.counters["per_body"] =
        benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <Shape S, core::SolverKind K> void BM_FactorSolve(benchmark::State& state)
{
    const int n = static_cast<int>(state.range(0));
    Problem problem(S, n);
    auto solver = core::makeSolver(K, 20);
    for (auto _ : state)
    {
        solver->factorAndSolve(problem.system, problem.rhs, problem.solution);
        benchmark::DoNotOptimize(problem.solution.body.data());
        benchmark::ClobberMemory();
    }
    setCounters(state, n);
}

template <Shape S> void BM_LinearAssemble(benchmark::State& state)
{
    const int n = static_cast<int>(state.range(0));
    Problem problem(S, n);
    for (auto _ : state)
    {
        core::assembleRows(problem.model, problem.layout, problem.state, problem.model.simulation.dt,
                           problem.system);
        benchmark::ClobberMemory();
    }
    setCounters(state, n);
}

using core::SolverKind;
#define FRONTIER_LINEAR_SIZES RangeMultiplier(10)->Range(10, 100000)->Unit(benchmark::kMicrosecond)
#define FRONTIER_DENSE_SIZES Arg(10)->Arg(100)->Arg(200)->Unit(benchmark::kMicrosecond)

BENCHMARK(BM_FactorSolve<Shape::BallChain, SolverKind::Linear>)->FRONTIER_LINEAR_SIZES;
BENCHMARK(BM_FactorSolve<Shape::RevoluteChain, SolverKind::Linear>)->FRONTIER_LINEAR_SIZES;
BENCHMARK(BM_FactorSolve<Shape::RandomTree, SolverKind::Linear>)->FRONTIER_LINEAR_SIZES;
BENCHMARK(BM_FactorSolve<Shape::BallChain, SolverKind::Dense>)->FRONTIER_DENSE_SIZES;
BENCHMARK(BM_FactorSolve<Shape::RevoluteChain, SolverKind::Dense>)->FRONTIER_DENSE_SIZES;
BENCHMARK(BM_FactorSolve<Shape::RandomTree, SolverKind::Dense>)->FRONTIER_DENSE_SIZES;
BENCHMARK(BM_FactorSolve<Shape::BallChain, SolverKind::Pgs>)->FRONTIER_LINEAR_SIZES;
BENCHMARK(BM_FactorSolve<Shape::RevoluteChain, SolverKind::Pgs>)->FRONTIER_LINEAR_SIZES;
BENCHMARK(BM_FactorSolve<Shape::RandomTree, SolverKind::Pgs>)->FRONTIER_LINEAR_SIZES;
BENCHMARK(BM_LinearAssemble<Shape::RandomTree>)->FRONTIER_LINEAR_SIZES;

} // namespace

BENCHMARK_MAIN();
