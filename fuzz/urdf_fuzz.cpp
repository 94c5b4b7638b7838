// fuzz/urdf_fuzz.cpp: libFuzzer target for URDF models (io::loadScene on a .urdf: the XML checks,
// urdfdom, the conversion into bodies and joints, meshes, placement on the floor). Package URIs
// resolve against the bundled robots in scenes/robots.
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace frontier;
    const std::string path = fuzz::writeInput(data, size, "robot.urdf");
    return fuzz::expectInputErrorOnly(
        [&]
        {
            io::UrdfOptions options;
            options.packagePaths = {std::string(FRONTIER_SOURCE_DIR) + "/scenes/robots"};
            io::LoadReport report;
            io::loadScene(path, options, &report);
        });
}
