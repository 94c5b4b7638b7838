// render/meshes.h: triangle meshes (CPU side) for every shape type, built once per Renderer.
#pragma once

#include "core/model.h"

#include <vector>

namespace frontier::render
{

// Non-indexed triangles; each vertex is 6 floats: position xyz, unit normal xyz, in the shape
// frame. Triangles are counter-clockwise seen from outside.
struct MeshData
{
    std::vector<float> vertices;
    int vertexCount() const { return static_cast<int>(vertices.size() / 6); }
};

MeshData boxMesh(const core::Vec3& size);
MeshData sphereMesh(double radius, int slices, int stacks);
MeshData capsuleMesh(double radius, double length, int slices, int stacksPerCap);
MeshData cylinderMesh(double radius, double length, int slices);
// Flat-shaded: one normal per triangle.
MeshData triangleMesh(const std::vector<core::Vec3>& vertices,
                      const std::vector<std::array<int, 3>>& triangles);

// The mesh for a shape (Plane gives an empty mesh: the renderer draws a floor instead).
MeshData shapeMesh(const core::Shape& shape);

} // namespace frontier::render
