// Sparse map images for the tests of every layer: a dense map (states, or node values) laid out as the contract's
// sparse map (docs/contract.md, "Sparse voxmaps and shells"), so that a sparse job can be checked against the dense
// job of the same map, and distance bricks of any level from a field given as a function.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::test {

// Where a sparse map went in the memory: the job fields a sparse job on it takes.
struct SparsePlacement {
  uint32_t map_base = 0, brick_base = 0, brick_units = 0;
  std::vector<uint8_t> codes;  // per coarse cell, in table order
};

// Appends the sparse form of a 2-bit map of nx x ny x nz voxels (states[x + nx (y + ny z)]) to mem.map: its table,
// then its bricks. A cell whose voxels (those inside the map) share a state 0, 1 or 2 is uniform; every other cell a
// brick (its voxels past the map's faces 0).
SparsePlacement append_sparse_states(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz,
                                     const std::vector<uint8_t>& states, DeviceMemory& mem);

// Appends a sparse distance map of nx x ny x nz cells to mem.map (on bank boundaries): the field q(x, y, z) (node
// value at voxel coordinates (x, y, z), SB-bit) sampled at level level(cell) in each brick; a cell whose level is
// negative is uniform, with every node qmax (-1) or qmin (-2).
SparsePlacement append_sparse_field(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz,
                                    const std::function<int64_t(double, double, double)>& q,
                                    const std::function<int(uint64_t cx, uint64_t cy, uint64_t cz)>& level,
                                    DeviceMemory& mem);

// The dense parity-bank image of the same field at level 0 (node values q at integer coordinates), appended to
// mem.map on a bank boundary; returns its map_base.
uint32_t append_dense_field(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz,
                            const std::function<int64_t(double, double, double)>& q, DeviceMemory& mem);

// A job on a sparse placement (the map's dims and bases; kSparseMap set).
Job sparse_map_job(const SparsePlacement& p, uint32_t nx, uint32_t ny, uint32_t nz);

}  // namespace voxcd::test
