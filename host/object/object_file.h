// The object file: a processed mesh (voxmap as the device's memory image, point shell as device words plus float
// points and normals, or either in its sparse form) saved once and reused. docs/objects.md gives the byte layout.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/errors.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/host/object/sparse_shell.h"
#include "voxcd/host/object/sparse_voxmap.h"
#include "voxcd/host/object/storage.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd {

struct ObjectFile {
  std::string source;            // mesh path as given, or "shape:NAME" for a built-in shape
  uint64_t source_hash = 0;      // FNV-1a 64 of the source file's bytes (of the string "shape:NAME" for a shape)
  double shell_ratio = 0;        // target voxel / shell spacing the shell was built with
  Eigen::Vector3d shift = Eigen::Vector3d::Constant(0.5);  // VoxelizeOptions::shift used for both grids
  // The voxmap and the shell, each dense, sparse or both. A sparse form is the stored one (write_object writes it);
  // the dense form is empty (no words, no points) when only the sparse one is held (read_object says when).
  Voxmap voxmap;
  PointShell shell;              // built for target voxel = the voxmap's voxel
  SparseVoxmap sparse_voxmap;    // the voxmap stored sparse (cells() > 0), docs/objects.md "Sparse objects"
  SparseShell sparse_shell;      // the shell stored sparse (not empty)
  DistanceField distance;        // the signed distance field on the voxmap's grid (empty unless asked for)
  // The field stored sparse, with refined bricks (docs/objects.md, "Sparse distance field"): an object holds this or
  // `distance`, never both; the accessors below read whichever it holds.
  SparseDistanceField sparse_distance;
  // What loading, repair and voxelising found (file version 2; a version 1 file has none: has_report false).
  bool has_report = false;
  MeshReport mesh_report;
  VoxelizeReport voxelize_report;

  bool voxmap_sparse() const { return sparse_voxmap.cells() > 0; }
  bool shell_sparse() const { return !sparse_shell.empty(); }
  bool has_dense_voxmap() const { return !voxmap.words().empty(); }
  bool has_dense_shell() const { return !shell_sparse() || shell.size() > 0; }
  // The voxmap's grid and its voxels per state, from whichever form is held.
  const GridPlacement& voxmap_grid() const { return voxmap_sparse() ? sparse_voxmap.grid() : voxmap.grid(); }
  std::array<uint64_t, 4> voxmap_counts() const { return voxmap_sparse() ? sparse_voxmap.counts() : voxmap.counts(); }
  bool distance_sparse() const { return !sparse_distance.empty(); }
  // The distance field, from whichever form is held: whether there is one, its bits (0: none), step (voxels a unit),
  // band (voxels) and largest value; its interpolant at grid point g (voxels) as the device computes it, with the
  // gradient; whether g's cell shares a node with a conservative cell (a hit there has the 2-bit bound).
  bool has_distance() const { return !distance.empty() || distance_sparse(); }
  int distance_bits() const { return distance_sparse() ? sparse_distance.bits() : distance.bits; }
  double distance_step() const { return distance_sparse() ? sparse_distance.step() : distance.step; }
  double distance_band() const { return distance_sparse() ? sparse_distance.band() : distance.band(); }
  int distance_qmax() const { return distance_sparse() ? sparse_distance.qmax() : distance.qmax(); }
  double distance_at(const Eigen::Vector3d& g, Eigen::Vector3d* gradient = nullptr) const {
    return distance_sparse() ? sparse_distance.sample(g, gradient) : distance.sample(g, gradient);
  }
  bool distance_near_conservative(const Eigen::Vector3d& g) const;
  // The shell's grid and point count, from whichever form is held.
  const GridPlacement& shell_grid() const { return shell_sparse() ? sparse_shell.grid : shell.grid; }
  size_t shell_count() const { return shell_sparse() ? sparse_shell.size() : shell.size(); }
};


// The largest dense voxmap an object holds, per axis (the default device's 2^DW): larger grids are sparse only.
constexpr uint32_t kMaxDenseDim = 1024;
// The largest sparse shell grid per axis: an origin word's z holds 2^14 shell voxels with the default PW 24, PF 8.
constexpr uint32_t kMaxSparseShellDim = 16384;

// What make_object builds: the voxmap at `voxel`, the shell for target voxel `voxel` at spacing voxel / shell_ratio.
struct ObjectOptions {
  double voxel = 0;                                        // finite, > 0; or resolution > 0
  uint32_t resolution = 0;                                 // > 0: voxel = longest side / resolution
  double shell_ratio = std::sqrt(2.0);                     // the paper's rule
  Eigen::Vector3d shift = Eigen::Vector3d::Constant(0.5);  // VoxelizeOptions::shift, for both grids
  uint32_t max_dim = 1024;                                 // voxmap grid per axis (VoxelizeOptions::max_dim)
  unsigned threads = 0;                                    // 0: every hardware thread; never changes the result
  int distance_bits = 0;                                   // 4, 8 or 16: also build the distance field; 0: none
  double band = 4.0;                                       // the field's band, voxels (DistanceOptions::band)
  ObjectStorage storage = ObjectStorage::kDense;           // which forms to build
};

// Sets opt.storage and the grid limit that goes with it, as voxcd voxelize does: a dense object (or one with a
// distance field, which is dense) up to kMaxDenseDim voxels per axis, a sparse or auto one up to kMaxSparseDim.
void set_storage(ObjectOptions& opt, ObjectStorage storage);
// "auto", "dense" or "sparse" as an ObjectStorage; std::nullopt for anything else.
std::optional<ObjectStorage> parse_storage(const std::string& name);

// The mesh named by `mesh_or_shape`: an existing file (load_mesh: RAW or any assimp format), else a built-in shape.
// Sets *source ("shape:NAME" or the path) and *hash (hash_file or hash_bytes of the source string). MeshError when
// it is neither, naming the argument and listing the shapes; MeshError from load_mesh for a bad file.
// *report gets what loading and repair found (for a shape: a closed mesh, nothing repaired). opt.strict refuses
// any defect (load_mesh).
Mesh load_source(const std::string& mesh_or_shape, std::string* source = nullptr, uint64_t* hash = nullptr,
                 MeshReport* report = nullptr, const LoadOptions& opt = {});

// Voxmap and shell of a mesh as load_source left it, in the forms opt.storage asks for; `report` (what loading found)
// is kept in the object file. With distance_bits, also the distance field (distance_field) and the shell on the
// surface (surface_shell). MeshError as voxelize, point_shell and distance_field throw them, for distance bits not 0,
// 4, 8 or 16, and for a distance field asked of a sparse object.
ObjectFile make_object(const Mesh& mesh, const std::string& source, uint64_t source_hash, const ObjectOptions& opt,
                       const MeshReport* report = nullptr);

// FNV-1a 64 of a file's bytes (ObjectFileError when unreadable) and of a string.
uint64_t hash_file(const std::string& path);
uint64_t hash_bytes(const std::string& bytes);

// Writes the object file (atomically: a temporary file renamed into place): version 5 when the voxmap or the shell is
// held sparse (the sparse forms are written), else version 3 or 4 when the object has a distance field, a shell on
// the surface or the report's second section, else version 2 exactly as before. ObjectFileError on I/O failure.
void write_object(const std::string& path, const ObjectFile& obj);
// What read_object builds of an object stored sparse: the stored forms only, or also the dense forms of those that
// fit (a voxmap of at most kMaxDenseDim per axis, a shell grid of at most 4096), as the collision queries take them.
enum class ObjectRead { kStored, kWithDense };
// Reads and checks an object file (magic, version, sizes, CRC-32). ObjectFileError naming the problem.
ObjectFile read_object(const std::string& path, ObjectRead forms = ObjectRead::kWithDense);
// The dense forms of an object's sparse voxmap and shell where they are missing and fit (as ObjectRead::kWithDense).
void add_dense_forms(ObjectFile& obj);

// Shell words in the file use this fixed format (grid coordinates, signed 32-bit with 8 fraction bits): exact,
// because shell points are voxel centres (half-integers) or, on the surface, rounded to it. PointShell::words gives
// them for any configuration.
constexpr int kObjectShellFrac = kShellFrac;
// Largest grid dimension an object file accepts on any axis.
constexpr uint32_t kObjectMaxDim = 1u << 20;

}  // namespace voxcd
