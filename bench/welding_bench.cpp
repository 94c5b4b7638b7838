// bench/welding_bench.cpp: what links welded by fixed joints cost. A URDF chain of 2K links hanging
// from the world, every other joint fixed (a link and a bracket bolted to it), is loaded three ways:
//   urdf_welded:       the URDF as Frontier loads it: K bodies, K revolute joints;
//   yaml_fixed_joints: the same 2K links as YAML bodies with K fixed joints between them (6 rows each);
//   yaml_k_bodies:     K bodies written by hand with the welded mass properties, K revolute joints.
// The time column is per step; the counter `bodies` the moving bodies. The claim to check: urdf_welded costs
// what yaml_k_bodies costs, not what yaml_fixed_joints costs. Whole Simulator::step, no contacts.
//
//   welding_bench --benchmark_min_time=0.5
#include "core/simulator.h"
#include "core/state.h"
#include "io/scene.h"

#include <benchmark/benchmark.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace
{

using namespace frontier;

constexpr double cLinkLength = 0.1;  // m, hinge to hinge, along -z
constexpr double cLinkMass = 0.2;    // kg, the link (a box 0.02 x 0.02 x 0.1 m)
constexpr double cBracketMass = 0.1; // kg, the bracket bolted to it (a 0.04 m cube, 0.05 m along +x)
constexpr int cWarmUpSteps = 200;

std::string boxInertia(double m, double x, double y, double z)
{
    std::ostringstream out;
    out << "ixx=\"" << m / 12 * (y * y + z * z) << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << m / 12 * (x * x + z * z)
        << "\" iyz=\"0\" izz=\"" << m / 12 * (x * x + y * y) << "\"";
    return out.str();
}

// Hinges about y; each link's bracket on a fixed joint. The chain starts tilted 0.3 rad so it swings.
std::string chainUrdf(int k)
{
    std::ostringstream out;
    out << "<robot name=\"chain\">\n  <link name=\"world\"/>\n";
    for (int i = 0; i < k; ++i)
    {
        const std::string parent = i == 0 ? "world" : "link" + std::to_string(i - 1);
        out << "  <joint name=\"hinge" << i << "\" type=\"continuous\"><parent link=\"" << parent
            << "\"/><child link=\"link" << i << "\"/><origin xyz=\"0 0 " << (i == 0 ? 0.0 : -cLinkLength)
            << "\" rpy=\"0 " << (i == 0 ? 0.3 : 0.0) << " 0\"/><axis xyz=\"0 1 0\"/></joint>\n"
            << "  <link name=\"link" << i << "\"><inertial><origin xyz=\"0 0 " << -cLinkLength / 2
            << "\"/><mass value=\"" << cLinkMass << "\"/><inertia "
            << boxInertia(cLinkMass, 0.02, 0.02, cLinkLength) << "/></inertial></link>\n"
            << "  <joint name=\"bolt" << i << "\" type=\"fixed\"><parent link=\"link" << i
            << "\"/><child link=\"bracket" << i << "\"/><origin xyz=\"0.05 0 " << -cLinkLength / 2
            << "\"/></joint>\n"
            << "  <link name=\"bracket" << i << "\"><inertial><mass value=\"" << cBracketMass
            << "\"/><inertia " << boxInertia(cBracketMass, 0.04, 0.04, 0.04) << "/></inertial></link>\n";
    }
    out << "</robot>\n";
    return out.str();
}

std::string vec(const core::Vec3& v)
{
    std::ostringstream out;
    out.precision(17);
    out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
    return out.str();
}

std::string quat(const core::Quat& q)
{
    std::ostringstream out;
    out.precision(17);
    out << "[" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z() << "]";
    return out.str();
}

std::string inertia(const core::Mat3& I)
{
    std::ostringstream out;
    out.precision(17);
    out << "[" << I(0, 0) << ", " << I(1, 1) << ", " << I(2, 2) << ", " << I(0, 1) << ", " << I(0, 2) << ", "
        << I(1, 2) << "]";
    return out.str();
}

// YAML with the links and brackets as separate bodies (fixed joints), poses from the welded model.
std::string yamlFixedJoints(int k)
{
    const core::Quat tilt(Eigen::AngleAxisd(0.3, core::Vec3::UnitY()));
    std::ostringstream out;
    out << "simulation: {gravity: [0, 0, -9.81]}\nbodies:\n";
    for (int i = 0; i < k; ++i)
    {
        const core::Vec3 hinge = tilt * core::Vec3(0, 0, -cLinkLength * i);
        const core::Vec3 link = hinge + tilt * core::Vec3(0, 0, -cLinkLength / 2);
        const core::Vec3 bracket = hinge + tilt * core::Vec3(0.05, 0, -cLinkLength / 2);
        out << "  - {name: link" << i << ", mass: " << cLinkMass << ", inertia: ["
            << cLinkMass / 12 * (0.0004 + cLinkLength * cLinkLength) << ", "
            << cLinkMass / 12 * (0.0004 + cLinkLength * cLinkLength) << ", " << cLinkMass / 12 * 0.0008
            << "], position: " << vec(link) << ", orientation: " << quat(tilt) << "}\n"
            << "  - {name: bracket" << i << ", mass: " << cBracketMass << ", inertia: ["
            << cBracketMass / 12 * 0.0032 << ", " << cBracketMass / 12 * 0.0032 << ", "
            << cBracketMass / 12 * 0.0032 << "], position: " << vec(bracket)
            << ", orientation: " << quat(tilt) << "}\n";
    }
    out << "joints:\n";
    for (int i = 0; i < k; ++i)
    {
        const core::Vec3 hinge = tilt * core::Vec3(0, 0, -cLinkLength * i);
        out << "  - {name: hinge" << i
            << ", type: revolute, parent: " << (i == 0 ? "world" : "link" + std::to_string(i - 1))
            << ", child: link" << i << ", anchor: " << vec(hinge) << ", axis: [0, 1, 0]}\n"
            << "  - {name: bolt" << i << ", type: fixed, parent: link" << i << ", child: bracket" << i
            << ", anchor: " << vec(hinge) << "}\n";
    }
    return out.str();
}

// YAML with K bodies carrying the welded mass properties (copied from the welded model's bodies).
std::string yamlKBodies(const core::Model& welded, int k)
{
    std::ostringstream out;
    out << "bodies:\n";
    for (int i = 0; i < k; ++i)
    {
        const core::Body& b = welded.bodies[static_cast<std::size_t>(i)];
        out << "  - {name: " << b.name << ", mass: " << b.mass << ", inertia: " << inertia(b.inertia_B)
            << ", position: " << vec(b.position_W) << ", orientation: " << quat(b.orientation_WB) << "}\n";
    }
    out << "joints:\n";
    const core::Quat tilt(Eigen::AngleAxisd(0.3, core::Vec3::UnitY()));
    for (int i = 0; i < k; ++i)
    {
        out << "  - {name: hinge" << i
            << ", type: revolute, parent: " << (i == 0 ? "world" : "link" + std::to_string(i - 1))
            << ", child: link" << i << ", anchor: " << vec(tilt * core::Vec3(0, 0, -cLinkLength * i))
            << ", axis: [0, 1, 0]}\n";
    }
    return out.str();
}

core::Model weldedChain(int k)
{
    const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                       ("frontier-welding-bench-" + std::to_string(::getpid()) + ".urdf");
    std::ofstream(path) << chainUrdf(k);
    io::UrdfOptions options;
    options.selfCollision = false;
    core::Model model = io::loadScene(path.string(), options);
    std::filesystem::remove(path);
    model.bodies.pop_back(); // the floor: the chain hangs clear of it, and no detector runs
    return model;
}

void stepModel(benchmark::State& st, const core::Model& model)
{
    core::Simulator sim(model);
    core::State state = core::initialState(model);
    for (int i = 0; i < cWarmUpSteps; ++i)
    {
        sim.step(state);
    }
    for (auto _ : st)
    {
        sim.step(state);
    }
    int moving = 0;
    for (const core::Body& b : model.bodies)
    {
        moving += b.isStatic ? 0 : 1;
    }
    st.counters["bodies"] = moving;
}

void BM_UrdfWelded(benchmark::State& st)
{
    stepModel(st, weldedChain(static_cast<int>(st.range(0))));
}

void BM_YamlFixedJoints(benchmark::State& st)
{
    const int k = static_cast<int>(st.range(0));
    stepModel(st, io::loadSceneFromString(yamlFixedJoints(k), "fixed_joints.yaml"));
}

void BM_YamlKBodies(benchmark::State& st)
{
    const int k = static_cast<int>(st.range(0));
    stepModel(st, io::loadSceneFromString(yamlKBodies(weldedChain(k), k), "k_bodies.yaml"));
}

} // namespace

BENCHMARK(BM_UrdfWelded)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_YamlKBodies)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_YamlFixedJoints)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
