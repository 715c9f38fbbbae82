// Scene files: a JSON description of a run (object types, how many of each, the environment, what is asked of the
// device that tests it, how it runs), read into a RunConfig. `voxcd simulate SCENE.json` runs one, `voxcd size`
// derives the smallest device for one. docs/scenes.md documents every key.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "voxcd/host/scene/run_config.h"
#include "voxcd/host/scene/scene.h"

namespace voxcd {

// The requested accuracy, or by default 1/50 of the smallest voxel of the scene's types: of the scene made from
// the configuration (make_scene resolves the types' resolutions and default voxels), or without it of the voxels
// the configuration gives (RunConfig::accuracy_or_default).
double accuracy_or_default(const RunConfig& c, const Scene& scene);

// The run configuration of a scene file's text (its frames 100 unless given); `where` names it in messages and its
// directory resolves relative mesh paths. SceneFileError naming the JSON path for malformed JSON, an unknown key, a
// wrong type, or a value check() refuses. Touches no file (mesh files are read by make_scene).
RunConfig parse_scene_file(std::string_view text, const std::string& where);
// Reads and parses a file; SceneFileError when it cannot be read.
RunConfig read_scene_file(const std::string& path);

// The scene of a scene file's configuration: its types scaled as asked and voxelised at their voxel, their
// resolution or by default at default_voxel of one object's volume (each shell fine enough for the smallest voxmap
// of the scene), and their instances placed at random without overlapping bounding spheres, as the built-in scene
// places one type's. SceneFileError naming the key for a missing or unreadable mesh, a size that does not fit the
// cube or a voxel that makes an object too large or too small for a voxmap.
Scene make_file_scene(const RunConfig& f);

// Each type's mesh in its type's frame, as make_scene places it (centred on its box, scaled as asked): what a
// contact is checked against exactly. make_scene's SceneFileError for a missing or unreadable mesh or a fill that
// does not fit the cube.
std::vector<Mesh> scene_meshes(const RunConfig& f);

}  // namespace voxcd
