// Scene files: a JSON description of a scene (object types, how many of each, the environment) and of what is asked
// of the device that tests it (accuracy, frame rate, clock). `voxcd simulate SCENE.json` runs one, `voxcd size`
// derives the smallest device for one. docs/scenes.md documents every key.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/scene/scene.h"

namespace voxcd {

// A scene file that cannot be used: the message starts with the file and the JSON path of the key at fault,
// e.g. "mixed.json: types[1].voxel: -1 is not > 0".
struct SceneFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One object type of a scene file and its instance count.
struct SceneTypeSpec {
  std::string key;      // its JSON path, for messages: "types[1]"
  std::string name;     // label (default: the shape name, or the mesh file's name)
  std::string shape;    // a built-in shape name, or
  std::string mesh;     // a mesh file, resolved against the scene file's directory
  double size = 0;      // largest extent of the object's box, world units (0: not given)
  double scale = 0;     // factor on the mesh's coordinates (0: not given)
  double voxel = 0;     // voxmap voxel size, world units (0: not given)
  uint32_t resolution = 0;  // or voxels along the object's longest side (0: not given); neither: default_voxel
  uint64_t count = 1;   // instances
  bool auto_scaled() const { return size == 0 && scale == 0; }
};

struct SceneFile {
  std::string where;  // the file (or the name given to the parser), for messages
  std::vector<SceneTypeSpec> types;
  // The environment (docs/simulate.md): the cube, the fill of the types without a size or scale, motion, seed.
  double side = 100;
  double density = 0.025;
  bool density_given = false;
  double speed = 0.1;
  double spin = 0.02;
  uint64_t seed = 1;
  // What is asked of the device.
  double accuracy = 0;   // world units; 0: not given (accuracy_or_default)
  double contact_accuracy = 0;  // world units: how far outside the other surface a contact may lie (voxcd size);
                                // 0: not given
  double rate = 1000;    // frames per second
  // The device clock for its frame rates: the file's "clock" (MHz), "given by <file>'s \"clock\"", or without
  // it default_device_clock() (OpenSTA's clock of the default configuration, docs/hardware.md).
  DeviceClock clock = default_device_clock();
  uint64_t frames = 100; // frames `voxcd size` simulates to measure pairs and points
  // How the scene is run.
  std::string broadphase = "grid";
  std::string backend = "cpu";
  std::string mode = "ALL";
  bool both_directions = false;
  int distance_bits = 0;  // "distance_bits": 4, 8 or 16 (distance voxmaps); 0: not given (2-bit states)
  double band = 4.0;      // "band": the distance fields' band, voxels
  bool ccd = false;       // "ccd": continuous collision (needs distance_bits)

  // The requested accuracy, or by default 1/50 of the smallest voxel of the scene's types: of the scene made from
  // the file (make_scene resolves the types' resolutions and default voxels), or without it of the voxels the file
  // gives (1 where a type gives none: the paper's).
  double accuracy_or_default(const Scene& scene) const;
  double accuracy_or_default() const;
  double smallest_voxel() const;  // of the voxels the file gives (1 for a type that gives none)
  uint64_t objects() const;
};

// Parses a scene file's text; `where` names it in messages and its directory resolves relative mesh paths.
// SceneFileError naming the JSON path for malformed JSON, an unknown key, a wrong type or a value out of range.
// Touches no file (mesh files are read by make_scene).
SceneFile parse_scene_file(std::string_view text, const std::string& where);
// Reads and parses a file; SceneFileError when it cannot be read.
SceneFile read_scene_file(const std::string& path);

// The scene of a scene file: its types scaled as asked and voxelised at their voxel, their resolution or by default
// at default_voxel of one object's volume (each shell fine enough for the smallest voxmap of the scene), and their instances placed at random without overlapping bounding spheres, as make_scene
// places one type's. SceneFileError naming the key for a missing or unreadable mesh, a size that does not fit the
// cube or a voxel that makes an object too large or too small for a voxmap.
Scene make_scene(const SceneFile& f);

// Each type's mesh in its type's frame, as make_scene places it (centred on its box, scaled as asked): what a
// contact is checked against exactly. make_scene's SceneFileError for a missing or unreadable mesh or a fill that
// does not fit the cube.
std::vector<Mesh> scene_meshes(const SceneFile& f);

}  // namespace voxcd
