// Internal to host/object (sparse_build.cpp, detail/brick_build.cpp): the sign of a sparse distance field's nodes,
// the voxeliser's own solid (detail/solid.h) on grids whose voxel centres are the nodes, so that a sparse field, the
// dense field and the voxmap agree on what is inside. Level-0 nodes come from one solid over the whole node grid
// when it is small enough, else from one layer of coarse cells at a time (so that memory follows a layer, not the
// volume); the nodes of a refined brick from a solid over that brick's nodes alone.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

class BrickSigns {
 public:
  // For the nodes 0 .. 8 cells[i] per axis of grid g (the voxmap's): one solid over all of them when there are at
  // most whole_limit, else layers (load_layer). `threads` for the level-0 solids.
  BrickSigns(const Mesh& mesh, const GridPlacement& g, const std::array<uint32_t, 3>& cells, uint64_t whole_limit,
             unsigned threads);
  // Makes the level-0 nodes with 8 cz - 1 <= Z <= 8 cz + 9 available (a no-op for a whole-grid solid).
  void load_layer(uint32_t cz);
  // Level-0 node (X, Y, Z) lies in the solid (X, Y within the grid's nodes, Z in the loaded layer).
  bool inside(int64_t X, int64_t Y, int64_t Z) const {
    const uint64_t i = uint64_t(X) + nodes_[0] * (uint64_t(Y) + nodes_[1] * uint64_t(Z - z0_));
    return (bits_[i >> 6] >> (i & 63)) & 1;
  }
  // The solid at the level-l nodes lo + (X, Y, Z), 0 <= X, Y, Z < n (level-l node coordinates: node K of level l
  // lies at K 2^-l voxels): bit X + n (Y + n Z). One solid of n^3 voxels; never depends on anything else.
  std::vector<uint64_t> fine(int level, const std::array<int64_t, 3>& lo, uint32_t n) const;
  bool whole() const { return whole_; }

 private:
  const Mesh& mesh_;
  GridPlacement g_;
  std::array<uint64_t, 3> nodes_;  // 8 cells + 1 per axis
  unsigned threads_;
  bool whole_;
  int64_t z0_ = 0;  // the first node layer in bits_
  std::vector<uint64_t> bits_;
};

}  // namespace voxcd::detail
