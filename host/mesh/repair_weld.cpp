// repair()'s cleaning (detail/repair_steps.h): triangles with a non-finite corner dropped, vertices welded within a
// tolerance, degenerate and duplicate triangles dropped, and cracks between parts closed.
#include "voxcd/host/mesh/detail/repair_steps.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <map>
#include <unordered_map>

#include "voxcd/host/mesh/detail/cells.h"
#include "voxcd/host/mesh/detail/edge_uses.h"
#include "voxcd/host/mesh/detail/point_hash.h"
#include "voxcd/host/mesh/ray_crossing.h"
#include "voxcd/host/mesh/detail/union_find.h"


namespace voxcd::detail::mesh_repair {

using detail::EdgeUse;
using detail::UnionFind;
using detail::edge_uses;

// Drops vertices no triangle uses and triangles with a non-finite corner; the finite vertices of a triangle-less
// mesh are kept (a point cloud).
size_t drop_nonfinite(Mesh& m) {
  size_t dropped = 0;
  std::vector<std::array<uint32_t, 3>> kept;
  kept.reserve(m.triangles.size());
  for (const auto& t : m.triangles) {
    if (m.vertices[t[0]].allFinite() && m.vertices[t[1]].allFinite() && m.vertices[t[2]].allFinite())
      kept.push_back(t);
    else
      ++dropped;
  }
  m.triangles = std::move(kept);
  return dropped;
}

// Merges exactly equal vertices, keeping index order (weld() numbers them by first use instead), and drops vertices
// no triangle uses; a point cloud keeps every finite point instead. Returns the vertices merged.
size_t weld_exact(Mesh& m) {
  if (m.triangles.empty()) {
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : m.vertices)
      if (p.allFinite()) pts.push_back(p);
    m.vertices = std::move(pts);
    return 0;
  }
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& t : m.triangles)
    for (uint32_t v : t) used[v] = 1;
  detail::ExactPoints points(m.vertices.size());
  std::vector<uint32_t> to(m.vertices.size(), UINT32_MAX);
  size_t n_used = 0;
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    if (!used[v]) continue;
    ++n_used;
    to[v] = points.add(m.vertices[v]);
  }
  for (auto& t : m.triangles)
    for (uint32_t& v : t) v = to[v];
  m.vertices = points.take();
  return n_used - m.vertices.size();
}

// Representatives of clusters of points within tol, in cells 4 tol wide, so that a point looks into a neighbouring
// cell only on an axis where it lies within tol of the cell's side. Each cell keeps a list of representatives
// through `next`.
class NearPoints {
 public:
  NearPoints(double tol, size_t n) : tol_(tol), cell_(4 * tol), next_(n, UINT32_MAX) {
    head_.reserve(n);
    out_.reserve(n);
  }
  // The representative of p: the first point kept within tol of it, else p itself, kept. *near: p was merged.
  uint32_t add(const Eigen::Vector3d& p, bool* near) {
    *near = false;
    if (!(tol_ > 0 && p.allFinite())) return keep(p);
    std::array<int64_t, 3> k{};
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double g = p[a] / cell_;
      k[a] = int64_t(std::floor(g));
      const double f = (g - double(k[a])) * 4;  // position in the cell, in units of tol
      lo[a] = f < 1 ? -1 : 0;
      hi[a] = f > 3 ? 1 : 0;
    }
    uint32_t found = UINT32_MAX;
    for (int dz = lo[2]; dz <= hi[2]; ++dz)
      for (int dy = lo[1]; dy <= hi[1]; ++dy)
        for (int dx = lo[0]; dx <= hi[0]; ++dx) {
          const auto it = head_.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == head_.end()) continue;
          for (uint32_t r = it->second; r != UINT32_MAX; r = next_[r])
            if ((out_[r] - p).cwiseAbs().maxCoeff() <= tol_ && r < found) found = r;
        }
    *near = found != UINT32_MAX;
    if (*near) return found;
    found = keep(p);
    auto [it, fresh] = head_.emplace(k, found);
    if (!fresh) {
      next_[found] = it->second;
      it->second = found;
    }
    return found;
  }
  std::vector<Eigen::Vector3d> take() { return std::move(out_); }

 private:
  uint32_t keep(const Eigen::Vector3d& p) {
    out_.push_back(p);
    return uint32_t(out_.size() - 1);
  }
  double tol_, cell_;
  std::unordered_map<std::array<int64_t, 3>, uint32_t, CellKeyHash> head_;
  std::vector<uint32_t> next_;
  std::vector<Eigen::Vector3d> out_;
};

// Welds vertices within `tol` (Chebyshev distance, to the first vertex of a cluster in index order, after exactly
// equal vertices are merged); vertices no triangle uses are dropped (all finite vertices are kept for a point cloud).
// Returns the vertices merged, and in *near those not exactly equal to their representative.
size_t weld_near(Mesh& m, double tol, size_t* near) {
  const size_t exact = weld_exact(m);
  NearPoints points(tol, m.vertices.size());
  std::vector<uint32_t> remap(m.vertices.size());
  size_t n_near = 0;
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    bool merged = false;
    remap[v] = points.add(m.vertices[v], &merged);
    n_near += merged;
  }
  for (auto& t : m.triangles)
    for (uint32_t& v : t) v = remap[v];
  m.vertices = points.take();
  if (near) *near = n_near;
  return exact + n_near;
}

bool zero_area(const Mesh& m, const std::array<uint32_t, 3>& t) {
  const Eigen::Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
  const double l2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return (b - a).cross(c - a).squaredNorm() <= 1e-26 * l2 * l2;
}

// Drops degenerate triangles (counted by cause) and exact duplicates (the same three vertices in either
// orientation; the first is kept).
void drop_degenerate_and_duplicates(Mesh& m, MeshReport& r) {
  std::vector<std::array<uint32_t, 3>> kept;
  kept.reserve(m.triangles.size());
  for (const auto& t : m.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      ++r.dropped_repeated;
    else if (zero_area(m, t))
      ++r.dropped_collinear;
    else
      kept.push_back(t);
  }
  std::vector<uint32_t> order(kept.size());
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](uint32_t i) {
    auto k = kept[i];
    std::sort(k.begin(), k.end());
    return k;
  };
  std::vector<std::array<uint32_t, 3>> keys(kept.size());
  for (size_t i = 0; i < kept.size(); ++i) keys[i] = key(uint32_t(i));
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  std::vector<char> dup(kept.size(), 0);
  for (size_t i = 1; i < order.size(); ++i)
    if (keys[order[i]] == keys[order[i - 1]]) dup[order[i]] = 1;
  std::vector<std::array<uint32_t, 3>> out;
  out.reserve(kept.size());
  for (size_t i = 0; i < kept.size(); ++i) {
    if (dup[i])
      ++r.dropped_duplicate;
    else
      out.push_back(kept[i]);
  }
  m.triangles = std::move(out);
}

// Closes cracks: a vertex on an open edge moves onto the nearest vertex on an open edge of another edge-connected
// part within `tol` (one that comes earlier in index order, so that no two vertices trade places). Returns how
// many vertices moved; the triangles are remapped.
size_t close_cracks(Mesh& m, const std::vector<EdgeUse>& uses, double tol) {
  UnionFind parts{m.size()};
  std::vector<char> boundary(m.vertices.size(), 0);
  bool any = false;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    for (size_t k = i + 1; k < j; ++k) parts.unite(uses[i].tri, uses[k].tri);
    if (j - i == 1) {
      boundary[uses[i].key >> 32] = boundary[uint32_t(uses[i].key)] = 1;
      any = true;
    }
    i = j;
  }
  if (!any || !(tol > 0)) return 0;
  std::vector<uint32_t> part_of(m.vertices.size(), UINT32_MAX);
  for (size_t t = 0; t < m.size(); ++t)
    for (uint32_t v : m.triangles[t]) part_of[v] = parts.find(uint32_t(t));
  std::unordered_map<std::array<int64_t, 3>, std::vector<uint32_t>, CellKeyHash> cells;
  auto key_of = [&](const Eigen::Vector3d& p) {
    std::array<int64_t, 3> k{};
    for (int a = 0; a < 3; ++a) k[a] = int64_t(std::floor(p[a] / tol));
    return k;
  };
  std::vector<uint32_t> to(m.vertices.size());
  std::iota(to.begin(), to.end(), 0u);
  size_t moved = 0;
  for (uint32_t v = 0; v < m.vertices.size(); ++v) {
    if (!boundary[v]) continue;
    const Eigen::Vector3d& p = m.vertices[v];
    const auto k = key_of(p);
    uint32_t best = UINT32_MAX;
    double best_d = tol;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == cells.end()) continue;
          for (uint32_t u : it->second) {
            const double d = (m.vertices[u] - p).norm();
            if (part_of[u] != part_of[v] && (d < best_d || (d == best_d && u < best))) {
              best = u;
              best_d = d;
            }
          }
        }
    if (best != UINT32_MAX) {
      to[v] = to[best];
      ++moved;
    } else {
      cells[k].push_back(v);
    }
  }
  if (moved)
    for (auto& t : m.triangles)
      for (uint32_t& v : t) v = to[v];
  return moved;
}


}  // namespace voxcd::detail::mesh_repair
