// Loads a scene or robot as `frontier run` does, steps it for SECONDS (default: the scene's
// duration) and prints each moving body's position at the end as `time,body,px,py,pz` with the
// trajectory CSV's 17 digits: the same as `frontier run SCENE --duration SECONDS --trajectory t.csv`.
#include "run/scene_loading.h"
#include "run/simulation.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv)
{
    using namespace frontier;
    if (argc < 2)
    {
        std::fprintf(stderr, "usage: run_a_scene SCENE [SECONDS]\n");
        return 2;
    }
    try
    {
        // Starting overlaps of a robot's links excluded, placement, hold servos: as the CLI.
        const run::LoadedScene scene = run::loadScene(argv[1]); // throws io::InputError
        const core::Model& model = scene.model;
        const double seconds = argc > 2 ? std::atof(argv[2]) : model.simulation.duration;
        // The contact detector with the CLI's margin and step time, the simulator, the state.
        run::Simulation simulation(model);
        simulation.step(std::lround(seconds / model.simulation.dt)); // throws core::SimulationError
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            if (!model.bodies[i].isStatic)
            {
                const core::Vec3& p = simulation.state().bodies[i].position_W; // m
                std::printf("%.17g,%s,%.17g,%.17g,%.17g\n", simulation.time(), model.bodies[i].name.c_str(),
                            p.x(), p.y(), p.z());
            }
        }
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
