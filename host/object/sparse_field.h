// The sparse signed distance field of an object (docs/objects.md, "Sparse distance field"): the field of
// distance_field.h stored only where it is not clamped. The voxmap's grid is cut into coarse cells of 8^3 voxels; a
// cell wholly beyond the band is uniform (every node qmax: far outside, or qmin: far inside), every other cell is a
// brick of its level l = 0..3, the field at the (8 2^l + 1)^3 nodes of the cell at spacing 2^-l voxel, in the same
// unit at every level. Refined bricks (l > 0) are where the coarse nodes cannot place the surface. This is the layout
// a sparse distance device reads (docs/contract.md, "Distance bricks and levels").
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// A sparse device's memory image of one field: the table words (from the job's map_base), the brick words (from
// its brick_base, a multiple of 8) and the job's brick_units.
struct SparseImage {
  std::vector<uint64_t> table;
  std::vector<uint64_t> bricks;
  uint64_t brick_units = 0;
};

// How many cells of each kind a sparse field has.
struct SparseFieldCounts {
  uint64_t far = 0, deep = 0;           // uniform cells: qmax, qmin
  std::array<uint64_t, 4> bricks = {};  // bricks of level 0 .. 3
  uint64_t conservative = 0;            // sub-cells whose nodes were lowered to at most 0
  uint64_t nodes = 0;                   // node values stored in all bricks
};

class SparseDistanceField {
 public:
  static constexpr int kBrickLog = 3;  // BL: a coarse cell is 2^3 = 8 voxels per axis
  static constexpr uint32_t kEdge = 1u << kBrickLog;
  static constexpr int kMaxLevel = 3;

  SparseDistanceField() = default;
  // From its parts (the builder's and the file reader's way): codes per cell in table order
  // (t = cx + Cx (cy + Cy cz), C = ceil(dims / 8)), each brick's nodes in table order, node (X, Y, Z) of a level-l
  // brick at X + n (Y + n Z), n = 8 2^l + 1; the conservative sub-cells as keys (conservative_key). Throws
  // std::invalid_argument naming what does not fit (a code above 5, a node count or value, a key).
  SparseDistanceField(int bits, double step, const std::array<uint32_t, 3>& dims, std::vector<uint8_t> codes,
                      std::vector<int16_t> nodes, std::vector<uint64_t> conservative);

  bool empty() const { return bits_ == 0; }
  int bits() const { return bits_; }
  double step() const { return step_; }
  int qmax() const { return (1 << (bits_ - 1)) - 1; }
  int qmin() const { return -(1 << (bits_ - 1)); }
  double band() const { return step_ * double(1 << (bits_ - 1)); }
  const std::array<uint32_t, 3>& dims() const { return dims_; }
  const std::array<uint32_t, 3>& cells() const { return cells_; }
  uint64_t cell_index(uint64_t cx, uint64_t cy, uint64_t cz) const { return cx + cells_[0] * (cy + cells_[1] * cz); }
  const std::vector<uint8_t>& codes() const { return codes_; }
  const std::vector<int16_t>& nodes() const { return nodes_; }
  const std::vector<uint64_t>& conservative() const { return conservative_; }
  // The level of cell t's brick, or -1 for a uniform cell.
  int level(uint64_t t) const { return codes_[t] >= 2 ? codes_[t] - 2 : -1; }
  // The value of node (X, Y, Z) of cell t at its level (a uniform cell's value at any node).
  int at(uint64_t t, uint64_t X, uint64_t Y, uint64_t Z) const;

  // Key of sub-cell (X, Y, Z) (each below 8 2^level) of cell t: t * 2^18 + X + 64 (Y + 64 Z).
  static uint64_t conservative_key(uint64_t t, uint32_t X, uint32_t Y, uint32_t Z) {
    return (t << 18) | X | uint64_t(Y) << 6 | uint64_t(Z) << 12;
  }
  // The sub-cell holding grid point g (voxel units, clamped to the grid) shares a node with a conservative sub-cell
  // of its cell: a hit there has the conservative sub-cell's bound rather than the field's (docs/pairs.md).
  bool near_conservative(const Eigen::Vector3d& g) const;

  // The interpolant the device computes at grid point g (voxel units from the grid's origin; clamped to the grid):
  // the trilinear interpolant of the 8 nodes of g's sub-cell in its cell's brick, in voxels (value * step), with its
  // gradient per voxel when `gradient` is not null; a uniform cell's value, gradient 0.
  double sample(const Eigen::Vector3d& g, Eigen::Vector3d* gradient = nullptr) const;

  SparseFieldCounts counts() const;
  // Bytes this object holds in host memory (codes, nodes, keys and its index).
  uint64_t bytes() const;
  // The sparse device's image for cfg: cfg.distance(), cfg.SB == bits(), cfg.BL == kBrickLog, else
  // std::invalid_argument naming the parameter; the table through ref's table_image, each node at ref's
  // brick_node_address (slots that hold no node are 0).
  SparseImage device_image(const DeviceConfig& cfg) const;

 private:
  // The first node of cell t's brick in nodes_.
  uint64_t brick_first(uint64_t t) const;
  void index();

  int bits_ = 0;
  double step_ = 0;
  std::array<uint32_t, 3> dims_ = {0, 0, 0}, cells_ = {0, 0, 0};
  std::vector<uint8_t> codes_;
  std::vector<int16_t> nodes_;
  std::vector<uint64_t> conservative_;  // sorted, no repeats
  std::vector<uint64_t> block_first_;   // per 64 cells: the first node of their first brick
};

// Nodes of a level-l brick per axis: 8 2^l + 1.
inline uint64_t brick_side(int level) { return (uint64_t{SparseDistanceField::kEdge} << level) + 1; }

struct SparseFieldOptions {
  DistanceOptions distance;  // bits, band, threads; `conservative` off leaves out the resolution test entirely
  int max_level = 3;         // 0 .. 3: the finest level a brick may be refined to
  // Level-0 signs from one solid over every node up to this many nodes, else one layer of cells at a time (the
  // same values: docs/objects.md); tests lower it to run the layered path on small grids.
  uint64_t whole_solid_nodes = uint64_t{1} << 27;
};

// The sparse field of a mesh as repair() left it on grid g (the voxmap's), built a brick at a time: exact
// point-triangle distances at the nodes of each brick only, the sign from the solid voxelize computes
// (docs/objects.md, "Sparse distance field"); bricks whose coarse nodes do not resolve the surface are rebuilt at
// levels 1, 2, 3 until they do, and the sub-cells even max_level does not resolve are made conservative. MeshError as
// distance_field throws, and for max_level outside 0..3. The result never depends on the thread count.
SparseDistanceField sparse_distance_field(const Mesh& mesh, const GridPlacement& g, const SparseFieldOptions& opt);

// The level-0 sparse form of a dense field: the same node values wherever the dense field has them (a cell uniform
// when all its nodes are qmax or all qmin; nodes past the grid's far faces repeat the nearest face's).
SparseDistanceField sparse_from_dense(const DistanceField& f);
// The dense field at the level-0 nodes of a sparse one (a refined brick gives its nodes at those places).
DistanceField dense_from_sparse(const SparseDistanceField& f);

// The field's bytes in an object file (docs/objects.md, "Sparse distance field"), appended to `out`.
void write_sparse_field(std::vector<uint8_t>& out, const SparseDistanceField& f);
// The field from the bytes written by write_sparse_field, which must fill [data, data + size) exactly.
// ObjectFileError (host/object/object_file.h) beginning with `where`, saying what is wrong at which byte offset
// (counted from data).
SparseDistanceField read_sparse_field(const uint8_t* data, size_t size, const std::string& where);

}  // namespace voxcd
