// fuzz/yaml_scene_fuzz.cpp: libFuzzer target for YAML scenes (io::loadScene's YAML path), the
// text given as if it were a file in scenes/robots, so that a scene's URDF models, meshes and csv
// targets resolve against the bundled robots.
#include "fuzz/fuzz_input.h"
#include "io/yaml_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace frontier;
    static const std::string sourceName = std::string(FRONTIER_SOURCE_DIR) + "/scenes/robots/fuzz.yaml";
    const std::string text(reinterpret_cast<const char*>(data), size);
    return fuzz::expectInputErrorOnly(
        [&]
        {
            io::LoadReport report;
            io::detail::loadYamlScene(text, sourceName, io::UrdfOptions{}, &report);
        });
}
