// An object type as a scene uses it: the object file (voxmap and point shell) plus what collision queries derive
// from it once: the penetration depth of every voxel and bounding volumes in the object's frame.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "voxcd/host/object/object_file.h"

namespace voxcd {

struct ObjectType {
  std::string name;
  ObjectFile object;
  // Per voxel (linear index), in voxels: the distance from the voxel's centre to the centre of the nearest surface
  // voxel; 0 for surface and empty voxels. The penetration estimate of a contact (docs/pairs.md bounds its error).
  std::vector<float> depth;
  // Bounds in the object's frame of everything that can take part in a contact: the voxmap's non-empty voxels and
  // the shell points.
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // of the smallest enclosing sphere (host/object/bounds.h)
  double radius = 0;
  // The mesh the type was voxelised from, in the type's frame (as scaled and centred by the scene); null for an
  // object file used as it is. Recordings draw the type with it (host/scene/record.h).
  std::shared_ptr<const Mesh> mesh;

  const Voxmap& voxmap() const { return object.voxmap; }
  const PointShell& shell() const { return object.shell; }
};

// Derives depth and bounds (from the dense forms: add_dense_forms makes them of a sparse object). MeshError when the
// voxmap has no surface voxel (nothing to collide with), or a sparse object is too large for its dense forms.
ObjectType make_object_type(ObjectFile obj, const std::string& name);

// An object type from an object file (recognised by its magic, whatever its name), a mesh file or a built-in
// shape name; meshes and shapes are voxelised at `voxel` (which must then be > 0), with a distance field of
// `distance_bits` (4, 8, 16; 0: none) over `band` voxels, in the forms `storage` asks for. An object file must have a
// field of distance_bits when distance_bits > 0, and is taken in the forms it was saved in. Errors name the argument.
ObjectType load_object_type(const std::string& file_or_shape, double voxel, int distance_bits = 0,
                            double band = 4.0, ObjectStorage storage = ObjectStorage::kDense);

// An object used as it is where distance voxmaps of `distance_bits` (4, 8, 16) are asked for must carry a field of
// exactly that many bits: MeshError "NAME: the object has no distance field; 8 bits were asked for ..." otherwise.
// Nothing is asked of it when distance_bits is 0. load_object_type checks object files with it; the Python module
// checks its Objects.
void require_distance_bits(const ObjectFile& obj, int distance_bits, const std::string& name);

// The voxel that puts `resolution` voxels along the longest side of the largest mesh or shape among `sources`
// (its bounding box's longest side / resolution); object files are left out (they have their voxel), and with
// nothing else it is 0. `voxcd pair`'s voxel when none is given (resolution 32 by default). MeshError from
// load_source, or for a resolution below kMinVoxelsAcross.
double shared_voxel(const std::vector<std::string>& sources, uint32_t resolution);

// True when the file starts with the object file's magic.
bool is_object_file(const std::string& path);

}  // namespace voxcd
