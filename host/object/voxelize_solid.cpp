// The voxeliser's solid fill: the voxels whose centres have a generalized winding number of at least 1/2, from the
// closed chain's column crossings, refined voxel by voxel near the holes.
#include "voxcd/host/object/voxelize.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/host/object/detail/column_crossings.h"
#include "voxcd/host/object/detail/solid.h"
#include "voxcd/host/object/detail/voxel_geometry.h"
#include "voxcd/host/object/detail/voxelize_stages.h"

namespace voxcd {

namespace detail {

// Sets voxels [b, e) of an all-empty-or-interior word array to interior.
void fill_interior(std::vector<uint64_t>& w, uint64_t b, uint64_t e) {
  constexpr uint64_t kInt = 0xaaaaaaaaaaaaaaaaull;
  while (b < e) {
    const uint64_t wi = b >> 5, first = b & 31;
    const uint64_t last = std::min<uint64_t>(32, first + (e - b));
    const uint64_t lo_mask = first == 0 ? ~uint64_t{0} : ~((uint64_t{1} << (2 * first)) - 1);
    const uint64_t hi_mask = last == 32 ? ~uint64_t{0} : ((uint64_t{1} << (2 * last)) - 1);
    w[wi] |= kInt & lo_mask & hi_mask;
    b += last - first;
  }
}

namespace {

// The caps' winding number moves W only near the holes: voxels where it could reach kUncertainLow are evaluated one
// by one (W + caps >= 1/2), every other voxel keeps W's answer. Voxels set in *skip are left as they are.
void refine_near_holes(const std::vector<detail::ChainTriangle>& caps, const GridPlacement& gp,
                       const detail::ColumnCrossings& cc, ThreadPool& pool, const std::vector<uint64_t>* skip,
                       Voxmap& vm, VoxelizeReport& rep) {
  const detail::CapField field(caps, detail::kFrac);
  constexpr uint32_t kBlock = 8;
  const uint32_t bx = (gp.dims[0] + kBlock - 1) / kBlock, by = (gp.dims[1] + kBlock - 1) / kBlock,
                 bz = (gp.dims[2] + kBlock - 1) / kBlock;
  struct Change {
    uint64_t index;
    bool inside;
  };
  std::vector<std::vector<Change>> changes(size_t(bx) * by * bz);
  std::vector<uint64_t> evaluated(changes.size(), 0), uncertain(changes.size(), 0);
  pool.parallel_for(changes.size(), [&](size_t blk) {
    const uint32_t x0 = uint32_t(blk % bx) * kBlock, y0 = uint32_t(blk / bx % by) * kBlock,
                   z0 = uint32_t(blk / (size_t(bx) * by)) * kBlock;
    const std::array<uint32_t, 3> lo = {x0, y0, z0};
    const std::array<uint32_t, 3> hi = {std::min(x0 + kBlock, gp.dims[0]), std::min(y0 + kBlock, gp.dims[1]),
                                        std::min(z0 + kBlock, gp.dims[2])};
    field.uncertain_voxels(lo, hi, kUncertainLow, [&](uint32_t x, uint32_t y, uint32_t z, double near, double bound) {
      const uint64_t i = vm.index(x, y, z);
      if (skip && ((*skip)[i >> 6] >> (i & 63)) & 1) return;
      ++evaluated[blk];
      const double w = detail::near_hole_winding(field, cc, x, y, z, near, bound);
      if (w >= kUncertainLow && w <= kUncertainHigh) ++uncertain[blk];
      const bool inside = w >= 0.5;
      if (inside != (vm.at(i) == kInterior)) changes[blk].push_back({i, inside});
    });
  });
  for (size_t b = 0; b < changes.size(); ++b) {
    for (const Change& ch : changes[b]) vm.set(ch.index, ch.inside ? kInterior : kEmpty);
    rep.evaluated += evaluated[b];
    rep.uncertain += uncertain[b];
  }
}

}  // namespace

// Steps 1-4 of the voxeliser on grid gp: every voxel whose centre has a generalized winding number of the non-sheet
// triangles of at least 1/2 becomes interior in vm (all empty before). Step 4 leaves out the voxels set in *skip
// (the surface voxels, which voxelize overrides anyway); with skip null every voxel is decided.
void fill_solid(const Mesh& mesh, const GridMesh& gm, const GridPlacement& gp, ThreadPool& pool,
                const std::vector<uint64_t>* skip, Voxmap& vm, VoxelizeReport& rep) {
  // 1. The closed chain: the triangles that bound the solid (sheets excluded) minus the caps of their boundary.
  const detail::Chain chain = detail::closed_chain(mesh, gm);
  // 2. and 3.: the chain's crossings with every column, and the fill they give (W >= 1).
  const detail::ColumnCrossings cc = detail::column_crossings(chain, gm, gp, pool, detail::ZWindow{});
  const uint64_t nx = gp.dims[0];
  detail::walk_columns(mesh.name, gp, cc, [&](size_t c, uint64_t lo, uint64_t hi) {
    fill_interior(vm.words(), uint64_t(c) * nx + lo, uint64_t(c) * nx + hi);
  });
  // 4. Near the holes.
  if (!chain.caps.empty()) refine_near_holes(chain.caps, gp, cc, pool, skip, vm, rep);
}

std::vector<uint64_t> solid_bits(const Mesh& mesh, const GridPlacement& g, unsigned threads,
                                 std::vector<uint64_t>* surface) {
  if (mesh.points_only()) throw MeshError(mesh.name + ": a point cloud encloses no solid");
  const GridMesh gm = to_grid(mesh, g);
  ThreadPool pool(threads);
  if (surface) *surface = surface_bits_grid(gm, mesh, g, pool);
  Voxmap vm(g);
  VoxelizeReport rep;
  fill_solid(mesh, gm, g, pool, nullptr, vm, rep);
  // Interior states (2) to bits.
  std::vector<uint64_t> bits((g.size() + 63) / 64, 0);
  const auto& w = vm.words();
  for (size_t i = 0; i < w.size(); ++i) {
    uint64_t x = (w[i] >> 1) & 0x5555555555555555ull;  // the high bit of each state
    // Compact the even bits into 32 bits.
    x = (x | (x >> 1)) & 0x3333333333333333ull;
    x = (x | (x >> 2)) & 0x0f0f0f0f0f0f0f0full;
    x = (x | (x >> 4)) & 0x00ff00ff00ff00ffull;
    x = (x | (x >> 8)) & 0x0000ffff0000ffffull;
    x = (x | (x >> 16)) & 0x00000000ffffffffull;
    bits[i >> 1] |= x << (32 * (i & 1));
  }
  return bits;
}

}  // namespace detail

}  // namespace voxcd
