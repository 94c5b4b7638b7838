// io/mesh_file.h: triangle meshes from Wavefront .obj and STL (ASCII or binary) files.
#pragma once

#include "core/model.h"

#include <string>

namespace frontier::io::detail
{

// A Mesh shape with the file's vertices (m) multiplied component-wise by `scale`, faces as
// triangles (OBJ polygons split as fans). Throws InputError naming the mesh file and, for bad
// content, the line. An unknown extension is an error.
core::Shape loadMeshFile(const std::string& path, const core::Vec3& scale);

} // namespace frontier::io::detail
