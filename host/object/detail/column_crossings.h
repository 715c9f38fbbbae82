// Internal to host/object (voxelize.cpp, voxelize_sparse.cpp): the solid's integer part. The closed chain (the
// triangles that bound the solid minus the caps of their boundary, host/object/detail/winding.h) crosses every ray
// along x through a voxel-column centre; the signed crossings beyond a voxel's centre are the chain's winding number
// W there. And the caps' winding number near holes, which moves W's answer only there.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/object/detail/voxel_geometry.h"
#include "voxcd/host/object/detail/winding.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd::detail {

// Bound on the far caps' winding number below which the near caps' exact part stands for the whole.
constexpr double kNearEnough = 0.02;

// The closed chain: the triangles that bound the solid (every triangle of the mesh but its sheets) and their caps.
struct Chain {
  std::vector<std::array<uint32_t, 3>> solid;  // vertex indices into the GridMesh
  std::vector<ChainTriangle> caps;
  size_t size() const { return solid.size() + caps.size(); }
};
Chain closed_chain(const Mesh& mesh, const GridMesh& gm);

// Signed crossings of the closed chain with the column rays of z in [z0, z0 + rows), bucketed by column
// c = y + ny * (z - z0) and sorted along it: column c's crossings are xs[start[c], start[c + 1]), (x, sign).
struct ColumnCrossings {
  uint32_t ny = 1;
  int64_t z0 = 0;
  std::vector<uint32_t> start;
  std::vector<std::pair<double, int32_t>> xs;
  size_t columns() const { return start.size() - 1; }
  // The column of (y, z).
  size_t column(uint32_t y, uint32_t z) const { return size_t(y) + size_t(ny) * size_t(int64_t(z) - z0); }
  // The signs of the crossings of column c at or before x (W at a voxel centre x is minus this).
  int64_t prefix(size_t c, double x) const;
};

// The crossings of chain items (indices < chain.size(): solid triangles first, then caps) with the columns of the
// window: items[0, n), or every item when items is null. Spread over `pool` (run inline when called from one of its
// tasks).
ColumnCrossings column_crossings(const Chain& chain, const GridMesh& gm, const GridPlacement& gp, ThreadPool& pool,
                                 const ZWindow& win, const uint32_t* items = nullptr, size_t n = 0);

// Calls fill(c, lo, hi) for every run of voxels [lo, hi) of column c whose centres have W >= 1, in order along the
// column (runs may touch). std::logic_error naming the mesh and the column when a column's signs do not sum to zero
// (the chain is not closed: an internal error).
template <class Fill>
void walk_columns(const std::string& mesh_name, const GridPlacement& gp, const ColumnCrossings& cc, Fill&& fill) {
  const uint64_t nx = gp.dims[0];
  for (size_t c = 0; c < cc.columns(); ++c) {
    const auto* b = cc.xs.data() + cc.start[c];
    const auto* e = cc.xs.data() + cc.start[c + 1];
    if (b == e) continue;
    int64_t prefix = 0;  // signs of the crossings at or before the current one; W = -prefix after it
    for (const auto* p = b; p < e; ++p) {
      prefix += p->second;
      if (-prefix < 1 || p + 1 == e) continue;
      // Voxels whose centre lies in [p->first, next crossing).
      const double lo_i = std::max(0.0, std::ceil(p->first - 0.5));
      const double hi_i = std::min(double(nx), std::ceil(p[1].first - 0.5));
      if (lo_i >= hi_i) continue;
      fill(c, uint64_t(lo_i), uint64_t(hi_i));
    }
    if (prefix != 0)
      throw std::logic_error(mesh_name + ": the closed chain's crossings along column (y " +
                             std::to_string(c % cc.ny) + ", z " + std::to_string(int64_t(c / cc.ny) + cc.z0) +
                             ") do not sum to zero");
  }
}

// The generalized winding number at the centre of voxel (x, y, z), which the caps' field says may be uncertain:
// W from the crossings, plus the near caps' exact part when the bound on the rest decides (bound <= kNearEnough and
// 1/2 outside it), else plus the whole field. `near` and `bound` are as CapField::uncertain_voxels gives them.
double near_hole_winding(const CapField& field, const ColumnCrossings& cc, uint32_t x, uint32_t y, uint32_t z,
                         double near, double bound);

}  // namespace voxcd::detail
