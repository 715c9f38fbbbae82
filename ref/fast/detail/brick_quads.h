// Internal to FastRunner's distance path: a copy of a sparse distance map (docs/contract.md, "Distance bricks and
// levels") in which the table is resolved and every brick is node quads (detail/node_quads.h), so that a lookup reads
// one 4-byte entry for its cell and one 8-byte quad for its sub-cell's eight nodes, two gathers, instead of the table
// word (with its rank) and eight brick words.
//
// Layout: entries[t] for coarse cell t = level << 30 | the index in `quads` of the first quad of the cell's brick,
// laid out as a dense map's copy of B 2^level sub-cells per axis (quad e(X, Y, Z) = first + X + (n + 1) (Y + n Z),
// n = B 2^level). A uniform cell (and a code read as one: past the job's units, codes 6..15) points at one of two
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

struct BrickQuads {
  // The job fields and the voxmap words the copy was made from: the table's and the bricks'.
  uint32_t map_base = 0, brick_base = 0, brick_units = 0, nx = 0, ny = 0, nz = 0;
  uint64_t table_end = 0, brick_end = 0;
  std::unique_ptr<uint32_t[], NodeQuads::Free> entries, quads;
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

// The bytes job j's copy takes (it reads the table; nothing is allocated), or UINT64_MAX where its entries would not
// fit 30 bits. j must be a valid sparse-map job on a distance device with SB <= 8 for `map`.
uint64_t brick_quad_bytes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j);
// Builds job j's copy.
BrickQuads build_brick_quads(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j);

// What the kernel needs of a job: M and t scaled by 2^-(TF - WB - kMaxLevel), so that floor(M p + t) is the
// accumulator at the finest level's weights (acc >> (TF - WB - 3)); the scales from there to a level's weights.
struct BrickQuadJob {
  double m[9], t[3], n[3];
  double inv_fine;        // 2^-(WB + 3): the finest steps to voxels
  double weight;          // 2^WB
  double inv_weight;      // 2^-WB
  double level_scale[8];  // level l: 2^-(3 - l), the finest steps to level l's
  int32_t edge[8];        // level l: B 2^l sub-cells per axis
  int32_t cx, cy;         // coarse cells along x and y
  int bl;
  const uint32_t* entries;
  const uint32_t* quads;
  double biased_threshold;  // threshold + bias, bias = 2^(SB-1) * 2^(3 WB)
  double bias;
};
BrickQuadJob brick_quad_job(const DeviceConfig& cfg, const Job& j, const BrickQuads& q);

// Points [0, n) as the dense distance kernels (detail/distance_kernel.h): hit[k], for hits the voxel and D.
using BrickQuadBlockFn = uint32_t (*)(const int32_t* x, const int32_t* y, const int32_t* z, size_t n,
                                      const BrickQuadJob& job, uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz,
                                      double* dist);
BrickQuadBlockFn brick_quad_block();
const char* brick_quad_block_name();

}  // namespace voxcd::detail
