// bench/startup_bench.cpp: what it costs to start a large scene (docs/benchmarks.md, "Start-up"):
// a chain of n boxes (0.08 x 0.02 x 0.02 m, 0.1 kg) on ball joints hanging from the world, laid
// along x like scenes/tools/make_chain.py writes it, either built in code or loaded from a scene
// file, then the contact detector and the simulator set up and 10 steps taken, as `frontier run`
// does. One row per process, so that the peak memory is this size's own:
//
//   startup_bench N              the chain built in code (load = building the core::Model)
//   startup_bench --scene FILE   the scene loaded from FILE (load = io::loadScene)
//
// Columns (CPU seconds): bodies, load s, set-up s of the contact detector and of the simulator (with the
// initial state), first 10 steps s, max RSS MB (getrusage), KB per body (max RSS / bodies); then
// the heap each part holds, KB per body (glibc's mallinfo2, mmapped blocks included, measured as
// the increase over the part before): the model, the contact detector, the state, and the
// simulator after the 10 steps (its solver's rows, factor blocks and vectors; the detector's
// per-step buffers are small) and at its set-up; then the same parts as resident memory (Linux
// /proc/self/statm). The two differ: an array of 2 MiB or more (core/large_vector.h) is mapped
// with up to 2 MiB of alignment slack that mallinfo2 counts and no page backs, and memory the
// scene loader freed is resident already when a later part reuses it (--scene: the later parts'
// resident figures are low, the model's includes the loader's).
#include "collision/contacts.h"
#include "core/model.h"
#include "core/simulator.h"
#include "core/state.h"
#include "io/scene.h"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <malloc.h>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

namespace
{

using namespace frontier;
using core::Vec3;

constexpr double cPitch = 0.1;  // m between link centres
constexpr double cMass = 0.1;   // kg per link
constexpr double cHeight = 2.0; // m
constexpr int cSteps = 10;

core::Model makeChain(int n)
{
    core::Model model;
    model.name = "chain of " + std::to_string(n) + " boxes";
    model.simulation.dt = 0.001;
    core::Shape box;
    box.type = core::ShapeType::Box;
    box.size = Vec3(0.08, 0.02, 0.02);
    const core::MassProperties props = core::shapeMassProperties(box, 1000.0);
    model.bodies.reserve(static_cast<std::size_t>(n));
    model.joints.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
        core::Body body;
        body.name = "link" + std::to_string(i);
        body.mass = cMass;
        body.inertia_B = props.inertia * (cMass / props.mass);
        body.shapes.push_back(box);
        body.position_W = Vec3((i + 0.5) * cPitch, 0.0, cHeight);
        model.bodies.push_back(std::move(body));
    }
    for (int i = 0; i < n; ++i)
    {
        core::Joint joint;
        joint.name = "j" + std::to_string(i);
        joint.type = core::JointType::Ball;
        joint.parent = i == 0 ? core::cWorld : i - 1;
        joint.child = i;
        core::setJointFrames(model, joint, Vec3(i * cPitch, 0.0, cHeight), Vec3::UnitZ());
        model.joints.push_back(std::move(joint));
    }
    return model;
}

// CPU seconds (user + system, page faults included) of this single-threaded process: a shared,
// loaded machine inflates them far less than wall time.
double cpuSeconds()
{
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Bytes of heap in use now (small blocks and mmapped ones).
double heapBytes()
{
    const struct mallinfo2 info = mallinfo2();
    return static_cast<double>(info.uordblks + info.hblkhd);
}

// Bytes of the process resident now (pages in memory, shared libraries included).
double residentBytes()
{
    long pages = 0;
    if (std::FILE* statm = std::fopen("/proc/self/statm", "r"))
    {
        long total = 0;
        if (std::fscanf(statm, "%ld %ld", &total, &pages) != 2)
        {
            pages = 0;
        }
        std::fclose(statm);
    }
    return static_cast<double>(pages) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

// Heap and resident bytes at one moment.
struct Memory
{
    double heap = heapBytes();
    double resident = residentBytes();
};

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2 && !(argc == 3 && std::string(argv[1]) == "--scene"))
    {
        std::fprintf(stderr, "usage: startup_bench N | startup_bench --scene FILE\n");
        return 2;
    }
    const Memory atStart;
    double start = cpuSeconds();
    const core::Model model = argc == 3 ? io::loadScene(argv[2]) : makeChain(std::atoi(argv[1]));
    const double loadS = cpuSeconds() - start;
    const Memory withModel;

    start = cpuSeconds();
    collision::ContactDetector detector(model, collision::contactMargin(model.simulation.dt));
    const double detectorS = cpuSeconds() - start;
    const Memory withDetector;
    start = cpuSeconds();
    core::Simulator simulator(model, {}, &detector);
    const Memory withSimulator;
    core::State state = core::initialState(model);
    const Memory withState;
    const double simulatorS = cpuSeconds() - start;

    start = cpuSeconds();
    for (int k = 0; k < cSteps; ++k)
        simulator.step(state);
    const double stepsS = cpuSeconds() - start;
    const Memory afterSteps;

    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double rssMB = static_cast<double>(usage.ru_maxrss) / 1024.0; // ru_maxrss is in KB
    const auto bodies = static_cast<double>(model.bodies.size());
    std::printf(
        "bodies %zu  load %.3f s  detector %.3f s  simulator %.3f s  %d steps %.3f s  max RSS %.1f MB  "
        "%.2f KB/body\n",
        model.bodies.size(), loadS, detectorS, simulatorS, cSteps, stepsS, rssMB,
        bodies > 0 ? static_cast<double>(usage.ru_maxrss) / bodies : 0.0);
    const double perBodyKB = bodies > 0 ? 1.0 / (1024.0 * bodies) : 0.0;
    auto parts = [&](const char* label, double Memory::*bytes)
    {
        std::printf("%s KB/body  model %.2f  detector %.2f  state %.2f  simulator %.2f (%.2f at set-up)\n",
                    label, (withModel.*bytes - atStart.*bytes) * perBodyKB,
                    (withDetector.*bytes - withModel.*bytes) * perBodyKB,
                    (withState.*bytes - withSimulator.*bytes) * perBodyKB,
                    (afterSteps.*bytes - withDetector.*bytes - (withState.*bytes - withSimulator.*bytes)) *
                        perBodyKB,
                    (withSimulator.*bytes - withDetector.*bytes) * perBodyKB);
    };
    parts("heap", &Memory::heap);
    parts("resident", &Memory::resident);
    return 0;
}
