// Objects (public: <voxcd/voxcd.h>): a mesh voxelised once into a voxmap (or a distance field) and a point shell,
// ready for collide() and a World. Made from a mesh file, arrays, a built-in shape or an object file.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/storage.h"

namespace voxcd {

// How an object is made; the defaults make a 2-bit voxmap 32 voxels along the mesh's longest side.
struct ObjectDef {
  double voxel = 0;          // voxel edge in mesh units; 0: from `resolution`
  uint32_t resolution = 32;  // voxels along the longest side, when `voxel` is 0
  int distance_bits = 0;     // 4, 8 or 16: a distance field too (sub-voxel contacts, docs/pairs.md); 0: none
  double band = 4;           // the distance field's band, voxels
  // How a mesh's voxmap, shell and field are kept (docs/objects.md, "Sparse objects"): dense (the default), sparse,
  // or auto (each in whichever form takes less device memory). A sparse object runs on a sparse device.
  ObjectStorage storage = ObjectStorage::kDense;
  bool strict = false;       // refuse a mesh that is not a closed manifold instead of repairing it
  unsigned threads = 0;      // 0: every hardware thread; never changes the object
  std::string name;          // for messages and reports; by default the file, the shape or "arrays"
};

class Object {
 public:
  // A mesh file (any format `voxcd voxelize` reads), a built-in shape (shape_names()), or an object file (which
  // brings its own voxel; with distance_bits it must carry a field of that many bits). MeshError or
  // ObjectFileError saying what is wrong and where.
  static Object load(const std::string& file_or_shape, const ObjectDef& def = {});
  // A mesh given as arrays: `vertices` x, y, z each (row-major, n_vertices rows), `triangles` three vertex indices
  // each. Repaired as a file is (unless def.strict); MeshError for an index out of range or nothing usable.
  static Object from_arrays(const double* vertices, size_t n_vertices, const uint32_t* triangles, size_t n_triangles,
                            const ObjectDef& def = {});
  static Object from_arrays(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>& vertices,
                            const Eigen::Ref<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>& triangles,
                            const ObjectDef& def = {});
  // A mesh already in memory (repaired unless def.strict).
  static Object from_mesh(Mesh mesh, const ObjectDef& def = {});

  const std::string& name() const;
  double voxel() const;                      // voxel edge, mesh units
  std::array<uint32_t, 3> dims() const;      // voxels along x, y, z
  size_t shell_count() const;                // points of the point shell
  // The point shell, one point a row in the object's frame, in the order a Contact's `point` indexes them (Python's
  // Object.shell_points); shell_normals() their outward unit normals. voxcd::Error for a shell stored sparse on a grid
  // too large for its dense form (over 1024 cells an axis: docs/objects.md, "Sparse objects").
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> shell_points() const;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> shell_normals() const;
  int distance_bits() const;                 // 0 without a distance field
  const MeshReport& report() const;          // what loading and repair found and did
  // Writes the object file (as `voxcd voxelize -o`), atomically; ObjectFileError when it cannot.
  void save(const std::string& path) const;

  struct Impl;  // the library's form of the object (internal: host/api/access.h)

 private:
  friend struct ApiAccess;  // the library's own door (internal: host/api/access.h)
  explicit Object(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
};

}  // namespace voxcd
