// Internal to FastRunner: the block kernels that look points up in a sparse map (docs/contract.md, "Sparse voxmaps and
// shells") on the double path: the table read (a cell's code and, from the word's rank and the codes before the cell,
// its brick's first word), then the brick read, both by gathers. 2-bit maps read the contract's layout as it is
// (ref/fast/sparse_kernel.cpp); distance maps a copy in which every brick's sub-cells are node quads
// (detail/sparse_copy.h, ref/fast/sparse_distance_kernel.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// What the 2-bit kernel needs of a job: M and t scaled by 2^-TF (exact), the map's voxels per axis, the memory, and
// the layout's fields as shifts (every count a power of two: B, CPW, UW and the states a word).
struct SparseJob {
  double m[9], t[3], n[3];
  const uint64_t* map;  // the voxmap memory (word 0)
  uint32_t table;       // map_base: the table's first word
  uint32_t brick_base, brick_units;
  int32_t cx, cy;   // coarse cells along x and y
  int bl;           // BL
  int cpw_bits;     // log2 CPW
  int unit_bits;    // log2 UW
  int spw_bits;     // log2 MEMW / 2 (states a word)
  int half;         // MEMW / 2: the rank's place in a table word
  uint32_t hit_mask;
  // The map's copy with its table resolved (detail/sparse_copy.h), or null: the kernel of sparse_entry_block reads
  // it for the table read, that of sparse_block the table itself.
  const uint32_t* entries = nullptr;
};
// The job's fields (scale: 2^-TF).
SparseJob sparse_job(const DeviceConfig& cfg, const Job& j, const uint64_t* map, double scale);

// Points [0, n) of coordinates x, y, z: per point state[k] = its voxel's state | hit << 2 (0 outside), for hits its
// voxel (cx, cy, cz); returns the hits. Exact as the 2-bit block kernel of ref/fast/fast.cpp is (integers below 2^53).
using SparseBlockFn = uint32_t (*)(const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const SparseJob& job,
                                   int32_t* cx, int32_t* cy, int32_t* cz, uint8_t* state);
SparseBlockFn sparse_block();
SparseBlockFn sparse_entry_block();
const char* sparse_block_name();

// A sparse map read one point at a time with 64-bit integers (the int64 and wide paths, and distance maps the copy
// cannot serve): ref/pipeline.h's read_cell, sparse_state, sub_cell and brick_nodes, fused.
class SparseReader {
 public:
  SparseReader(const DeviceConfig& cfg, const Job& j, const uint64_t* map);
  // The state of inside voxel idx (2-bit maps).
  uint8_t state(const int64_t idx[3]) const;
  // D at an inside point of voxel idx whose accumulator's fraction bits (acc mod 2^TF) are frac (distance maps).
  int64_t distance(const int64_t idx[3], const uint64_t frac[3]) const;

 private:
  // The cell's level (-1: uniform, its code in `code`) and its brick's first word.
  int cell(const int64_t idx[3], uint8_t& code, uint64_t& first) const;

  const uint64_t* map_;
  uint64_t table_, brick_base_, brick_units_, cx_, cy_, uw_;
  int bl_, cw_, half_, cpw_, tf_, wb_, sb_, npw_;
  bool distance_;
  uint32_t units_[16];  // units of each code
};

}  // namespace voxcd::detail
