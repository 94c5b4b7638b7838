// fuzz/mesh_fuzz.cpp: libFuzzer target for mesh files (io::detail::loadMeshFile, assimp behind the
// project's input checks). The first byte picks the file's extension, which picks assimp's
// importer; the rest is the file (scripts/fuzz.sh seeds prefix each bundled mesh with its byte).
#include "fuzz/fuzz_input.h"
#include "io/mesh_file.h"

#include <array>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace frontier;
    if (size == 0)
    {
        return 0;
    }
    // Index = first byte % 5: '0' (0x30 = 48) is .stl, '1' .obj, '2' .dae, '3' .ply, '4' .off.
    static constexpr std::array<const char*, 5> cExtensions = {".stl", ".obj", ".dae", ".ply", ".off"};
    const std::string path =
        fuzz::writeInput(data + 1, size - 1, std::string("mesh") + cExtensions[data[0] % 5]);
    return fuzz::expectInputErrorOnly([&] { io::detail::loadMeshFile(path, core::Vec3(1.0, 1.0, 1.0)); });
}
