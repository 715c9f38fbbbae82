// The sparse voxmap (docs/contract.md, "Sparse voxmaps and shells"): the grid cut into coarse cells of B = 2^BL
// voxels per axis, each uniform (every voxel empty, surface or interior) or a brick of B^3 2-bit states. Memory grows
// with the surface, not the volume; a dense Voxmap converts both ways. docs/objects.md, "Sparse objects".
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {

// BL, the host's choice of brick (docs/voxelize.md, "Sparse voxmaps"): 8^3 voxels.
constexpr int kDefaultBrickLog = 3;
// The bricks a device can hold: BL 2..4 (ref/config.h).
constexpr int kMinBrickLog = 2, kMaxBrickLog = 4;

// A canonical sparse map: a cell is a brick exactly when its voxels are not all in one state (voxels of far-face cells
// beyond the grid count as empty and are 0 in the brick), so two maps of the same states are equal member for member.
class SparseVoxmap {
 public:
  SparseVoxmap() = default;
  // Every cell uniformly empty. std::invalid_argument for bl outside kMinBrickLog..kMaxBrickLog or a grid of 2^32
  // cells or more.
  explicit SparseVoxmap(const GridPlacement& g, int bl = kDefaultBrickLog);

  const GridPlacement& grid() const { return grid_; }
  const std::array<uint32_t, 3>& dims() const { return grid_.dims; }
  uint64_t size() const { return grid_.size(); }
  int bl() const { return bl_; }
  uint32_t edge() const { return uint32_t{1} << bl_; }
  // Coarse cells per axis, ceil(n_i / B); cell t = cx + Cx * (cy + Cy * cz) is the table order.
  const std::array<uint64_t, 3>& coarse() const { return coarse_; }
  uint64_t cells() const { return cells_; }
  uint64_t bricks() const { return bricks_.size() / brick_words(); }
  // 64-bit words of a brick: B^3 states, 32 a word, voxel i = fx + B (fy + B fz) at bits 2 (i % 32) of word i / 32.
  uint64_t brick_words() const { return (uint64_t{1} << (3 * bl_)) / 32; }

  // The code of cell t: kEmpty, kSurface, kInterior (uniform) or kCodeBrick.
  uint8_t code(uint64_t t) const { return uint8_t((codes_[t >> 5] >> (2 * (t & 31))) & 3); }
  // Every cell's code in table order (ref's table_image takes them).
  std::vector<uint8_t> codes() const;
  // The brick index of brick cell t (bricks lie in table order: the bricks before it).
  uint64_t brick_index(uint64_t t) const;
  // Brick b's words (brick_words() of them).
  const uint64_t* brick(uint64_t b) const { return bricks_.data() + b * brick_words(); }
  // The state of voxel (x, y, z), which must lie in the grid.
  VoxelState at(uint32_t x, uint32_t y, uint32_t z) const;
  // Voxels of the grid in each state, indexed by VoxelState.
  std::array<uint64_t, 4> counts() const;
  // Cells per code (0, 1, 2 uniform; 3 bricks).
  std::array<uint64_t, 4> code_counts() const;

  // Device memory for MEMW-bit words on a 2-bit sparse device: the table (MEMW/4 codes and a rank a word) and the
  // bricks (2 B^3 / MEMW words each), in bytes.
  uint64_t table_bytes(int memw = 64) const;
  uint64_t brick_bytes() const { return bricks() * (uint64_t{1} << (3 * bl_)) / 4; }
  uint64_t bytes(int memw = 64) const { return table_bytes(memw) + brick_bytes(); }
  // The device's words (ref/sparse.h): the table with each word's rank (table_image), the bricks one after another
  // (unit_words each), and the job's brick_units. std::invalid_argument when cfg is not a 2-bit sparse device of
  // this map's BL, or its MEMW is wider than a brick.
  struct DeviceImage {
    std::vector<uint64_t> table, bricks;
    uint64_t brick_units = 0;
  };
  DeviceImage device_image(const DeviceConfig& cfg) const;

  // The same states, sparse and canonical (bl as the constructor takes it).
  static SparseVoxmap from_dense(const Voxmap& vm, int bl = kDefaultBrickLog);
  // The same states, dense.
  Voxmap to_dense() const;

  // Building in table order: the next cell gets `code`, and a brick's words when it is kCodeBrick (which must be
  // canonical: not all one state, voxels beyond the grid 0). std::logic_error past the last cell.
  void append(uint8_t code, const uint64_t* brick = nullptr);
  uint64_t appended() const { return appended_; }
  // Why brick words could not be the brick of cell t (a state 3, a voxel beyond the grid not 0, every voxel in one
  // state), or null when they can.
  const char* brick_problem(uint64_t t, const uint64_t* words) const;
  // The cells' codes packed 32 a word (code of cell t at bits 2 (t % 32) of word t / 32; bits past the last cell 0)
  // and the bricks' words: the object file's form.
  const std::vector<uint64_t>& code_words() const { return codes_; }
  const std::vector<uint64_t>& brick_data() const { return bricks_; }

  bool operator==(const SparseVoxmap& o) const;
  bool operator!=(const SparseVoxmap& o) const { return !(*this == o); }

 private:
  // Voxels of cell (cx, cy, cz) that lie in the grid, per axis.
  std::array<uint32_t, 3> extent(uint64_t cx, uint64_t cy, uint64_t cz) const;

  GridPlacement grid_;
  int bl_ = kDefaultBrickLog;
  std::array<uint64_t, 3> coarse_ = {0, 0, 0};
  uint64_t cells_ = 0, appended_ = 0;
  std::vector<uint64_t> codes_;  // 32 codes a word
  std::vector<uint32_t> rank_;   // bricks before each word of codes_
  std::vector<uint64_t> bricks_;
};

}  // namespace voxcd
