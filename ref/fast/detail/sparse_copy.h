// Internal to FastRunner: a copy of a sparse map (docs/contract.md, "Sparse voxmaps and shells") in which the table is
// resolved, one 32-bit entry a coarse cell, so that a lookup reads its cell's entry and then one brick word (2-bit) or
// one quad of nodes (distance): two gathers, without the rank's arithmetic.
//
// 2-bit maps: entries[t] = the first voxmap word of cell t's brick, or kUniformCell | its state for a uniform cell (and
// a code read as one: a reference past the job's units reads as code 0). The bricks are read where they are.
//
// Distance maps: entries[t] = level << 30 | the index in `quads` of the first quad of the cell's brick, every brick laid
// out as node quads (detail/node_quads.h) of B 2^level sub-cells per axis (quad e(X, Y, Z) = first + X + (n + 1) (Y +
// n Z), n = B 2^level). A uniform cell (and a code read as one: past the job's units, codes 6..15) points at one of two
// bricks of level 0 that hold its value at every node, so every cell is read alike and the interpolation gives
// q * 2^(3 WB), the contract's D for it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/fast/detail/node_quads.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// A 2-bit map's entry of a uniform cell: this bit, and the state in the low two bits.
constexpr uint32_t kUniformCell = uint32_t{1} << 31;

struct SparseCopy {
  // The job fields and the voxmap words the copy was made from: the table's and the bricks'.
  uint32_t map_base = 0, brick_base = 0, brick_units = 0, nx = 0, ny = 0, nz = 0;
  uint64_t table_end = 0, brick_end = 0;
  std::unique_ptr<uint32_t[], NodeQuads::Free> entries, quads;  // quads: distance maps only
  size_t cells = 0, count = 0;

  uint64_t bytes() const { return uint64_t(cells + count) * sizeof(uint32_t); }
  // Made from job j's map.
  bool serves(const Job& j) const {
    return j.map_base == map_base && j.brick_base == brick_base && j.brick_units == brick_units && j.nx == nx &&
           j.ny == ny && j.nz == nz;
  }
  // Made from any of voxmap words [first, end).
  bool overlaps(uint64_t first, uint64_t end) const {
    return (map_base < end && first < table_end) || (brick_base < end && first < brick_end);
  }
};

// The bytes job j's copy takes (it reads the table; nothing is allocated), or UINT64_MAX where a distance map's quads
// would not fit 30 bits. j must be a valid sparse-map job for `map`, on a distance device with SB <= 8 or a 2-bit one.
uint64_t sparse_copy_bytes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j);
// Builds job j's copy.
SparseCopy build_sparse_copy(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j);

// What the kernel needs of a job: M and t scaled by 2^-(TF - WB), so that a = M p + t is acc * 2^-(TF - WB), exact
// (TF - WB fraction bits: the accumulator's bits fit 53), floor(a) is acc >> (TF - WB) (level 0's weights and voxel)
// and floor(a 2^l) is acc >> (TF - WB - l) (level l's: TF >= WB + 3 on a sparse distance device).
struct BrickQuadJob {
  double m[9], t[3], n[3];
  double weight;          // 2^WB
  double inv_weight;      // 2^-WB
  double level_scale[8];  // level l: 2^l
  int32_t edge[8];        // level l: B 2^l sub-cells per axis
  int32_t cx, cy;         // coarse cells along x and y
  int bl;
  const uint32_t* entries;
  const uint32_t* quads;
  double biased_threshold;  // threshold + bias, bias = 2^(SB-1) * 2^(3 WB)
  double bias;
};
BrickQuadJob brick_quad_job(const DeviceConfig& cfg, const Job& j, const SparseCopy& q);

// Points [0, n) as the dense distance kernels (detail/distance_kernel.h): hit[k], for hits the voxel and D.
using BrickQuadBlockFn = uint32_t (*)(const int32_t* x, const int32_t* y, const int32_t* z, size_t n,
                                      const BrickQuadJob& job, uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz,
                                      double* dist);
BrickQuadBlockFn brick_quad_block();
const char* brick_quad_block_name();

}  // namespace voxcd::detail
