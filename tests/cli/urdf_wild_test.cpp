// tests/cli/urdf_wild_test.cpp: robot files as makers ship them, run with `frontier` and drawn
// with render::Renderer: meshes mirrored by a negative scale, a link whose visual mesh is missing.
#include "app_test_util.h"
#include "io/scene.h"
#include "render/renderer.h"

#include <filesystem>
#include <gtest/gtest.h>

namespace
{
using frontier::app::test::Result;
using frontier::app::test::shellQuote;
using frontier::app::test::TestDir;
namespace core = frontier::core;
namespace io = frontier::io;
namespace render = frontier::render;

// A 0.3 m tetrahedron (0,0,0) (0.3,0,0) (0,0.3,0) (0,0,0.3), faces outward: no mirror symmetry.
const char* const cWildTetraObj =
    "v 0 0 0\nv 0.3 0 0\nv 0 0.3 0\nv 0 0 0.3\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
// The same tetrahedron mirrored in y by hand: y negated, every face's corners reversed.
const char* const cWildTetraMirroredObj =
    "v 0 0 0\nv 0.3 0 0\nv 0 -0.3 0\nv 0 0 0.3\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";

// A one-link robot whose visual and collision are the mesh `file` at `scale`.
std::string wildMeshRobot(const std::string& file, const std::string& scale)
{
    const std::string mesh = "<geometry><mesh filename=\"" + file + "\" scale=\"" + scale + "\"/></geometry>";
    return "<robot name=\"tetra\">\n  <link name=\"a\">\n    <inertial><mass value=\"1\"/><inertia "
           "ixx=\"0.01\" "
           "ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial>\n    <visual>" +
           mesh + "</visual>\n    <collision>" + mesh + "</collision>\n  </link>\n</robot>\n";
}

// The scene's first state drawn without caption from a fixed camera above and to the side.
render::Image wildFrame(core::Model model)
{
    model.camera.automatic = false;
    model.camera.position = core::Vec3(1.0, -1.2, 1.0);
    model.camera.lookAt = core::Vec3(0.0, 0.0, 0.1);
    render::RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.caption = false;
    render::Renderer renderer(model, options);
    return renderer.render(core::initialState(model));
}

std::size_t differingPixels(const render::Image& a, const render::Image& b)
{
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4)
    {
        n += (a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2]) ? 1
                                                                                                          : 0;
    }
    return n;
}

TEST(UrdfWild, MirroredMeshRunsAndIsDrawnMirrored)
{
    const TestDir dir;
    dir.write("tetra.obj", cWildTetraObj);
    dir.write("tetra_mirrored.obj", cWildTetraMirroredObj);
    const std::string mirrored = dir.write("mirrored.urdf", wildMeshRobot("tetra.obj", "1 -1 1"));
    const Result r =
        dir.run("run " + shellQuote(mirrored) + " --duration 0.2 --fps 10 --width 64 --height 48 --frames " +
                shellQuote(dir.out("frames")));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir.out("frames/frame_00000.png"))) << r.err;

    // Drawn as the mesh mirrored in its file is drawn, and not as the unmirrored one.
    const render::Image byScale = wildFrame(io::loadScene(mirrored));
    const render::Image byFile =
        wildFrame(io::loadScene(dir.write("by_file.urdf", wildMeshRobot("tetra_mirrored.obj", "1 1 1"))));
    const render::Image unmirrored =
        wildFrame(io::loadScene(dir.write("plain.urdf", wildMeshRobot("tetra.obj", "1 1 1"))));
    EXPECT_EQ(differingPixels(byScale, byFile), 0u);
    EXPECT_GT(differingPixels(byScale, unmirrored), 100u);
}

// trunk (its <visual> is `trunkVisual`, its collision a box) welded to marker (a visual sphere
// 0.5 m up): the body has visuals whatever the trunk's are.
std::string wildTrunkRobot(const std::string& trunkVisual)
{
    return R"(<robot name="dog">
  <link name="trunk">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    )" + trunkVisual +
           R"(
    <collision><origin xyz="0.1 0 0"/><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
  </link>
  <joint name="marker_fixed" type="fixed"><parent link="trunk"/><child link="marker"/><origin xyz="0 0 0.5"/></joint>
  <link name="marker">
    <visual><geometry><sphere radius="0.05"/></geometry></visual>
  </link>
</robot>
)";
}

TEST(UrdfWild, ALinkWhoseVisualMeshIsMissingIsDrawnAsItsCollisionBox)
{
    const TestDir dir;
    const std::string missing = dir.write(
        "missing.urdf",
        wildTrunkRobot(R"(<visual><geometry><mesh filename="no_such_trunk.dae"/></geometry></visual>)"));
    const Result r =
        dir.run("run " + shellQuote(missing) + " --duration 0.1 --fps 10 --width 64 --height 48 --frames " +
                shellQuote(dir.out("frames")));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find(missing + ":4:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("warning: visual mesh 'no_such_trunk.dae' of link 'trunk' cannot be read"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("the link is drawn from its collision shapes"), std::string::npos) << r.err;

    // Drawn as a trunk whose visual is its collision box, and unlike a trunk with no visual at all.
    const render::Image drawn = wildFrame(io::loadScene(missing));
    const render::Image asBox = wildFrame(io::loadScene(dir.write(
        "box.urdf",
        wildTrunkRobot(
            R"(<visual><origin xyz="0.1 0 0"/><geometry><box size="0.4 0.2 0.1"/></geometry></visual>)"))));
    const render::Image invisible = wildFrame(io::loadScene(dir.write("none.urdf", wildTrunkRobot(""))));
    EXPECT_EQ(differingPixels(drawn, asBox), 0u);
    EXPECT_GT(differingPixels(drawn, invisible), 500u); // of 160 x 120: where the box is
}

} // namespace
