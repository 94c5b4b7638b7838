// bench/step_bench.cpp: whole simulation steps (core::Simulator::step: free velocities, rows,
// factor, impulses, positions, SHAKE stabilization, angular momentum) on chains of n capsules on
// ball joints hanging from the world, released horizontal like scenes/chain30.yaml (0.1 m, 0.1 kg
// links), with the `linear`, `dense` and `pgs` (20 sweeps) solvers; no contacts.
//
// Each case starts from the chain after cWarmUpSteps steps (with the same solver; `dense` starts
// from the `linear` warm-up, the same trajectory to round-off), so the chain is swinging and
// bent. Counters: us_per_step, us_per_body_step (wall time / steps / n) and
// max_joint_error_m, the largest joint position error after any benchmarked step.
// The target: `linear` us_per_body_step flat within 1.5x from 100 to 10 000 links.
// Hinge cases: the same chain on revolute joints about y (it swings in the xz plane), `linear`,
// plain, with damping on every hinge (a compliant row in each joint block), with a position servo
// on every hinge (the same row with the servo's stiffness and target) and with Coulomb friction on
// every hinge (a bounded extra row per joint): what joint damping, servos and friction cost.
//
//   step_bench --benchmark_min_time=0.5
#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"

#include <algorithm>
#include <benchmark/benchmark.h>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>

namespace
{

using namespace frontier;
using core::Vec3;

constexpr int cWarmUpSteps = 300;
constexpr double cLinkLength = 0.1; // m, joint to joint
constexpr double cLinkMass = 0.1;   // kg
constexpr double cServoKp = 1.0;    // N m/rad
constexpr double cServoKd = 0.05;   // N m s/rad

// What the chain's joints are: ball joints, or hinges about y with damping (N m s/rad) and Coulomb
// friction (N m) on each, and a position servo holding each hinge straight (cServoKp, cServoKd).
struct ChainJoints
{
    core::JointType type = core::JointType::Ball;
    double damping = 0.0;
    double friction = 0.0;
    bool servo = false;
    auto operator<=>(const ChainJoints&) const = default;
};

// n capsules (radius 0.01 m, segment 0.08 m) along +x at z = 2 m, capsule axis (local z) along
// world x, joints at the link ends, the first joined to the world.
core::Model makeChain(int n, core::SolverKind solver, const ChainJoints& joints = {})
{
    core::Model model;
    model.name = "chain of " + std::to_string(n);
    model.simulation.dt = 0.001;
    model.simulation.solver = solver;
    model.simulation.pgsIterations = 20;
    core::Shape capsule;
    capsule.type = core::ShapeType::Capsule;
    capsule.radius = 0.01;
    capsule.length = cLinkLength - 2.0 * capsule.radius;
    const core::MassProperties props = core::shapeMassProperties(capsule, 1000.0);
    const core::Quat alongX(std::sqrt(0.5), 0.0, std::sqrt(0.5), 0.0);
    model.bodies.reserve(static_cast<std::size_t>(n));
    model.joints.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
        core::Body body;
        body.name = "link" + std::to_string(i);
        body.mass = cLinkMass;
        body.inertia_B = props.inertia * (cLinkMass / props.mass);
        body.shapes.push_back(capsule);
        body.position_W = Vec3((i + 0.5) * cLinkLength, 0.0, 2.0);
        body.orientation_WB = alongX;
        model.bodies.push_back(body);
    }
    for (int i = 0; i < n; ++i)
    {
        core::Joint joint;
        joint.name = "joint" + std::to_string(i);
        joint.type = joints.type;
        joint.damping = joints.damping;
        joint.friction = joints.friction;
        joint.parent = i == 0 ? core::cWorld : i - 1;
        joint.child = i;
        const Vec3 axis = joints.type == core::JointType::Ball ? Vec3::UnitZ() : Vec3::UnitY();
        core::setJointFrames(model, joint, Vec3(i * cLinkLength, 0.0, 2.0), axis);
        model.joints.push_back(joint);
        if (joints.servo)
        {
            core::Actuator servo; // a position servo on the hinge, target 0, no effort limit
            servo.joint = i;
            servo.kp = cServoKp;
            servo.kd = cServoKd;
            model.actuators.push_back(servo);
        }
    }
    return model;
}

// A chain model and its state after the warm-up, kept for every repetition of a case.
struct Prepared
{
    std::unique_ptr<core::Model> model;
    core::State warm;
};

const Prepared& prepare(int n, core::SolverKind solver, const ChainJoints& joints)
{
    static std::map<std::tuple<int, core::SolverKind, ChainJoints>, Prepared> cache;
    const auto key = std::make_tuple(n, solver, joints);
    auto found = cache.find(key);
    if (found != cache.end())
    {
        return found->second;
    }
    Prepared p;
    p.model = std::make_unique<core::Model>(makeChain(n, solver, joints));
    const core::SolverKind warmSolver = solver == core::SolverKind::Dense ? core::SolverKind::Linear : solver;
    const core::Model warmModel = makeChain(n, warmSolver, joints);
    core::Simulator warmUp(warmModel);
    p.warm = core::initialState(warmModel);
    for (int k = 0; k < cWarmUpSteps; ++k)
    {
        warmUp.step(p.warm);
    }
    return cache.emplace(key, std::move(p)).first->second;
}

void stepChain(benchmark::State& st, core::SolverKind solver, const ChainJoints& joints = {})
{
    const int n = static_cast<int>(st.range(0));
    const Prepared* prepared = nullptr;
    try
    {
        prepared = &prepare(n, solver, joints);
    }
    catch (const core::SimulationError& error)
    {
        st.SkipWithError(error.what());
        return;
    }
    core::Simulator simulator(*prepared->model);
    core::State state = prepared->warm;
    double maxJointError = 0.0;
    double seconds = 0.0;
    for (auto _ : st)
    {
        const auto start = std::chrono::steady_clock::now();
        try
        {
            simulator.step(state);
        }
        catch (const core::SimulationError& error)
        {
            st.SkipWithError(error.what());
            break;
        }
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        maxJointError = std::max(maxJointError, simulator.lastStep().maxJointErrorM);
    }
    const double steps = static_cast<double>(st.iterations());
    if (steps > 0)
    {
        st.counters["us_per_step"] = 1e6 * seconds / steps;
        st.counters["us_per_body_step"] = 1e6 * seconds / steps / n;
    }
    st.counters["max_joint_error_m"] = maxJointError;
    st.counters["bodies"] = n;
}

void BM_StepLinear(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Linear);
}
void BM_StepDense(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Dense);
}
void BM_StepPgs20(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Pgs);
}

void BM_StepHinges(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Linear, {core::JointType::Revolute, 0.0, 0.0});
}
void BM_StepHingesDamped(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Linear, {core::JointType::Revolute, 1e-3, 0.0});
}
void BM_StepHingesServo(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Linear, {core::JointType::Revolute, 0.0, 0.0, true});
}
void BM_StepHingesFriction(benchmark::State& st)
{
    stepChain(st, core::SolverKind::Linear, {core::JointType::Revolute, 0.0, 1e-3});
}

BENCHMARK(BM_StepLinear)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepHinges)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepHingesDamped)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
// A servo below its effort limit shares its hinge's block: a drive row like damping, plus its target.
BENCHMARK(BM_StepHingesServo)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
// Friction rows are extra rows: their Delassus matrix is dense within a tree (O(n^2) per step).
BENCHMARK(BM_StepHingesFriction)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);
// Dense LU is O(n^3) per factorization: ~0.05 s per step at 100 links, ~0.4 s at 200.
BENCHMARK(BM_StepDense)->Arg(10)->Arg(100)->Arg(200)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepPgs20)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

} // namespace

BENCHMARK_MAIN();
