// Internal to host/object (mesh.cpp's load_mesh): one reader per mesh file format. Each reads the file at `path` as
// it is, with no welding, repair or validation, names the file in every MeshError, and sets Mesh::name to `path`.
#pragma once

#include <string>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::formats {

// The paper's RAW triangles (parse_raw on the file's bytes).
Mesh read_raw(const std::string& path);
// PLY, ASCII or binary, by this program's reader (assimp 5.2's hangs on damaged files): ply.cpp.
Mesh read_ply(const std::string& path);
// OFF through assimp, once its header's counts are found to fit the file (assimp allocates for them first).
Mesh read_off(const std::string& path);
// Wavefront OBJ through assimp; a file of vertex lines and no faces is a point cloud.
Mesh read_obj(const std::string& path);
// Any other format assimp reads (STL, glTF, 3MF, ...); meshes of points only make a point cloud.
Mesh read_assimp(const std::string& path);

// The file's lower-case extension without the dot ("" when it has none).
std::string lower_ext(const std::string& path);

}  // namespace voxcd::formats
