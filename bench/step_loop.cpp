// bench/step_loop.cpp: the C++ half of bench/python_step.sh: a scene loaded as `frontier run`
// loads it (run::loadScene), stepped one run::Simulation::step() call at a time, in the loop a
// Python user writes with the frontier module (bench/python_step.py). One measurement per process:
//
//   step_loop SCENE STEPS step [REPS]   STEPS calls of step()
//   step_loop SCENE STEPS read [REPS]   the same, copying every body's position (n x 3 doubles, as
//                                       sim.positions does) after each step
//   step_loop SCENE STEPS peek [REPS]   one step, then STEPS copies of the positions alone: the
//                                       cost of reading them, per call
//
// The scene is loaded afresh for each of REPS repetitions (default 3) and the fastest loop kept.
// Times are the process's CPU time (CLOCK_PROCESS_CPUTIME_ID), so that other processes on a
// shared machine do not count. Prints one line: `mode=M bodies=N steps=S seconds=T per_step_us=U`
// (the loop only; loading is not timed). Exit status 2 on bad arguments or input.
#include "io/scene.h"
#include "run/scene_loading.h"
#include "run/simulation.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <string>
#include <vector>

namespace
{

using namespace frontier;

int usage()
{
    std::fprintf(stderr, "usage: step_loop SCENE STEPS step|read|peek [REPS]\n");
    return 2;
}

double cpuSeconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Every body's position, body order, as one row-major n x 3 array (what sim.positions returns).
void copyPositions(const core::State& state, std::vector<double>& out)
{
    out.resize(3 * state.bodies.size());
    double* p = out.data();
    for (const core::BodyState& body : state.bodies)
    {
        *p++ = body.position_W.x();
        *p++ = body.position_W.y();
        *p++ = body.position_W.z();
    }
}

struct Loop
{
    double seconds = 0.0;  // CPU s
    double checksum = 0.0; // keeps the copies from being optimised away
    std::size_t bodies = 0;
};

Loop timeLoop(const char* path, long steps, const std::string& mode)
{
    const run::LoadedScene scene = run::loadScene(path);
    run::Simulation simulation(scene.model);
    std::vector<double> positions;
    Loop out;
    out.bodies = scene.model.bodies.size();
    if (mode == "peek")
    {
        simulation.step();
    }
    const double start = cpuSeconds();
    for (long k = 0; k < steps; ++k)
    {
        if (mode != "peek")
        {
            simulation.step();
        }
        if (mode != "step")
        {
            copyPositions(simulation.state(), positions);
            out.checksum += positions[2];
        }
    }
    out.seconds = cpuSeconds() - start;
    return out;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 4 && argc != 5)
    {
        return usage();
    }
    const std::string mode = argv[3];
    char* end = nullptr;
    const long steps = std::strtol(argv[2], &end, 10);
    if (*end != '\0' || steps < 1 || (mode != "step" && mode != "read" && mode != "peek"))
    {
        return usage();
    }
    const long reps = argc == 5 ? std::strtol(argv[4], &end, 10) : 3;
    if (*end != '\0' || reps < 1)
    {
        return usage();
    }
    try
    {
        Loop best;
        double checksum = 0.0;
        for (long rep = 0; rep < reps; ++rep)
        {
            const Loop loop = timeLoop(argv[1], steps, mode);
            checksum += loop.checksum;
            if (rep == 0 || loop.seconds < best.seconds)
            {
                best = loop;
            }
        }
        std::printf("mode=%s bodies=%zu steps=%ld seconds=%.6f per_step_us=%.4f checksum=%.3g\n",
                    mode.c_str(), best.bodies, steps, best.seconds,
                    1e6 * best.seconds / static_cast<double>(steps), checksum);
    }
    catch (const io::InputError& e)
    {
        std::fprintf(stderr, "step_loop: %s\n", e.what());
        return 2;
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "step_loop: %s\n", e.what());
        return 1;
    }
    return 0;
}
