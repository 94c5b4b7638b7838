// io/mesh_file.h: triangle meshes from files, read with assimp (STL, OBJ, COLLADA and the other
// formats it knows). The one place where mesh files are read.
#pragma once

#include "core/model.h"

#include <string>

namespace frontier::io::detail
{

// A Mesh shape in the shape frame (m): the file's node transforms and unit (COLLADA
// <unit meter>) applied, the file's up axis ignored (as robot files expect), vertices then
// multiplied component-wise by `scale` (nonzero; negative components mirror); polygons
// triangulated, identical vertices merged, triangles in the file's winding (counter-clockwise seen
// from outside for a well-formed file), reversed where node transforms and scale mirror.
// Coordinates pass through assimp's single precision (about 1e-7 relative).
// Throws InputError(path, 0, 0, ...) naming what was wrong: not a regular file, too large,
// unreadable by assimp (its reason), non-finite vertices, or no triangles.
core::Shape loadMeshFile(const std::string& path, const core::Vec3& scale);

} // namespace frontier::io::detail
