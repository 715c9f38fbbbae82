// BrickSigns (host/object/detail/brick_signs.h): the voxeliser's solid on grids of cells centred on the nodes.
#include "voxcd/host/object/detail/brick_signs.h"

#include <algorithm>

#include "voxcd/host/object/detail/solid.h"

namespace voxcd::detail {

namespace {

// The grid whose voxel centres are the level-l nodes lo + (0 .. n-1) per axis of grid g: the same voxel corners
// as the dense field's node grid at level 0 (origin - voxel / 2).
GridPlacement node_cells(const GridPlacement& g, int level, const std::array<int64_t, 3>& lo,
                         const std::array<uint64_t, 3>& n) {
  GridPlacement c;
  c.voxel = std::ldexp(g.voxel, -level);
  for (int a = 0; a < 3; ++a) {
    c.origin[a] = g.origin[a] + c.voxel * (double(lo[size_t(a)]) - 0.5);
    c.dims[size_t(a)] = uint32_t(n[size_t(a)]);
  }
  return c;
}

}  // namespace

BrickSigns::BrickSigns(const Mesh& mesh, const GridPlacement& g, const std::array<uint32_t, 3>& cells,
                       uint64_t whole_limit, unsigned threads)
    : mesh_(mesh), g_(g), threads_(threads) {
  for (int a = 0; a < 3; ++a) nodes_[size_t(a)] = uint64_t(cells[size_t(a)]) * 8 + 1;
  whole_ = nodes_[0] * nodes_[1] * nodes_[2] <= whole_limit;
  if (whole_) bits_ = solid_bits(mesh_, node_cells(g_, 0, {0, 0, 0}, nodes_), threads_);
}

void BrickSigns::load_layer(uint32_t cz) {
  if (whole_) return;
  z0_ = std::max<int64_t>(0, int64_t(cz) * 8 - 1);
  const int64_t z1 = std::min<int64_t>(int64_t(nodes_[2]) - 1, int64_t(cz) * 8 + 9);
  bits_ = solid_bits(mesh_, node_cells(g_, 0, {0, 0, z0_}, {nodes_[0], nodes_[1], uint64_t(z1 - z0_ + 1)}), threads_);
}

std::vector<uint64_t> BrickSigns::fine(int level, const std::array<int64_t, 3>& lo, uint32_t n) const {
  // Inside a task of the builder's pool: one thread.
  return solid_bits(mesh_, node_cells(g_, level, lo, {n, n, n}), 1);
}

}  // namespace voxcd::detail
