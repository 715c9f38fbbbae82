// The voxeliser's surface voxels: every voxel a triangle overlaps (or a point cloud's vertices touch), set over
// whatever the fill gave; the triangle-cube overlap test.
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

std::vector<uint64_t> surface_bits_grid(const GridMesh& gm, const Mesh& m, const GridPlacement& gp,
                                        ThreadPool& pool) {
  std::vector<uint64_t> bits((gp.size() + 63) / 64, 0);
  const auto parts = detail::chunks(m.size(), pool.size());
  const uint64_t nx = gp.dims[0], nxy = nx * gp.dims[1];
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t t = parts[p].first; t < parts[p].second; ++t)
      detail::triangle_voxels(gm, m, t, gp, [&](uint32_t x, uint32_t y, uint32_t z) {
        const uint64_t i = x + nx * y + nxy * z;
        uint64_t* w = &bits[i >> 6];
        const uint64_t bit = uint64_t{1} << (i & 63);
        if (!(__atomic_load_n(w, __ATOMIC_RELAXED) & bit)) __atomic_fetch_or(w, bit, __ATOMIC_RELAXED);
      });
  });
  return bits;
}

namespace {

// 32 bits to the even bits of 64.
uint64_t spread(uint64_t x) {
  x &= 0xffffffffull;
  x = (x | (x << 16)) & 0x0000ffff0000ffffull;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffull;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0full;
  x = (x | (x << 2)) & 0x3333333333333333ull;
  x = (x | (x << 1)) & 0x5555555555555555ull;
  return x;
}

}  // namespace

// Bit i set for every voxel whose cube, grown by kGrow, holds a vertex (a point cloud's surface).
std::vector<uint64_t> point_bits(const Mesh& m, const GridPlacement& gp) {
  std::vector<uint64_t> bits((gp.size() + 63) / 64, 0);
  const uint64_t nx = gp.dims[0], nxy = nx * gp.dims[1];
  for (const Eigen::Vector3d& p : m.vertices) {
    if (!p.allFinite()) continue;
    detail::point_voxels((p - gp.origin) / gp.voxel, gp, [&](uint32_t x, uint32_t y, uint32_t z) {
      const uint64_t i = uint64_t(x) + nx * uint64_t(y) + nxy * uint64_t(z);
      bits[i >> 6] |= uint64_t{1} << (i & 63);
    });
  }
  return bits;
}

// Surface voxels override whatever the fill gave.
void apply_surface(Voxmap& vm, const std::vector<uint64_t>& sb) {
  auto& w = vm.words();
  for (size_t i = 0; i < w.size(); ++i) {
    const uint64_t s = spread(sb[i >> 1] >> (32 * (i & 1)));
    w[i] = (w[i] & ~(s | (s << 1))) | s;
  }
}

}  // namespace detail

using detail::GridMesh;
using detail::to_grid;

std::vector<uint64_t> surface_bits(const Mesh& mesh, const GridPlacement& g, unsigned threads) {
  if (mesh.points_only()) return detail::point_bits(mesh, g);
  ThreadPool pool(threads);
  return detail::surface_bits_grid(to_grid(mesh, g), mesh, g, pool);
}

void for_each_overlap(const Mesh& mesh, const GridPlacement& g, size_t t0, size_t t1,
                      const std::function<void(size_t, uint32_t, uint32_t, uint32_t)>& fn) {
  const GridMesh gm = to_grid(mesh, g);
  for (size_t t = t0; t < t1 && t < mesh.size(); ++t)
    detail::triangle_voxels(gm, mesh, t, g, [&](uint32_t x, uint32_t y, uint32_t z) { fn(t, x, y, z); });
}

bool triangle_meets_cube(const Eigen::Vector3d& c, double h, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             const Eigen::Vector3d& d) {
  const Eigen::Vector3d v0 = a - c, v1 = b - c, v2 = d - c;
  for (int i = 0; i < 3; ++i) {
    if (std::min({v0[i], v1[i], v2[i]}) > h || std::max({v0[i], v1[i], v2[i]}) < -h) return false;
  }
  const Eigen::Vector3d e[3] = {v1 - v0, v2 - v1, v0 - v2};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      axis[i] = 1;
      axis = axis.cross(e[k]);
      const double p0 = axis.dot(v0), p1 = axis.dot(v1), p2 = axis.dot(v2);
      const double r = h * axis.cwiseAbs().sum();
      if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
    }
  const Eigen::Vector3d n = e[0].cross(e[1]);
  return std::abs(n.dot(v0)) <= h * n.cwiseAbs().sum();
}

}  // namespace voxcd
