// tests/app/load_test.cpp: loading under a signal and with hostile meshes, end to end: a signal
// while a large mesh loads ends the process at once (128 + the signal, nothing written); a COLLADA
// file that would expand without bound exits 2 naming the mesh file, its line and the limit.
#include "app_test_util.h"

#include <cstdint>
#include <cstring>

namespace frontier::app::test
{
namespace
{

// A binary STL of `triangles` triangles (a flat grid 1000 cells wide, two triangles a cell).
void writeGridStl(const std::string& path, std::uint32_t triangles)
{
    std::string data(84 + std::size_t{50} * triangles, '\0');
    std::memcpy(&data[80], &triangles, 4);
    for (std::uint32_t t = 0; t < triangles; ++t)
    {
        const float x = static_cast<float>((t / 2) % 1000) * 0.001f;
        const float y = static_cast<float>((t / 2) / 1000) * 0.001f;
        const float d = 0.001f;
        const float upper[12] = {0, 0, 1, x, y, 0, x + d, y, 0, x + d, y + d, 0};
        const float lower[12] = {0, 0, 1, x, y, 0, x + d, y + d, 0, x, y + d, 0};
        std::memcpy(&data[84 + std::size_t{50} * t], t % 2 == 0 ? upper : lower, 48);
    }
    std::ofstream(path, std::ios::binary) << data;
}

// SIGTERM while a mesh of two million triangles is read (seconds of work inside assimp and the
// vertex merging) ends the run within a checkpoint: exit 143, the message says it stopped while
// loading, and no output (nor a temporary file) exists. It used to finish loading first and stop
// at step 0, leaving failed outputs behind.
TEST(Load, SignalWhileLoadingALargeMeshStopsTheLoad)
{
    const TestDir dir;
    writeGridStl((dir.path() / "grid.stl").string(), 2000000);
    const std::string scene = dir.write(
        "scene.yaml", "bodies: [{name: ground, static: true, shape: {type: mesh, file: grid.stl}}]\n");
    const pid_t pid = spawnFrontier(dir, {"run", scene, "--steps", "10", "--quiet", "--trajectory",
                                          dir.out("t.csv"), "--stats", dir.out("s.json")});
    ASSERT_GT(pid, 0);
    ASSERT_TRUE(waitForHandler(pid, SIGTERM, 30.0)); // installed just before the scene is read
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ::kill(pid, SIGTERM);
    EXPECT_EQ(waitForExit(pid, 120.0), 143);
    const std::string err = readText(dir.path() / "stderr.txt");
    EXPECT_EQ(err, "frontier: interrupted by SIGTERM while loading " + scene + "; nothing written\n");
    EXPECT_TRUE(dir.outputs().empty()) << dir.outputs().front();
}

// 30 levels that each instance the level before twice: 3 KB of COLLADA that assimp expanded into
// 2^30 nodes until memory ran out. Refused before assimp reads it: exit 2 at the mesh file's line.
TEST(Load, ColladaThatExpandsWithoutBoundExitsTwoAtItsLine)
{
    const TestDir dir;
    std::string dae = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array><technique_common>
<accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/>
<param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_nodes>
<node id="n0"><instance_geometry url="#g"/></node>
)";
    for (int k = 1; k < 30; ++k)
    {
        const std::string before = "<instance_node url=\"#n" + std::to_string(k - 1) + "\"/>";
        dae += "<node id=\"n" + std::to_string(k) + "\">" + before + before + "</node>\n";
    }
    dae += R"(</library_nodes>
<library_visual_scenes><visual_scene id="s"><node id="top"><instance_node url="#n29"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
    const std::string mesh = dir.write("doubling.dae", dae);
    const std::string scene = dir.write(
        "scene.yaml", "bodies: [{name: ground, static: true, shape: {type: mesh, file: doubling.dae}}]\n");
    const Result r = dir.run("info " + shellQuote(scene));
    EXPECT_EQ(r.exitCode, 2) << r.err;
    // n16 (line 11 + 16) is the first node to expand beyond 100 000 nodes (2^17 - 1).
    EXPECT_EQ(
        r.err,
        "frontier: " + mesh +
            ":27:1: error: this node expands to more than 100000 nodes (instances counted), the limit for a "
            "mesh file\n");
}

} // namespace
} // namespace frontier::app::test
