// fuzz/scene_steps_fuzz.cpp: libFuzzer target for the whole path of `frontier run` after the file is
// read: run::loadSceneText (the YAML scene, its robots, meshes and targets, the finite-energy and
// starting-overlap checks), then run::Simulation (the contact detector's set-up, the simulator)
// and a few steps. A scene that loads must build and step, or stop with the errors a run reports
// (fuzz/fuzz_steps.h).
#include "fuzz/fuzz_input.h"
#include "fuzz/fuzz_steps.h"
#include "run/scene_loading.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace frontier;
    // As if the file were in scenes/robots (fuzz/yaml_scene_fuzz.cpp): its robots and meshes resolve.
    static const std::string sourceName = std::string(FRONTIER_SOURCE_DIR) + "/scenes/robots/fuzz.yaml";
    constexpr long cSteps = 10;
    const std::string text(reinterpret_cast<const char*>(data), size);
    return fuzz::expectInputErrorOnly(
        [&] { fuzz::stepModel(run::loadSceneText(text, sourceName).model, cSteps); });
}
