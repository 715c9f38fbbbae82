// Empty space of a voxmap for the pair tests' culling (host/pairs/collide.cpp): a pyramid of blocks, each holding
// what its voxels could give a lookup (the states present, or the least distance a point in it can interpolate), so
// that a box of the grid is proved to hold no hit with a few reads whatever its size, and clusters of shell points
// that land only in empty air are never looked up.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace voxcd {
class Voxmap;
struct DistanceField;
class SparseDistanceField;
}  // namespace voxcd

namespace voxcd::detail {

class EmptySpace {
 public:
  using Dims3 = std::array<uint32_t, 3>;
  // Blocks of the finest level hold at most this many entries (coarser blocks than voxels above it).
  static constexpr uint64_t kMaxBaseCells = uint64_t{1} << 21;
  // A box is tested from the level where it spans at most two blocks per axis down this many levels.
  static constexpr size_t kDescend = 2;

  EmptySpace() = default;  // knows nothing: every box may hold a hit
  // From 2-bit states: a voxel's entry is 1 << state, a block's the OR of its voxels'.
  static EmptySpace of_states(const Voxmap& vm);
  // From a distance field: a cell's entry is the least of its 8 nodes (the interpolant is a weighted mean of them,
  // so no point of the cell interpolates below it), a block's the least of its cells'.
  static EmptySpace of_field(const DistanceField& f);
  // From a sparse distance field: a voxel's entry is the least of the nodes of its sub-cells in its cell's brick (its
  // uniform cell's value), so that no point of the voxel interpolates below it at any level.
  static EmptySpace of_sparse_field(const SparseDistanceField& f);

  bool empty() const { return levels_.empty(); }
  // Whether voxels [lo, hi] (inclusive, clamped to the grid; none when lo > hi on an axis) hold one whose state is in
  // `mask` (a map of states). False only when none does.
  bool may_hit_states(std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, uint32_t mask) const;
  // Whether a point of cells [lo, hi] can interpolate a distance D <= threshold (a job's threshold: D is the nodes'
  // weighted mean times 2^(3 wb)). False only when none can.
  bool may_hit_field(std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, int64_t threshold, int wb) const;
  // One read for the common question: whether a voxel within Chebyshev distance r of voxel c (inside the grid) may
  // hold a state of {surface, interior} (a mask without the empty state's bit: masks of those states only). False
  // only when none does. On 2-bit states only (true otherwise).
  bool may_hit_near(const std::array<int64_t, 3>& c, int64_t r) const;
  // may_hit_near's table, for a vector kernel: per block of the finest level (edge 2^base voxels, dims blocks per
  // axis) its distance, then 3 bytes of padding (a 32-bit read at any block stays inside). Null on a distance field.
  struct Near {
    const uint8_t* d = nullptr;
    int base = 0;
    std::array<uint32_t, 3> dims = {0, 0, 0};
  };
  Near near() const { return {near_.empty() ? nullptr : near_.data(), base_, levels_.empty() ? Dims3{} : levels_.front().dims}; }
  // The finest level's block edge in voxels (a power of two), for tests.
  uint32_t base_block() const { return uint32_t(1) << base_; }

 private:
  struct Level {
    std::array<uint32_t, 3> dims;  // blocks per axis
    std::vector<int16_t> v;        // block (x, y, z) at x + dims[0] * (y + dims[1] * z)
  };
  // Level base_ + k in levels_[k], each block of edge 2^(base_ + k) voxels.
  std::vector<Level> levels_;
  std::array<uint32_t, 3> n_ = {0, 0, 0};  // voxels (cells) per axis
  int base_ = 0;
  bool min_ = false;  // entries combine by min (distance) or by OR (states)
  // States: per block of the finest level, the Chebyshev distance in blocks to the nearest block with a surface or
  // interior voxel (0 for such a block), at most 255.
  std::vector<uint8_t> near_;

  // near_ from the finest level (two raster passes over the 26 neighbours: exact for the Chebyshev distance).
  void build_near();

  // The levels above the finest, each block combining its 2x2x2 children.
  void build_coarser();
  template <class Accept>
  bool any(std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, const Accept& accept) const;
  template <class Accept>
  bool visit(size_t k, size_t last, const std::array<uint32_t, 3>& b, const std::array<int64_t, 3>& lo,
             const std::array<int64_t, 3>& hi, const Accept& accept) const;
};

}  // namespace voxcd::detail
