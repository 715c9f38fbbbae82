// The object file: a processed mesh (voxmap as the device's memory image, point shell as device words plus float
// points and normals) saved once and reused. docs/objects.md gives the byte layout.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd {

// A file that is not a valid object file: says which file, what is wrong and at which byte offset.
struct ObjectFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ObjectFile {
  std::string source;            // mesh path as given, or "shape:NAME" for a built-in shape
  uint64_t source_hash = 0;      // FNV-1a 64 of the source file's bytes (of the string "shape:NAME" for a shape)
  double shell_ratio = 0;        // target voxel / shell spacing the shell was built with
  Eigen::Vector3d shift = Eigen::Vector3d::Constant(0.5);  // VoxelizeOptions::shift used for both grids
  Voxmap voxmap;
  PointShell shell;              // built for target voxel = voxmap.voxel()
  DistanceField distance;        // the signed distance field on the voxmap's grid (empty unless asked for)
  // What loading, repair and voxelising found (file version 2; a version 1 file has none: has_report false).
  bool has_report = false;
  MeshReport mesh_report;
  VoxelizeReport voxelize_report;
};

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
};

// The mesh named by `mesh_or_shape`: an existing file (load_mesh: RAW or any assimp format), else a built-in shape.
// Sets *source ("shape:NAME" or the path) and *hash (hash_file or hash_bytes of the source string). MeshError when
// it is neither, naming the argument and listing the shapes; MeshError from load_mesh for a bad file.
// *report gets what loading and repair found (for a shape: a closed mesh, nothing repaired). opt.strict refuses
// any defect (load_mesh).
Mesh load_source(const std::string& mesh_or_shape, std::string* source = nullptr, uint64_t* hash = nullptr,
                 MeshReport* report = nullptr, const LoadOptions& opt = {});

// Voxmap and shell of a mesh as load_source left it; `report` (what loading found) is kept in the object file.
// With distance_bits, also the distance field (distance_field) and the shell on the surface (surface_shell).
// MeshError as voxelize, point_shell and distance_field throw them, and for distance bits not 0, 4, 8 or 16.
ObjectFile make_object(const Mesh& mesh, const std::string& source, uint64_t source_hash, const ObjectOptions& opt,
                       const MeshReport* report = nullptr);

// FNV-1a 64 of a file's bytes (ObjectFileError when unreadable) and of a string.
uint64_t hash_file(const std::string& path);
uint64_t hash_bytes(const std::string& bytes);

// Writes the object file (atomically: a temporary file renamed into place): version 3 when the object has a distance
// field or a shell on the surface, else version 2 exactly as before. ObjectFileError on I/O failure.
void write_object(const std::string& path, const ObjectFile& obj);
// Reads and checks an object file (magic, version, sizes, CRC-32). ObjectFileError naming the problem.
ObjectFile read_object(const std::string& path);

// Shell words in the file use this fixed format (grid coordinates, signed 32-bit with 8 fraction bits): exact,
// because shell points are voxel centres (half-integers) or, on the surface, rounded to it. PointShell::words gives
// them for any configuration.
constexpr int kObjectShellFrac = kShellFrac;
// Largest grid dimension an object file accepts on any axis.
constexpr uint32_t kObjectMaxDim = 1u << 20;

}  // namespace voxcd
