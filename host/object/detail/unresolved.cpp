// make_unresolved_conservative() (host/object/detail/unresolved.h): each triangle's piece in each cell it crosses,
// clipped to the cell, sampled at its corners and centroid against the field's interpolant, on the surface and a
// little inside it.
#include "voxcd/host/object/detail/unresolved.h"

#include <algorithm>
#include <atomic>
#include <vector>

#include "voxcd/ref/util/thread_pool.h"

namespace voxcd::detail {

namespace {

// The part of polygon p on the side x[axis] * sign <= bound * sign (Sutherland-Hodgman, one plane).
Polygon clip(const Polygon& p, int axis, double bound, double sign) {
  Polygon out;
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d& a = p[i];
    const Eigen::Vector3d& b = p[(i + 1) % p.size()];
    const double da = (a[axis] - bound) * sign, db = (b[axis] - bound) * sign;
    if (da <= 0) out.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

Polygon piece_in_cube(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& lo, double size) {
  Polygon p = {a, b, c};
  for (int axis = 0; axis < 3 && !p.empty(); ++axis) {
    p = clip(p, axis, lo[axis], -1);
    if (!p.empty()) p = clip(p, axis, lo[axis] + size, 1);
  }
  return p;
}

bool inward_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d& n) {
  const Eigen::Vector3d x = (b - a).cross(c - a);
  if (!(x.squaredNorm() > 0)) return false;
  n = -x.normalized();
  return true;
}

uint64_t make_unresolved_conservative(const Mesh& mesh, const GridPlacement& g, DistanceField& f, unsigned threads) {
  const uint64_t nx = g.dims[0], nxy = nx * g.dims[1];
  std::vector<std::atomic<uint64_t>> flags((g.size() + 63) / 64);
  for (auto& w : flags) w.store(0, std::memory_order_relaxed);
  std::vector<Eigen::Vector3d> gv(mesh.vertices.size());
  for (size_t i = 0; i < gv.size(); ++i) gv[i] = (mesh.vertices[i] - g.origin) / g.voxel;
  ThreadPool pool(threads);
  const double tolerance = kResolvedTolerance + f.step / 2;
  const size_t parts = std::max<size_t>(1, std::min<size_t>(mesh.size(), size_t(pool.size()) * 16));
  pool.parallel_for(parts, [&](size_t part) {
    const size_t t0 = mesh.size() * part / parts, t1 = mesh.size() * (part + 1) / parts;
    for_each_overlap(mesh, g, t0, t1, [&](size_t t, uint32_t x, uint32_t y, uint32_t z) {
      const uint64_t i = x + nx * y + nxy * z;
      if (flags[i >> 6].load(std::memory_order_relaxed) >> (i & 63) & 1) return;
      const auto& tri = mesh.triangles[t];
      if (!mesh.is_sheet(t)) {
        const Eigen::Vector3d& a = gv[tri[0]];
        const Eigen::Vector3d& b = gv[tri[1]];
        const Eigen::Vector3d& c = gv[tri[2]];
        Eigen::Vector3d inward;
        const auto sample = [&f](const Eigen::Vector3d& p) { return f.sample(p); };
        const auto deep = [&](const Eigen::Vector3d& p) { return f.sample(p + kResolvedDepth * inward) <= 0; };
        if (inward_normal(a, b, c, inward) &&
            piece_resolved(sample, piece_in_cube(a, b, c, Eigen::Vector3d(x, y, z), 1.0), tolerance, deep))
          return;
      }
      flags[i >> 6].fetch_or(uint64_t{1} << (i & 63), std::memory_order_relaxed);
    });
  });
  // Lower the nodes only once every cell is judged, so that the result does not depend on the order.
  uint64_t count = 0;
  for (uint64_t z = 0; z < g.dims[2]; ++z)
    for (uint64_t y = 0; y < g.dims[1]; ++y)
      for (uint64_t x = 0; x < nx; ++x) {
        const uint64_t i = x + nx * y + nxy * z;
        if (!(flags[i >> 6].load(std::memory_order_relaxed) >> (i & 63) & 1)) continue;
        ++count;
        for (int k = 0; k < 8; ++k) {
          int16_t& q = f.q[f.node_index(x + (k & 1), y + (k >> 1 & 1), z + (k >> 2 & 1))];
          q = std::min<int16_t>(q, 0);
        }
      }
  return count;
}

}  // namespace voxcd::detail
