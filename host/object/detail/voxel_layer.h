// Internal to host/object (voxelize_sparse.cpp): one layer of the sparse voxeliser. A layer is H planes of z (H a
// multiple of both the brick edge B and the near-hole refinement's block of 8), so it holds whole coarse cells and
// whole refinement blocks; its cells' codes and bricks come out in table order, with exactly voxelize's states.
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/host/object/detail/column_crossings.h"
#include "voxcd/host/object/detail/layers.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd::detail {

// What every layer shares.
struct LayerJob {
  const Mesh* mesh = nullptr;
  const GridMesh* gm = nullptr;
  GridPlacement gp;
  int bl = 3;
  uint32_t height = 8;            // H
  const Chain* chain = nullptr;   // null for a point cloud (no solid)
  const CapField* field = nullptr;  // null without caps
  const LayerLists* surface = nullptr;
  const LayerLists* chain_items = nullptr;
};

// A layer's cells in table order (code per cell; bricks of B^3 states, 32 a word, for the kCodeBrick cells) and the
// near-hole refinement's counts (VoxelizeReport's evaluated and uncertain).
struct LayerCells {
  std::vector<uint8_t> codes;
  std::vector<uint64_t> bricks;
  uint64_t evaluated = 0, uncertain = 0;
};

// Layer `layer` of the job. MeshError or std::logic_error as voxelize throws them. `pool` is the pool the caller runs
// in (its loops run inline).
LayerCells voxelize_layer(const LayerJob& job, size_t layer, ThreadPool& pool);

}  // namespace voxcd::detail
