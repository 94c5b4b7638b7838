// tests/io/mesh_test.cpp: OBJ and STL meshes through scenes (volume, faces, errors).
#include "io/scene.h"
#include "io_test_util.h"

#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>

namespace frontier::io::test
{
namespace
{

// A tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), outward-facing: volume 1/6.
const char* const cTetraAsciiStl = R"(
solid tetra
  facet normal 0 0 -1
    outer loop
      vertex 0 0 0
      vertex 0 1 0
      vertex 1 0 0
    endloop
  endfacet
  facet normal 0 -1 0
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 0 0 1
    endloop
  endfacet
  facet normal -1 0 0
    outer loop
      vertex 0 0 0
      vertex 0 0 1
      vertex 0 1 0
    endloop
  endfacet
  facet normal 1 1 1
    outer loop
      vertex 1 0 0
      vertex 0 1 0
      vertex 0 0 1
    endloop
  endfacet
endsolid tetra
)";

std::string binaryStl(const std::vector<std::array<float, 9>>& triangles)
{
    std::string data(80, ' ');
    const auto count = static_cast<std::uint32_t>(triangles.size());
    data.append(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : triangles)
    {
        const float normal[3] = {0, 0, 0};
        data.append(reinterpret_cast<const char*>(normal), sizeof(normal));
        data.append(reinterpret_cast<const char*>(t.data()), sizeof(float) * 9);
        data.append(2, '\0');
    }
    return data;
}

core::Model loadMeshScene(const TempDir& dir, const std::string& file)
{
    const std::string scene =
        dir.write("scene.yaml", "bodies: [{name: m, density: 6, shape: {type: mesh, file: " + file + "}}]\n");
    return loadScene(scene);
}

TEST(Mesh, AsciiStlTetrahedron)
{
    TempDir dir;
    dir.write("tetra.stl", text(cTetraAsciiStl));
    const core::Model model = loadMeshScene(dir, "tetra.stl");
    const core::Body& b = model.bodies.at(0);
    EXPECT_NEAR(b.mass, 1.0, 1e-14);               // density 6 x volume 1/6
    EXPECT_EQ(b.shapes.at(0).vertices.size(), 4u); // shared corners merged
    EXPECT_EQ(b.shapes.at(0).triangles.size(), 4u);
    EXPECT_NEAR((b.position_W - core::Vec3(0.25, 0.25, 0.25)).norm(), 0.0, 1e-14);
}

TEST(Mesh, BinaryStlTetrahedron)
{
    TempDir dir;
    dir.write("tetra.stl", binaryStl({{0, 0, 0, 0, 1, 0, 1, 0, 0},
                                      {0, 0, 0, 1, 0, 0, 0, 0, 1},
                                      {0, 0, 0, 0, 0, 1, 0, 1, 0},
                                      {1, 0, 0, 0, 1, 0, 0, 0, 1}}));
    const core::Model model = loadMeshScene(dir, "tetra.stl");
    EXPECT_NEAR(model.bodies.at(0).mass, 1.0, 1e-14);
    EXPECT_EQ(model.bodies.at(0).shapes.at(0).vertices.size(), 4u);
}

TEST(Mesh, BinaryStlWithWrongSize)
{
    TempDir dir;
    std::string data = binaryStl({{0, 0, 0, 0, 1, 0, 1, 0, 0}});
    data.pop_back();
    dir.write("bad.stl", data);
    const InputError e = captureInputError([&] { loadMeshScene(dir, "bad.stl"); });
    EXPECT_EQ(e.file(), dir.file("scene.yaml"))
        << e.what(); // a whole-file problem: reported at the scene node
    EXPECT_NE(std::string(e.what()).find("binary STL declares 1 triangles"), std::string::npos) << e.what();
}

TEST(Mesh, ObjNegativeIndicesAndSlashes)
{
    TempDir dir;
    dir.write("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n"
                           "f 1//1 3//1 2//1\nf -4/1/1 -3/1/1 -1/1/1\nf 1 4 3\nf 2 3 4\n");
    const core::Model model = loadMeshScene(dir, "tetra.obj");
    EXPECT_NEAR(model.bodies.at(0).mass, 1.0, 1e-14);
}

TEST(Mesh, ObjIndexOutOfRange)
{
    TempDir dir;
    dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    const InputError e = captureInputError([&] { loadMeshScene(dir, "bad.obj"); });
    EXPECT_INPUT_ERROR_AT(e, dir.file("bad.obj"), 4, 7,
                          "vertex index 4 is out of range (3 vertices defined so far)");
}

TEST(Mesh, AsciiStlFacetWithTwoVertices)
{
    TempDir dir;
    dir.write(
        "bad.stl",
        "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n");
    const InputError e = captureInputError([&] { loadMeshScene(dir, "bad.stl"); });
    EXPECT_INPUT_ERROR_AT(e, dir.file("bad.stl"), 2, 1, "expected a facet with 3 vertices, got 2");
}

TEST(Mesh, InsideOutMeshOnAMovingBodyIsAnError)
{
    TempDir dir;
    // The tetrahedron with every face reversed: negative volume.
    dir.write("inverted.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n");
    const InputError e = captureInputError([&] { loadMeshScene(dir, "inverted.obj"); });
    EXPECT_EQ(e.file(), dir.file("scene.yaml"));
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(std::string(e.what()).find("encloses no positive volume"), std::string::npos) << e.what();
}

TEST(Mesh, UnsupportedFormat)
{
    TempDir dir;
    dir.write("thing.dae", "<COLLADA/>");
    const InputError e = captureInputError([&] { loadMeshScene(dir, "thing.dae"); });
    EXPECT_NE(std::string(e.what()).find("unsupported mesh format '.dae'; expected .obj or .stl"),
              std::string::npos)
        << e.what();
}

} // namespace
} // namespace frontier::io::test
