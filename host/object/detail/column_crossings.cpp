#include "voxcd/host/object/detail/column_crossings.h"

#include <algorithm>
#include <cmath>

namespace voxcd::detail {

namespace {

struct SignedCrossing {
  uint32_t col;  // y + ny * (z - z0)
  int32_t sign;  // +1 where the ray leaves the side the normal points away from (normal x > 0), times the weight
  double x;      // along the ray, in voxels
};

}  // namespace

Chain closed_chain(const Mesh& mesh, const GridMesh& gm) {
  Chain ch;
  if (mesh.sheet.empty()) {
    ch.solid = mesh.triangles;
  } else {
    for (size_t t = 0; t < mesh.size(); ++t)
      if (!mesh.is_sheet(t)) ch.solid.push_back(mesh.triangles[t]);
  }
  ch.caps = boundary_caps(gm.q, ch.solid, kFrac);
  return ch;
}

int64_t ColumnCrossings::prefix(size_t c, double x) const {
  int64_t p = 0;
  for (uint32_t k = start[c]; k < start[c + 1] && xs[k].first <= x; ++k) p += xs[k].second;
  return p;
}

ColumnCrossings column_crossings(const Chain& chain, const GridMesh& gm, const GridPlacement& gp, ThreadPool& pool,
                                 const ZWindow& win, const uint32_t* items, size_t n) {
  const int64_t z0 = std::max<int64_t>(0, win.z0);
  const int64_t z1 = std::min<int64_t>(int64_t(gp.dims[2]) - 1, win.z1);
  const size_t n_items = items ? n : chain.size();
  const auto parts = chunks(n_items, pool.size());
  std::vector<std::vector<SignedCrossing>> found(parts.size());
  const uint32_t ny = gp.dims[1];
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t k = parts[p].first; k < parts[p].second; ++k) {
      const size_t i = items ? items[k] : k;
      auto emit = [&](int32_t weight) {
        return [&, weight](uint32_t y, uint32_t z, double x, bool front) {
          found[p].push_back({uint32_t(y + uint64_t(ny) * uint64_t(z - z0)), (front ? 1 : -1) * weight, x});
        };
      };
      if (i < chain.solid.size()) {
        const auto& t = chain.solid[i];
        crossings_of(gm.q[t[0]], gm.q[t[1]], gm.q[t[2]], gp, emit(1), win);
      } else {
        const auto& c = chain.caps[i - chain.solid.size()];
        crossings_of(c.a, c.b, c.c, gp, emit(-c.weight), win);
      }
    }
  });
  ColumnCrossings cc;
  cc.ny = ny;
  cc.z0 = z0;
  const size_t cols = z1 >= z0 ? size_t(ny) * size_t(z1 - z0 + 1) : 0;
  cc.start.assign(cols + 1, 0);
  for (const auto& f : found)
    for (const SignedCrossing& c : f) ++cc.start[c.col + 1];
  for (size_t c = 0; c < cols; ++c) cc.start[c + 1] += cc.start[c];
  cc.xs.resize(cc.start[cols]);
  std::vector<uint32_t> at(cc.start.begin(), cc.start.end() - 1);
  for (const auto& f : found)
    for (const SignedCrossing& c : f) cc.xs[at[c.col]++] = {c.x, c.sign};
  found.clear();
  found.shrink_to_fit();
  const size_t sorts = std::min<size_t>(cols, 64);
  pool.parallel_for(sorts, [&](size_t part) {
    for (size_t c = cols * part / sorts; c < cols * (part + 1) / sorts; ++c)
      std::sort(cc.xs.begin() + cc.start[c], cc.xs.begin() + cc.start[c + 1]);
  });
  return cc;
}

double near_hole_winding(const CapField& field, const ColumnCrossings& cc, uint32_t x, uint32_t y, uint32_t z,
                         double near, double bound) {
  const double cx = x + 0.5;
  const int64_t prefix = cc.prefix(cc.column(y, z), cx);
  // The near caps' exact part with the bound on the rest decides, unless 1/2 lies within the bound (or the bound is
  // too loose to say how certain the voxel is): then the whole field is evaluated.
  double w = double(-prefix) + near;
  if (!(bound <= kNearEnough && std::abs(w - 0.5) > bound))
    w = double(-prefix) + field.value(Eigen::Vector3d(cx, y + 0.5, z + 0.5));
  return w;
}

}  // namespace voxcd::detail
