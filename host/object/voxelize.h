// The voxmap (2-bit states on a regular grid, packed as the device stores them) and the voxeliser: the solid is
// where the generalized winding number of the surface is at least 1/2 (host/object/detail/winding.cpp), plus every voxel the
// surface passes through.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/frame.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// A grid in an object's frame: voxel (x, y, z) covers origin + voxel * ([x, x+1] x [y, y+1] x [z, z+1]).
struct GridPlacement {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double voxel = 1.0;
  std::array<uint32_t, 3> dims = {1, 1, 1};

  uint64_t size() const { return uint64_t(dims[0]) * dims[1] * dims[2]; }
  GridFrame frame() const { return GridFrame{origin, voxel}; }
};

struct VoxelizeOptions {
  double voxel = 0;  // voxel edge length in mesh units; must be finite and > 0 (or resolution set)
  // When > 0, the voxel is the model's longest bounding-box side / resolution (voxel_for_resolution).
  uint32_t resolution = 0;
  // Grid placement: the mesh's AABB minimum lies at grid coordinate 1 + shift (each component in (0, 1]), so at
  // least one empty voxel pads every side. Tests move the grid with it.
  Eigen::Vector3d shift = Eigen::Vector3d::Constant(0.5);
  uint32_t max_dim = 1024;  // per axis (the device's 2^DW); a larger grid is an error naming the size
  unsigned threads = 0;     // 0: one per hardware thread; the result never depends on it
};

// 2-bit voxel states, linear index x + nx*(y + ny*z), 32 states per 64-bit word from bit 0 up: the device's
// voxmap memory image for MEMW = 64.
class Voxmap {
 public:
  Voxmap() = default;
  explicit Voxmap(const GridPlacement& g);  // every voxel empty

  const GridPlacement& grid() const { return grid_; }
  const std::array<uint32_t, 3>& dims() const { return grid_.dims; }
  double voxel() const { return grid_.voxel; }
  const Eigen::Vector3d& origin() const { return grid_.origin; }
  uint64_t size() const { return grid_.size(); }
  uint64_t index(uint32_t x, uint32_t y, uint32_t z) const {
    return x + uint64_t(grid_.dims[0]) * (y + uint64_t(grid_.dims[1]) * z);
  }
  VoxelState at(uint64_t i) const { return VoxelState((words_[i >> 5] >> (2 * (i & 31))) & 3); }
  VoxelState at(uint32_t x, uint32_t y, uint32_t z) const { return at(index(x, y, z)); }
  void set(uint64_t i, VoxelState s) {
    uint64_t& w = words_[i >> 5];
    w = (w & ~(uint64_t{3} << (2 * (i & 31)))) | (uint64_t(s) << (2 * (i & 31)));
  }
  // Centre of voxel (x, y, z) in the object's frame.
  Eigen::Vector3d centre(uint32_t x, uint32_t y, uint32_t z) const {
    return grid_.origin + grid_.voxel * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
  }
  // Number of voxels in each state, indexed by VoxelState.
  std::array<uint64_t, 4> counts() const;
  // The memory image for MEMW = 64 (unused high bits of the last word are 0).
  const std::vector<uint64_t>& words() const { return words_; }
  std::vector<uint64_t>& words() { return words_; }
  // The memory image for another word width (a power of two, 2..64): voxel i at word i / (memw/2).
  std::vector<uint64_t> device_words(int memw) const;

 private:
  GridPlacement grid_;
  std::vector<uint64_t> words_;
};

// Fewest voxels voxelize accepts along the model's longest side.
constexpr uint32_t kMinVoxelsAcross = 4;
// Most voxels a scene's object may have along its longest side: the device's 2^DW (DW = 10) voxels per axis, less
// room for the grid's padding. Scenes hold dense voxmaps (and a depth per voxel), which is what bounds them.
constexpr uint32_t kMaxVoxelsAcross = 1020;
// Most voxels an object stored sparse may have along its longest side (voxcd voxelize --resolution): its memory grows
// with the surface. Its grid, with the padding, has up to kMaxSparseDim voxels per axis: a device with DW = 12 takes
// models up to 4092 voxels across, DW = 13 the rest.
constexpr uint32_t kMaxSparseVoxelsAcross = 4096;
constexpr uint32_t kMaxSparseDim = kMaxSparseVoxelsAcross + 4;

// The voxel edge that puts `resolution` voxels along the longest side of the mesh's bounding box (of its points
// for a point cloud). MeshError when resolution < kMinVoxelsAcross or the mesh is empty or flat in every axis.
double voxel_for_resolution(const Mesh& mesh, uint32_t resolution);

// The grid voxelize uses for `mesh`: see VoxelizeOptions. Throws MeshError for a bad voxel size or shift, a voxel
// that leaves fewer than kMinVoxelsAcross voxels along the longest side (naming the size that gives that many),
// or a grid larger than max_dim on some axis (naming the dimensions and the smallest voxel size that fits).
GridPlacement place_grid(const Mesh& mesh, const VoxelizeOptions& opt);

// What voxelize found besides the voxmap.
struct VoxelizeReport {
  // Voxels neither surface nor certain: their centre's winding number lies in [kUncertainLow, kUncertainHigh].
  uint64_t uncertain = 0;
  // Voxels whose winding number was evaluated one by one (the rest were decided by the integer part alone).
  uint64_t evaluated = 0;
  // Cells of the distance field (when one is built) whose surface its nodes do not resolve, made conservative
  // (detail/unresolved.h): a part thinner than a voxel, a sharp edge, a sheet.
  uint64_t conservative = 0;
};
constexpr double kUncertainLow = 0.25, kUncertainHigh = 0.75;

// Voxelises a mesh as repair() or prepare() left it. A voxel is Surface when its closed cube, grown by 2^-19
// voxel on every side, meets a triangle (or holds a point of a point cloud); otherwise Interior when the
// generalized winding number of the non-sheet triangles at its centre is at least 1/2, else Empty. On a closed,
// consistently oriented mesh that is exact (an integer from signed ray crossings) and equals voxelize_raycast
// wherever the mesh does not overlap itself; so interior voxels lie inside the solid and the solid lies in
// interior + surface voxels.
Voxmap voxelize(const Mesh& mesh, const VoxelizeOptions& opt, VoxelizeReport* report = nullptr);

// The paper's ray-casting voxeliser (exact parity along rays through voxel-column centres): the reference the
// winding-number voxeliser is measured and tested against. MeshError for an odd crossing count (an open mesh).
Voxmap voxelize_raycast(const Mesh& mesh, const VoxelizeOptions& opt);

// Bit i (word i / 64, bit i % 64) set when voxel i is a surface voxel as voxelize defines it.
std::vector<uint64_t> surface_bits(const Mesh& mesh, const GridPlacement& g, unsigned threads = 0);

// Calls fn(triangle, x, y, z) for every surface voxel of each triangle in [t0, t1), as voxelize defines them.
void for_each_overlap(const Mesh& mesh, const GridPlacement& g, size_t t0, size_t t1,
                      const std::function<void(size_t, uint32_t, uint32_t, uint32_t)>& fn);

// Akenine-Moller's separating-axis test: does triangle (a, b, d) meet the axis-aligned cube centred at c with half
// side h (boundary included)?
bool triangle_meets_cube(const Eigen::Vector3d& c, double h, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& d);

}  // namespace voxcd
