// The viewer's object page (`voxcd view OBJECT`): an object file, a mesh or a built-in shape with its voxmap, point
// shell, distance field and repair report, as the JSON the page reads (docs/view.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/view/repair_places.h"

namespace voxcd::view {

struct ObjectView {
  std::string name;     // as given on the command line
  ObjectFile object;
  Mesh surface;         // what the page draws: the object's mesh, or its voxmap's surface
  bool from_mesh = false;
  std::string note;     // why the mesh is not drawn (from_mesh false), "" otherwise
  std::optional<RepairPlaces> places;  // where repair changed the mesh, when its input could be read again
};

// An object file as it is (its mesh from its source when that is a shape or the unchanged file); a mesh or shape
// voxelised at `voxel` world units, or at `resolution` voxels along its longest side when voxel is 0, with a
// distance field of `distance_bits` (0: none). MeshError, ObjectFileError as loading throws them.
ObjectView make_object_view(const std::string& file_or_shape, double voxel, uint32_t resolution, int distance_bits,
                            double band);

// What the page is sent of a large object at most (docs/view.md, "An object"): boxes of the voxmap's bricks and of
// the distance field's bricks (each), shell points (every k-th beyond), and bytes of the voxmap's states and of the
// field's node values (each; neither is sent beyond).
struct ViewLimits {
  size_t boxes = size_t{1} << 16;
  size_t shell_points = size_t{1} << 18;
  uint64_t array_bytes = uint64_t{1} << 25;
};

// The page's data: {"kind": "object", ...} (docs/view.md lists the keys).
std::string object_view_json(const ObjectView& v, const ViewLimits& limits = {});

}  // namespace voxcd::view
