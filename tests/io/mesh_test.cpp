// tests/io/mesh_test.cpp: mesh files (STL, OBJ, COLLADA) written here with known geometry, read
// directly and through scenes (volume, vertices, units, node transforms, winding, errors).
#include "io/mass_properties.h"
#include "io/mesh_file.h"
#include "io/scene.h"
#include "io_test_util.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>
#include <sys/stat.h>

namespace frontier::io::test
{
namespace
{

using detail::loadMeshFile;
using Triangle = std::array<core::Vec3, 3>;

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

// Corner i of the unit cube [0, 1]^3: bit 0 is x, bit 1 is y, bit 2 is z.
core::Vec3 cubeCorner(int i)
{
    return core::Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
}

// The unit cube's faces as quads of corner indices, counter-clockwise seen from outside
// (z = 0, z = 1, y = 0, y = 1, x = 0, x = 1).
constexpr std::array<std::array<int, 4>, 6> cCubeQuads = {
    {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};

std::vector<Triangle> unitCubeTriangles()
{
    std::vector<Triangle> out;
    for (const auto& q : cCubeQuads)
    {
        out.push_back({cubeCorner(q[0]), cubeCorner(q[1]), cubeCorner(q[2])});
        out.push_back({cubeCorner(q[0]), cubeCorner(q[2]), cubeCorner(q[3])});
    }
    return out;
}

std::string asciiStl(const std::vector<Triangle>& triangles)
{
    std::string out = "solid cube\n";
    for (const Triangle& t : triangles)
    {
        out += "facet normal 0 0 0\nouter loop\n";
        for (const core::Vec3& v : t)
        {
            out += "vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
                   std::to_string(v.z()) + "\n";
        }
        out += "endloop\nendfacet\n";
    }
    return out + "endsolid cube\n";
}

std::string binaryStl(const std::vector<Triangle>& triangles)
{
    std::string data(80, ' ');
    const auto count = static_cast<std::uint32_t>(triangles.size());
    data.append(reinterpret_cast<const char*>(&count), 4);
    for (const Triangle& t : triangles)
    {
        float values[12] = {0, 0, 0}; // normal, then the corners
        for (int k = 0; k < 3; ++k)
        {
            for (int c = 0; c < 3; ++c)
            {
                values[3 + 3 * k + c] = static_cast<float>(t[static_cast<std::size_t>(k)][c]);
            }
        }
        data.append(reinterpret_cast<const char*>(values), sizeof(values));
        data.append(2, '\0');
    }
    return data;
}

const std::vector<Triangle> cTetraTriangles = {
    {core::Vec3(0, 0, 0), core::Vec3(0, 1, 0), core::Vec3(1, 0, 0)},
    {core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 0, 1)},
    {core::Vec3(0, 0, 0), core::Vec3(0, 0, 1), core::Vec3(0, 1, 0)},
    {core::Vec3(1, 0, 0), core::Vec3(0, 1, 0), core::Vec3(0, 0, 1)}};

// A COLLADA file in units of `meter` metres with the given <up_axis>, holding one geometry, the
// tetrahedron (0,0,0) (100,0,0) (0,200,0) (0,0,300) in file units with outward faces, instanced
// by the nodes in `nodes` (XML of <node> elements; "#tetra" names the geometry).
std::string colladaTetra(const std::string& meter, const std::string& upAxis, const std::string& nodes)
{
    return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter=")" +
           meter + R"(" name="unit"/><up_axis>)" + upAxis + R"(</up_axis></asset>
  <library_geometries>
    <geometry id="tetra" name="tetra">
      <mesh>
        <source id="tetra-pos">
          <float_array id="tetra-pos-array" count="12">0 0 0 100 0 0 0 200 0 0 0 300</float_array>
          <technique_common>
            <accessor source="#tetra-pos-array" count="4" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="tetra-vtx"><input semantic="POSITION" source="#tetra-pos"/></vertices>
        <triangles count="4">
          <input semantic="VERTEX" source="#tetra-vtx" offset="0"/>
          <p>0 2 1 0 1 3 0 3 2 1 2 3</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">)" +
           nodes + R"(</visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

const char* const cInstance = R"(<instance_geometry url="#tetra"/>)";

// Signed volume by the divergence theorem: positive when the closed surface faces outwards.
double signedVolume(const core::Shape& shape)
{
    double sixTimes = 0.0;
    for (const auto& t : shape.triangles)
    {
        const core::Vec3& a = shape.vertices.at(static_cast<std::size_t>(t[0]));
        const core::Vec3& b = shape.vertices.at(static_cast<std::size_t>(t[1]));
        const core::Vec3& c = shape.vertices.at(static_cast<std::size_t>(t[2]));
        sixTimes += a.dot(b.cross(c));
    }
    return sixTimes / 6.0;
}

// Every expected point is a vertex (within tol) and there are no others.
void expectVertexSet(const core::Shape& shape, const std::vector<core::Vec3>& expected, double tol)
{
    EXPECT_EQ(shape.vertices.size(), expected.size());
    for (const core::Vec3& e : expected)
    {
        double nearest = 1e300;
        for (const core::Vec3& v : shape.vertices)
        {
            nearest = std::min(nearest, (v - e).norm());
        }
        EXPECT_LE(nearest, tol) << "no vertex at " << e.transpose();
    }
}

// Every triangle of a convex shape faces away from `centre`.
void expectOutwardFaces(const core::Shape& shape, const core::Vec3& centre)
{
    for (const auto& t : shape.triangles)
    {
        const core::Vec3& a = shape.vertices.at(static_cast<std::size_t>(t[0]));
        const core::Vec3& b = shape.vertices.at(static_cast<std::size_t>(t[1]));
        const core::Vec3& c = shape.vertices.at(static_cast<std::size_t>(t[2]));
        EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre), 0.0);
    }
}

std::vector<core::Vec3> scaledCubeCorners(const core::Vec3& scale)
{
    std::vector<core::Vec3> out;
    for (int i = 0; i < 8; ++i)
    {
        out.push_back(cubeCorner(i).cwiseProduct(scale));
    }
    return out;
}

core::Model loadMeshScene(const TempDir& dir, const std::string& file)
{
    const std::string scene =
        dir.write("scene.yaml", "bodies: [{name: m, density: 6, shape: {type: mesh, file: " + file + "}}]\n");
    return loadScene(scene);
}

// A mesh error raised at the scene's `file:` node: the scene's place, the mesh path and `reason`.
void expectSceneMeshError(const TempDir& dir, const std::string& file, const std::string& reason)
{
    const InputError e = captureInputError([&] { loadMeshScene(dir, file); });
    EXPECT_INPUT_ERROR_AT(
        e, dir.file("scene.yaml"), 1,
        static_cast<int>(std::string("bodies: [{name: m, density: 6, shape: {type: mesh, file: ").size()) + 1,
        "cannot read mesh file '" + dir.file(file) + "'");
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
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
    dir.write("tetra.stl", binaryStl(cTetraTriangles));
    const core::Model model = loadMeshScene(dir, "tetra.stl");
    EXPECT_NEAR(model.bodies.at(0).mass, 1.0, 1e-14);
    EXPECT_EQ(model.bodies.at(0).shapes.at(0).vertices.size(), 4u);
}

TEST(Mesh, AsciiStlCubeScaled)
{
    TempDir dir;
    const std::string path = dir.write("cube.stl", asciiStl(unitCubeTriangles()));
    const core::Vec3 scale(0.5, 2.0, 3.0);
    const core::Shape shape = loadMeshFile(path, scale);
    EXPECT_EQ(shape.type, core::ShapeType::Mesh);
    EXPECT_EQ(shape.meshFile, path);
    EXPECT_EQ(shape.triangles.size(), 12u);
    expectVertexSet(shape, scaledCubeCorners(scale), 0.0); // corners merged, exact
    expectOutwardFaces(shape, 0.5 * scale);
    EXPECT_NEAR(signedVolume(shape), 3.0, 1e-14);
}

TEST(Mesh, BinaryStlCube)
{
    TempDir dir;
    const std::string path = dir.write("cube.stl", binaryStl(unitCubeTriangles()));
    const core::Shape shape = loadMeshFile(path, core::Vec3::Ones());
    EXPECT_EQ(shape.triangles.size(), 12u);
    expectVertexSet(shape, scaledCubeCorners(core::Vec3::Ones()), 0.0);
    expectOutwardFaces(shape, core::Vec3::Constant(0.5));
}

TEST(Mesh, ObjQuadsAreSplitIntoOutwardTriangles)
{
    TempDir dir;
    std::string obj = "# unit cube, one quad per face\n";
    for (int i = 0; i < 8; ++i)
    {
        const core::Vec3 c = cubeCorner(i);
        obj +=
            "v " + std::to_string(c.x()) + " " + std::to_string(c.y()) + " " + std::to_string(c.z()) + "\n";
    }
    for (const auto& q : cCubeQuads)
    {
        obj += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " +
               std::to_string(q[2] + 1) + " " + std::to_string(q[3] + 1) + "\n";
    }
    const std::string path = dir.write("cube.obj", obj);
    const core::Vec3 scale(1.0, 2.0, 3.0);
    const core::Shape shape = loadMeshFile(path, scale);
    EXPECT_EQ(shape.triangles.size(), 12u);
    expectVertexSet(shape, scaledCubeCorners(scale), 0.0);
    expectOutwardFaces(shape, 0.5 * scale);
    EXPECT_NEAR(signedVolume(shape), 6.0, 1e-14);
}

TEST(Mesh, ObjNegativeIndicesAndSlashes)
{
    TempDir dir;
    // The texture and normal indices refer to a defined vt and vn (assimp refuses undefined ones).
    dir.write("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\n"
                           "f 1//1 3//1 2//1\nf -4/1/1 -3/1/1 -1/1/1\nf 1 4 3\nf 2 3 4\n");
    const core::Model model = loadMeshScene(dir, "tetra.obj");
    EXPECT_NEAR(model.bodies.at(0).mass, 1.0, 1e-14);
    EXPECT_EQ(model.bodies.at(0).shapes.at(0).vertices.size(), 4u);
}

// <unit meter="0.01">: file coordinates in centimetres; Z_UP kept as it is (no rotation to y-up).
TEST(Mesh, ColladaUnitAndZUp)
{
    TempDir dir;
    const std::string path = dir.write(
        "part.dae", colladaTetra("0.01", "Z_UP", std::string(R"(<node id="a">)") + cInstance + "</node>"));
    const core::Shape shape = loadMeshFile(path, core::Vec3::Ones());
    EXPECT_EQ(shape.triangles.size(), 4u);
    expectVertexSet(shape, {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}}, 1e-6);
    EXPECT_NEAR(signedVolume(shape), 1.0, 1e-6); // 1 x 2 x 3 / 6 m^3, faces outward

    // The caller's scale multiplies the unit.
    const core::Shape scaled = loadMeshFile(path, core::Vec3(2.0, 1.0, 0.5));
    expectVertexSet(scaled, {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1.5}}, 1e-6);
}

TEST(Mesh, ColladaYUpIsAlsoKeptAsItIs)
{
    TempDir dir;
    const std::string path = dir.write(
        "part.dae", colladaTetra("1", "Y_UP", std::string(R"(<node id="a">)") + cInstance + "</node>"));
    expectVertexSet(loadMeshFile(path, core::Vec3::Ones()),
                    {{0, 0, 0}, {100, 0, 0}, {0, 200, 0}, {0, 0, 300}}, 1e-4);
}

// Two instances: one translated, one rotated with a translated child node. Without the node
// transforms both would land on the same four vertices.
TEST(Mesh, ColladaNodeTransformsAreApplied)
{
    TempDir dir;
    const std::string nodes = std::string(R"(<node id="a"><translate>10 0 0</translate>)") + cInstance +
                              R"(</node>
      <node id="b"><rotate>0 0 1 90</rotate>
        <node id="c"><translate>0 0 100</translate>)" +
                              cInstance + "</node></node>";
    const std::string path = dir.write("parts.dae", colladaTetra("0.01", "Z_UP", nodes));
    const core::Shape shape = loadMeshFile(path, core::Vec3::Ones());
    EXPECT_EQ(shape.triangles.size(), 8u);
    // a: the tetrahedron (m) + (0.1, 0, 0). b then c: Rz(90 deg) (p + (0, 0, 1)), Rz(x, y, z) = (-y, x, z).
    expectVertexSet(
        shape,
        {{0.1, 0, 0}, {1.1, 0, 0}, {0.1, 2, 0}, {0.1, 0, 3}, {0, 0, 1}, {0, 1, 1}, {-2, 0, 1}, {0, 0, 4}},
        1e-6);
    EXPECT_NEAR(signedVolume(shape), 2.0, 1e-6);
}

TEST(Mesh, ColladaMirroredNodeStillFacesOutwards)
{
    TempDir dir;
    const std::string path =
        dir.write("mirror.dae",
                  colladaTetra("0.01", "Z_UP",
                               std::string(R"(<node id="m"><scale>-1 1 1</scale>)") + cInstance + "</node>"));
    const core::Shape shape = loadMeshFile(path, core::Vec3::Ones());
    expectVertexSet(shape, {{0, 0, 0}, {-1, 0, 0}, {0, 2, 0}, {0, 0, 3}}, 1e-6);
    EXPECT_NEAR(signedVolume(shape), 1.0, 1e-6);
}

// Each vertex of `shape` with its coordinates multiplied by `scale`, worked out here.
std::vector<core::Vec3> mirroredVertices(const core::Shape& shape, const core::Vec3& scale)
{
    std::vector<core::Vec3> out;
    for (const core::Vec3& v : shape.vertices)
    {
        out.push_back(v.cwiseProduct(scale));
    }
    return out;
}

TEST(Mesh, NegativeScaleMirrorsAndKeepsTheSurfaceFacingOutwards)
{
    TempDir dir;
    const std::string path = dir.write("tetra.stl", binaryStl(cTetraTriangles));
    const core::Shape plain = loadMeshFile(path, core::Vec3::Ones());
    // One, two and three negative components: an odd number mirrors, an even one rotates.
    for (const core::Vec3& scale : {core::Vec3(1, -1, 1), core::Vec3(-1, -1, 1), core::Vec3(-2, -1, -0.5)})
    {
        SCOPED_TRACE(testing::Message() << "scale " << scale.transpose());
        const core::Shape shape = loadMeshFile(path, scale);
        EXPECT_EQ(shape.triangles.size(), 4u);
        expectVertexSet(shape, mirroredVertices(plain, scale), 0.0);
        const double volume_m3 = std::abs(scale.prod()) / 6.0;
        EXPECT_NEAR(signedVolume(shape), volume_m3, 1e-12);
        expectOutwardFaces(shape, scale / 4.0); // the centroid, inside
    }
}

TEST(Mesh, MirroredMeshHasTheMirroredMassProperties)
{
    TempDir dir;
    const std::string path = dir.write("tetra.stl", binaryStl(cTetraTriangles));
    const double density = 6.0; // kg/m^3: the tetrahedron of volume 1/6 m^3 weighs 1 kg
    const detail::CompositeMass plain =
        detail::compositeMassProperties({loadMeshFile(path, core::Vec3::Ones())}, density);
    const detail::CompositeMass mirrored =
        detail::compositeMassProperties({loadMeshFile(path, core::Vec3(1, -1, 1))}, density);
    EXPECT_NEAR(plain.mass, 1.0, 1e-12);
    EXPECT_NEAR(mirrored.mass, 1.0, 1e-12);
    EXPECT_NEAR((plain.centre - core::Vec3(0.25, 0.25, 0.25)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((mirrored.centre - core::Vec3(0.25, -0.25, 0.25)).norm(), 0.0, 1e-12);
    // Mirroring y: the products of inertia with y change sign, the rest stay.
    const core::Mat3 flipY = core::Vec3(1, -1, 1).asDiagonal();
    EXPECT_NEAR((mirrored.inertia - flipY * plain.inertia * flipY).norm(), 0.0, 1e-12);
    EXPECT_GT(std::abs(plain.inertia(0, 1)), 1e-3); // kg m^2: a product that mirroring changes
}

TEST(Mesh, ColladaThroughASceneWithScale)
{
    TempDir dir;
    dir.write("part.dae",
              colladaTetra("0.01", "Z_UP", std::string(R"(<node id="a">)") + cInstance + "</node>"));
    const std::string scene = dir.write(
        "scene.yaml", "bodies: [{name: m, density: 3, shape: {type: mesh, file: part.dae, scale: 2}}]\n");
    const core::Model model = loadScene(scene);
    // Volume 1 m^3 from the file, times 2^3 from the scale; centroid (1, 2, 3) / 4 x 2.
    EXPECT_NEAR(model.bodies.at(0).mass, 3.0 * 8.0, 1e-4);
    EXPECT_NEAR((model.bodies.at(0).position_W - core::Vec3(0.5, 1.0, 1.5)).norm(), 0.0, 1e-6);
}

TEST(Mesh, BinaryStlWithWrongSize)
{
    TempDir dir;
    std::string data = binaryStl({cTetraTriangles[0]});
    data.pop_back();
    dir.write("bad.stl", data);
    expectSceneMeshError(dir, "bad.stl", "Failed to determine STL storage representation");
}

TEST(Mesh, ObjIndexOutOfRange)
{
    TempDir dir;
    dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    // assimp does not say which line; the scene's mesh node and the file are named.
    expectSceneMeshError(dir, "bad.obj", "OBJ: vertex index out of range");
}

TEST(Mesh, AsciiStlFacetWithTwoVertices)
{
    TempDir dir;
    dir.write(
        "bad.stl",
        "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n");
    expectSceneMeshError(dir, "bad.stl", "STL: Invalid number of vertices");
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

TEST(Mesh, UnknownFormat)
{
    TempDir dir;
    dir.write("thing.xyz", "not a mesh\n");
    expectSceneMeshError(dir, "thing.xyz", "No suitable reader found");
}

TEST(Mesh, EmptyColladaDocument)
{
    TempDir dir;
    dir.write("thing.dae", "<COLLADA/>");
    expectSceneMeshError(dir, "thing.dae", "Collada");
}

TEST(Mesh, NonFiniteVertex)
{
    TempDir dir;
    const std::string path = dir.write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, path, 0, 0, "non-finite vertex");
}

TEST(Mesh, NoTrianglesIsAnError)
{
    TempDir dir;
    // The geometry exists but no node places it.
    const std::string path = dir.write("none.dae", colladaTetra("1", "Z_UP", R"(<node id="empty"/>)"));
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, path, 0, 0, "mesh file has no triangles");
    // Points and lines only: nothing to collide with or draw either.
    const std::string lines = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n");
    const InputError l = captureInputError([&] { loadMeshFile(lines, core::Vec3::Ones()); });
    EXPECT_EQ(l.file(), lines);
    EXPECT_NE(std::string(l.what()).find("No meshes remaining"), std::string::npos) << l.what();
}

TEST(Mesh, MissingFile)
{
    TempDir dir;
    const InputError e = captureInputError([&] { loadMeshFile(dir.file("nope.stl"), core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, dir.file("nope.stl"), 0, 0, "no such mesh file");
}

// Refused before assimp sees them: a FIFO would block the reader, /dev/zero never ends.
TEST(Mesh, OnlyRegularFilesAreRead)
{
    TempDir dir;
    const InputError d = captureInputError([&] { loadMeshFile(dir.path().string(), core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(d, dir.path().string(), 0, 0, "is a directory, expected a mesh file");

    const std::string fifo = dir.file("pipe.stl");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const InputError f = captureInputError([&] { loadMeshFile(fifo, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(f, fifo, 0, 0, "is not a regular file");

    const InputError z = captureInputError([&] { loadMeshFile("/dev/zero", core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(z, "/dev/zero", 0, 0, "is not a regular file");
}

// Files that assimp opens itself (an OBJ's mtllib) pass the same checks: a FIFO or a link to
// /dev/zero beside the OBJ is refused at once, naming the OBJ's mtllib line.
TEST(Mesh, ObjMaterialFileThatIsNotARegularFileIsRefused)
{
    TempDir dir;
    const std::string fifo = dir.file("pipe.mtl");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::filesystem::create_symlink("/dev/zero", dir.file("zero.mtl"));
    const std::string faces = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    for (const std::string material : {"pipe.mtl", "zero.mtl"})
    {
        const std::string obj = dir.write("tetra.obj", "# tetrahedron\nmtllib " + material + "\n" + faces);
        const InputError e = captureInputError([&] { loadMeshFile(obj, core::Vec3::Ones()); });
        EXPECT_INPUT_ERROR_AT(e, obj, 2, 0, "refers to '");
        EXPECT_NE(e.message().find(material + "': is not a regular file"), std::string::npos) << e.what();
    }
    // A material file that is missing is not an error (assimp reads the geometry without it).
    const std::string obj = dir.write("tetra.obj", "mtllib missing.mtl\n" + faces);
    EXPECT_EQ(loadMeshFile(obj, core::Vec3::Ones()).triangles.size(), 4u);
}

// The 1-based line of the first `needle` in `text`.
int lineOfText(const std::string& text, const std::string& needle)
{
    const std::size_t at = text.find(needle);
    return at == std::string::npos
               ? 0
               : 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

// Hostile COLLADA node trees are refused before assimp reads them, at the node or reference that
// goes beyond the limits (scenes/README.md "Meshes"): assimp recursed into a node that instances
// itself and into 10 000 nested nodes until the stack overflowed, and expanded 30 levels of
// doubling instances until memory ran out.
TEST(Mesh, ColladaThatInstancesItselfIsRefusedAtTheReference)
{
    TempDir dir;
    const std::string text =
        colladaTetra("1", "Z_UP",
                     std::string("\n<node id=\"a\">") + cInstance +
                         "\n<node id=\"b\">\n<instance_node url=\"#a\"/>\n</node></node>\n");
    const std::string path = dir.write("self.dae", text);
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, path, lineOfText(text, "<instance_node"), 1,
                          "instances a node that contains it");
    // Through a scene: the mesh file's own line is kept.
    const InputError s = captureInputError([&] { loadMeshScene(dir, "self.dae"); });
    EXPECT_EQ(s.file(), path);
    EXPECT_EQ(s.line(), lineOfText(text, "<instance_node"));
}

TEST(Mesh, ColladaWithTenThousandNestedNodesIsRefused)
{
    TempDir dir;
    std::string nodes = "\n";
    for (int k = 0; k < 10000; ++k)
    {
        nodes += "<node id=\"n" + std::to_string(k) + "\">\n";
    }
    nodes += cInstance;
    for (int k = 0; k < 10000; ++k)
    {
        nodes += "</node>\n";
    }
    const std::string text = colladaTetra("1", "Z_UP", nodes);
    const std::string path = dir.write("deep.dae", text);
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, path, lineOfText(text, "<node id=\"n256\">"), 1,
                          "nodes nested more than 256 levels deep, the limit for a mesh file");
}

TEST(Mesh, ColladaThatDoublesItsNodesThirtyTimesIsRefused)
{
    TempDir dir;
    // n0 holds the tetrahedron; n1..n29 each instance the one before twice: 2^30 instances.
    std::string library = "<library_nodes>\n<node id=\"n0\">" + std::string(cInstance) + "</node>\n";
    for (int k = 1; k < 30; ++k)
    {
        const std::string before = "<instance_node url=\"#n" + std::to_string(k - 1) + "\"/>";
        library += "<node id=\"n" + std::to_string(k) + "\">" + before + before + "</node>\n";
    }
    library += "</library_nodes>\n";
    std::string text = colladaTetra("1", "Z_UP", "<node id=\"top\"><instance_node url=\"#n29\"/></node>");
    text.insert(text.find("<library_visual_scenes>"), library);
    const std::string path = dir.write("doubling.dae", text);
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    // n16 is the first to expand to more than 100 000 nodes (2^17 - 1).
    EXPECT_INPUT_ERROR_AT(e, path, lineOfText(text, "<node id=\"n16\">"), 1,
                          "expands to more than 100000 nodes (instances counted), the limit for a mesh file");
}

// Instances within the limits load as before; beyond the vertex limit the file is refused after
// assimp reads it (10 000 instances of a geometry of 3 300 vertices: 33 million).
TEST(Mesh, ColladaInstancesAreCountedAgainstTheVertexLimit)
{
    TempDir dir;
    std::string text =
        colladaTetra("1", "Z_UP",
                     "<node id=\"a\"><instance_node url=\"#part\"/></node>"
                     "<node id=\"b\"><translate>1000 0 0</translate><instance_node url=\"#part\"/></node>");
    text.insert(text.find("<library_visual_scenes>"),
                "<library_nodes><node id=\"part\">" + std::string(cInstance) + "</node></library_nodes>\n");
    const std::string twice = dir.write("twice.dae", text);
    const core::Shape shape = loadMeshFile(twice, core::Vec3::Ones());
    EXPECT_EQ(shape.vertices.size(), 8u);
    EXPECT_EQ(shape.triangles.size(), 8u);

    std::string indices;
    for (int k = 0; k < 1100; ++k)
    {
        indices += "0 2 1 ";
    }
    std::string wide = colladaTetra("1", "Z_UP", "<node id=\"top\"><instance_node url=\"#w4\"/></node>");
    const std::size_t p = wide.find("<p>");
    wide.replace(p, wide.find("</p>") - p, "<p>" + indices);
    wide.replace(wide.find("<triangles count=\"4\">"), 21, "<triangles count=\"1100\">");
    std::string library = "<library_nodes><node id=\"w0\">" + std::string(cInstance) + "</node>\n";
    for (int k = 1; k <= 4; ++k)
    {
        library += "<node id=\"w" + std::to_string(k) + "\">";
        for (int c = 0; c < 10; ++c)
        {
            library += "<instance_node url=\"#w" + std::to_string(k - 1) + "\"/>";
        }
        library += "</node>\n";
    }
    wide.insert(wide.find("<library_visual_scenes>"), library + "</library_nodes>\n");
    const std::string path = dir.write("wide.dae", wide);
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, path, 0, 0,
                          "mesh file expands to more than 30000000 vertices (every instance of its meshes "
                          "counted), the limit for a mesh file");
}

TEST(Mesh, TooLargeFileIsRefused)
{
    TempDir dir;
    const std::string path = dir.write("huge.stl", "");
    std::filesystem::resize_file(path, (std::uintmax_t{256} << 20) + 1); // sparse: no disk space used
    const InputError e = captureInputError([&] { loadMeshFile(path, core::Vec3::Ones()); });
    EXPECT_INPUT_ERROR_AT(e, path, 0, 0,
                          "mesh file has 268435457 bytes, above the limit of 268435456 bytes (set "
                          "FRONTIER_MAX_INPUT_BYTES to raise it)");
}

} // namespace
} // namespace frontier::io::test
