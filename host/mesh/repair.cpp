// repair(): a triangle soup as real exports give it, made into the best surface it allows, and reported. The
// steps, in order (docs/objects.md, "Repair"): drop triangles with a non-finite corner, weld vertices within
// kWeldRelative of the model's size, drop degenerate triangles and exact duplicates, orient each part
// consistently, orient parts outward (nested closed parts keep the orientation they were given, so cavities stay
// cavities), and mark the parts that enclose nothing as sheets.
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

#include "voxcd/host/mesh/mesh.h"

namespace voxcd {

namespace {

using detail::EdgeUse;
using detail::UnionFind;
using detail::edge_uses;

// A hole whose fill has more than this fraction of its part's area makes the part a sheet (docs/objects.md).
constexpr double kSheetRatio = 0.4;
// Open parts whose boundaries come this close (relative to the model's size) close each other (cracks).
constexpr double kCrackRelative = 1e-2;
// Nesting is tested between every two parts up to this many parts.
constexpr size_t kMaxNestingParts = 4096;

// The key of a cell of a spatial hash.
struct CellKeyHash {
  size_t operator()(const std::array<int64_t, 3>& k) const {
    return size_t((uint64_t(k[0]) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(k[1]) * 0xc2b2ae3d27d4eb4full) ^
                  (uint64_t(k[2]) * 0x165667b19e3779f9ull));
  }
};


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

// Signed volume of a part closed by the cone from its centroid (positive when its triangles face outward).
double part_volume(const Mesh& m, const std::vector<uint32_t>& tris) {
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  for (uint32_t t : tris) o += (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3;
  o /= double(tris.size());
  double v = 0;
  for (uint32_t t : tris) v += (m.corner(t, 0) - o).dot((m.corner(t, 1) - o).cross(m.corner(t, 2) - o));
  return v / 6;
}

// Parity of the crossings of the ray from p along a fixed irrational direction with the triangles `tris`.
bool inside_part(const Mesh& m, const std::vector<uint32_t>& tris, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = Eigen::Vector3d(0.5773502691896258, 0.5780821362, 0.5766176874).normalized();
  int n = 0;
  for (uint32_t t : tris) n += detail::ray_crosses(m, t, p, d);
  return n % 2 == 1;
}


// Per triangle, what the non-manifold parts' cells decided (detail/cells.h).
struct CellDecision {
  std::vector<uint8_t> part;     // 0: a part without non-manifold edges; else 1 + the resolved part's number
  std::vector<uint8_t> fin;      // empty space on both sides: a sheet
  std::vector<uint8_t> reverse;  // a boundary triangle to reverse so that it faces the empty side
  size_t parts = 0;
};

// Parts (edge-connected) with an edge of three triangles or more are decided by their cells: internal triangles
// are dropped, boundary triangles face the empty side, fins become sheets. Counts the non-manifold edges found.
CellDecision resolve_nonmanifold(Mesh& m, const std::vector<EdgeUse>& uses, MeshReport& r) {
  const size_t n = m.size();
  UnionFind parts{n};
  std::vector<char> nonmanifold(n, 0);
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    for (size_t k = i + 1; k < j; ++k) parts.unite(uses[i].tri, uses[k].tri);
    if (j - i > 2) {
      ++r.nonmanifold_edges;
      nonmanifold[uses[i].tri] = 1;
    }
    i = j;
  }
  std::vector<std::vector<uint32_t>> members(n);
  for (uint32_t t = 0; t < n; ++t) members[parts.find(t)].push_back(t);
  std::vector<char> flagged(n, 0);
  for (uint32_t t = 0; t < n; ++t)
    if (nonmanifold[t]) flagged[parts.find(t)] = 1;
  CellDecision d;
  d.part.assign(n, 0);
  d.fin.assign(n, 0);
  d.reverse.assign(n, 0);
  std::vector<char> drop(n, 0);
  for (uint32_t root = 0; root < n; ++root) {
    if (!flagged[root]) continue;
    const detail::CellRoles roles = detail::classify_cells(m, members[root]);
    ++d.parts;
    for (size_t i = 0; i < members[root].size(); ++i) {
      const uint32_t t = members[root][i];
      d.part[t] = uint8_t(1 + (d.parts - 1) % 255);
      d.fin[t] = roles.role[i] == detail::FaceRole::kFin;
      d.reverse[t] = roles.reverse[i];
      drop[t] = roles.role[i] == detail::FaceRole::kInternal;
    }
  }
  r.nonmanifold_parts = d.parts;
  if (std::find(drop.begin(), drop.end(), 1) != drop.end()) {
    size_t k = 0;
    for (size_t t = 0; t < n; ++t) {
      if (drop[t]) {
        ++r.dropped_internal;
        continue;
      }
      m.triangles[k] = m.triangles[t];
      d.part[k] = d.part[t];
      d.fin[k] = d.fin[t];
      d.reverse[k] = d.reverse[t];
      ++k;
    }
    m.triangles.resize(k);
    d.part.resize(k);
    d.fin.resize(k);
    d.reverse.resize(k);
  }
  r.fin_triangles = size_t(std::count(d.fin.begin(), d.fin.end(), 1));
  return d;
}

// Patches: triangles joined across edges of exactly two triangles, each oriented consistently and as most of its
// triangles were given; a resolved non-manifold part is one patch of its boundary triangles, oriented by its cells,
// and one of its fins.
struct Patches {
  std::vector<uint32_t> of;                  // per triangle
  std::vector<std::vector<uint32_t>> list;   // per patch, its triangles
  std::vector<uint8_t> resolved;             // per patch: 1 the boundary of a resolved part, 2 its fins, 0 neither
  std::vector<char> flip;                    // per triangle: reversed
};

Patches orient_patches(Mesh& m, const std::vector<EdgeUse>& uses, const CellDecision& cells) {
  const size_t n = m.size();
  // At most one neighbour across each of a triangle's three edges (an edge of exactly two triangles); bit k of
  // same[t]: the neighbour runs that edge the same way in the input.
  std::vector<std::array<uint32_t, 3>> adj(n, {UINT32_MAX, UINT32_MAX, UINT32_MAX});
  std::vector<uint8_t> degree(n, 0), same(n, 0);
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 2 && !cells.part[uses[i].tri]) {
      const bool s2 = uses[i].forward == uses[i + 1].forward;
      for (const auto& [a, b] : {std::make_pair(uses[i].tri, uses[i + 1].tri), std::make_pair(uses[i + 1].tri, uses[i].tri)}) {
        same[a] = uint8_t(same[a] | (s2 ? 1u << degree[a] : 0u));
        adj[a][degree[a]++] = b;
      }
    }
    i = j;
  }
  Patches p;
  p.of.assign(n, UINT32_MAX);
  p.flip.assign(n, 0);
  std::map<std::pair<uint8_t, bool>, uint32_t> resolved_patch;  // (part, fin) -> patch
  for (uint32_t s = 0; s < n; ++s) {
    if (p.of[s] != UINT32_MAX) continue;
    if (cells.part[s]) {
      const auto key = std::make_pair(cells.part[s], bool(cells.fin[s]));
      auto [it, fresh] = resolved_patch.emplace(key, uint32_t(p.list.size()));
      if (fresh) {
        p.list.emplace_back();
        p.resolved.push_back(cells.fin[s] ? 2 : 1);
      }
      p.of[s] = it->second;
      p.list[it->second].push_back(s);
      p.flip[s] = char(cells.reverse[s]);
      continue;
    }
    const uint32_t id = uint32_t(p.list.size());
    p.list.emplace_back();
    p.resolved.push_back(0);
    std::vector<uint32_t> queue = {s};
    p.of[s] = id;
    for (size_t q = 0; q < queue.size(); ++q) {
      const uint32_t t = queue[q];
      p.list[id].push_back(t);
      for (int e = 0; e < degree[t]; ++e) {
        const uint32_t u = adj[t][e];
        if (p.of[u] != UINT32_MAX) continue;
        p.of[u] = id;
        p.flip[u] = char(p.flip[t] ^ ((same[t] >> e) & 1));
        queue.push_back(u);
      }
    }
    size_t flipped = 0;
    for (uint32_t t : p.list[id]) flipped += size_t(p.flip[t]);
    if (2 * flipped > p.list[id].size() || (2 * flipped == p.list[id].size() && p.flip[p.list[id][0]]))
      for (uint32_t t : p.list[id]) p.flip[t] ^= 1;
  }
  for (size_t t = 0; t < n; ++t)
    if (p.flip[t]) std::swap(m.triangles[t][1], m.triangles[t][2]);
  return p;
}

// The edges after orientation (a reversed triangle runs each of its edges the other way); counts open and
// inconsistent edges. A patch is closed when each of its edges is used by an even number of its triangles, as
// often one way as the other.
std::vector<char> closed_patches(std::vector<EdgeUse>& after, const Patches& p, MeshReport& r) {
  for (EdgeUse& u : after) u.forward = u.forward != bool(p.flip[u.tri]);
  std::vector<char> closed(p.list.size(), 1);
  for (size_t i = 0; i < after.size();) {
    size_t j = i;
    while (j < after.size() && after[j].key == after[i].key) ++j;
    const size_t k = j - i;
    if (k == 1) ++r.open_edges;
    if (k == 2 && after[i].forward == after[i + 1].forward) ++r.inconsistent_edges;
    for (size_t a = i; a < j; ++a) {
      const uint32_t q = p.of[after[a].tri];
      int uses_in_q = 0, fwd = 0;
      for (size_t b = i; b < j; ++b)
        if (p.of[after[b].tri] == q) {
          ++uses_in_q;
          fwd += after[b].forward ? 1 : 0;
        }
      if (uses_in_q == 0 || uses_in_q != 2 * fwd) closed[q] = 0;
    }
    i = j;
  }
  for (size_t q = 0; q < p.list.size(); ++q)
    if (p.resolved[q] == 2) closed[q] = 0;  // fins enclose nothing
  return closed;
}

// Outward, nested parts alternating: a patch inside d closed patches (its box inside theirs, and sampled vertices
// inside by parity) faces outward when d is even and inward when d is odd, so a cavity stays empty whichever way its
// surface was given. Open patches use the volume closed by the cone from their centroid; a resolved part's boundary
// already faces out of its own cells and turns only when nested. Returns the triangles reversed in all.
size_t orient_outward(Mesh& m, Patches& p, const std::vector<char>& closed) {
  const size_t np = p.list.size();
  std::vector<double> vol(np);
  std::vector<Eigen::Vector3d> plo(np), phi(np);
  for (size_t q = 0; q < np; ++q) {
    vol[q] = part_volume(m, p.list[q]);
    plo[q] = Eigen::Vector3d::Constant(HUGE_VAL);
    phi[q] = -plo[q];
    for (uint32_t t : p.list[q])
      for (uint32_t v : m.triangles[t]) {
        plo[q] = plo[q].cwiseMin(m.vertices[v]);
        phi[q] = phi[q].cwiseMax(m.vertices[v]);
      }
  }
  auto depth = [&](size_t a) {
    size_t d = 0;
    if (np > kMaxNestingParts) return d;  // (pairs too many to test: every part outward)
    for (size_t b = 0; b < np; ++b) {
      if (b == a || !closed[b]) continue;
      if ((plo[a].array() <= plo[b].array()).any() || (phi[a].array() >= phi[b].array()).any()) continue;
      bool all = true;
      const size_t step = std::max<size_t>(1, p.list[a].size() / 8);
      for (size_t k = 0; k < p.list[a].size() && all; k += step) all = inside_part(m, p.list[b], m.corner(p.list[a][k], 0));
      d += all ? 1 : 0;
    }
    return d;
  };
  for (size_t q = 0; q < np; ++q) {
    if (p.resolved[q] == 2) continue;
    const bool inward = depth(q) % 2 == 1;
    const bool turn = p.resolved[q] ? inward : vol[q] != 0 && (vol[q] < 0) != inward;
    if (!turn) continue;
    for (uint32_t t : p.list[q]) {
      std::swap(m.triangles[t][1], m.triangles[t][2]);
      p.flip[t] ^= 1;
    }
  }
  return size_t(std::count(p.flip.begin(), p.flip.end(), 1));
}

// The patches grouped with the open patches whose boundary vertices come within `gap` of theirs (parts split by
// cracks close each other); resolved parts' fins (resolved 2) are left alone.
UnionFind group_by_cracks(const Mesh& m, const Patches& p, const std::vector<EdgeUse>& after, double gap) {
  UnionFind group{p.list.size()};
  std::unordered_map<std::array<int64_t, 3>, std::vector<std::pair<uint32_t, uint32_t>>, CellKeyHash> cells;
  auto key_of = [&](const Eigen::Vector3d& x) {
    std::array<int64_t, 3> k{};
    for (int a = 0; a < 3; ++a) k[a] = int64_t(std::floor(x[a] / gap));
    return k;
  };
  for (size_t i = 0; i < after.size();) {
    size_t j = i;
    while (j < after.size() && after[j].key == after[i].key) ++j;
    const uint32_t q = p.of[after[i].tri];
    if (j - i == 1 && p.resolved[q] != 2) {
      for (uint32_t v : {uint32_t(after[i].key >> 32), uint32_t(after[i].key)}) {
        const auto k = key_of(m.vertices[v]);
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const auto it = cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
              if (it == cells.end()) continue;
              for (const auto& [w, o] : it->second)
                if (o != q && (m.vertices[w] - m.vertices[v]).norm() <= gap) group.unite(q, o);
            }
        cells[k].push_back({v, q});
      }
    }
    i = j;
  }
  return group;
}

// Sheets: patches grouped with the open patches whose boundary vertices come within kCrackRelative of the model's size
// of theirs (parts split by cracks close each other); a group whose boundary encloses more than kSheetRatio of
// its area (the vector area of its boundary loops, origin-independent for closed loops) encloses nothing. A
// resolved part's fins are sheets whatever their boundary.
void mark_sheets(Mesh& m, const Patches& p, const std::vector<EdgeUse>& after, const std::vector<char>& closed,
                 const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, MeshReport& r) {
  const size_t n = m.size(), np = p.list.size();
  UnionFind group = group_by_cracks(m, p, after, kCrackRelative * (hi - lo).norm());
  std::vector<Eigen::Vector3d> loop_area(np, Eigen::Vector3d::Zero());
  std::vector<double> area(np, 0);
  const Eigen::Vector3d centre = (lo + hi) / 2;
  for (size_t t = 0; t < n; ++t) {
    const uint32_t g = group.find(p.of[t]);
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    area[g] += (b - a).cross(c - a).norm() / 2;
    // The vector area of the triangle's edges as part of the boundary chain: the boundary's is the sum over every
    // triangle of its own (inner edges cancel).
    loop_area[g] += ((a - centre).cross(b - centre) + (b - centre).cross(c - centre) + (c - centre).cross(a - centre)) / 2;
  }
  std::vector<char> sheet_group(np, 0);
  for (size_t q = 0; q < np; ++q) {
    const uint32_t g = group.find(uint32_t(q));
    if (g != q) continue;
    // The triangles' own vector areas sum to the boundary's: for a closed group it is zero up to rounding.
    sheet_group[g] = loop_area[g].norm() > kSheetRatio * area[g];
  }
  auto is_sheet = [&](uint32_t q) { return p.resolved[q] == 2 || sheet_group[group.find(q)]; };
  m.sheet.assign(n, 0);
  bool any_solid = false;
  for (size_t t = 0; t < n; ++t) {
    m.sheet[t] = is_sheet(p.of[t]);
    any_solid |= !m.sheet[t];
  }
  for (uint32_t q = 0; q < np; ++q) {
    if (closed[q]) ++r.closed_components;
    if (is_sheet(q)) ++r.sheet_components;
  }
  if (!any_solid) r.surface_only = true;
  if (std::none_of(m.sheet.begin(), m.sheet.end(), [](uint8_t s) { return s != 0; })) m.sheet.clear();
}

// Drops the vertices no triangle uses any more (of dropped triangles, or moved by welding).
void drop_unused_vertices(Mesh& m) {
  std::vector<uint32_t> to(m.vertices.size(), UINT32_MAX);
  for (const auto& t : m.triangles)
    for (uint32_t v : t) to[v] = 0;
  std::vector<Eigen::Vector3d> kept;
  for (size_t v = 0; v < m.vertices.size(); ++v)
    if (to[v] == 0) {
      to[v] = uint32_t(kept.size());
      kept.push_back(m.vertices[v]);
    }
  for (auto& t : m.triangles)
    for (uint32_t& v : t) v = to[v];
  m.vertices = std::move(kept);
}

size_t count_components(const Mesh& m) {
  UnionFind parts{m.size()};
  const std::vector<EdgeUse> uses = edge_uses(m);
  for (size_t i = 1; i < uses.size(); ++i)
    if (uses[i].key == uses[i - 1].key) parts.unite(uses[i - 1].tri, uses[i].tri);
  size_t c = 0;
  for (uint32_t t = 0; t < m.size(); ++t) c += parts.find(t) == t;
  return c;
}

// Makes a point cloud of the mesh's finite vertices (or of `corners`, when given) and reports it.
MeshReport& to_point_cloud(Mesh& m, MeshReport& r, const std::vector<uint32_t>* corners) {
  if (corners) {
    std::vector<char> used(m.vertices.size(), 0);
    for (uint32_t v : *corners) used[v] = 1;
    std::vector<Eigen::Vector3d> pts;
    for (size_t v = 0; v < m.vertices.size(); ++v)
      if (used[v]) pts.push_back(m.vertices[v]);
    m.vertices = std::move(pts);
  }
  r.points_only = r.surface_only = true;
  r.vertices = m.vertices.size();
  m.sheet.clear();
  return r;
}

// The bounding box of the vertices the triangles use (of the finite vertices for a point cloud); MeshError when
// nothing finite is left.
void finite_bounds(const Mesh& m, const MeshReport& r, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  lo = Eigen::Vector3d::Constant(HUGE_VAL);
  hi = -lo;
  auto grow = [&](const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  if (!m.triangles.empty()) {
    for (const auto& t : m.triangles)
      for (uint32_t v : t) grow(m.vertices[v]);
  } else {
    for (const auto& p : m.vertices)
      if (p.allFinite()) grow(p);
  }
  if (lo.allFinite()) return;
  if (r.input_triangles)
    throw MeshError(m.name + ": none of the mesh's " + std::to_string(r.input_triangles) +
                    " triangles has finite corners");
  throw MeshError(m.name + (m.vertices.empty() ? ": the file holds no triangles and no points"
                                               : ": the file holds no triangles and no finite points"));
}

}  // namespace

MeshReport repair(Mesh& m) {
  MeshReport r;
  r.input_vertices = m.vertices.size();
  r.input_triangles = m.triangles.size();
  for (size_t t = 0; t < m.size(); ++t)
    for (uint32_t v : m.triangles[t])
      if (v >= m.vertices.size())
        throw MeshError(m.name + ": triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                        " out of range (" + std::to_string(m.vertices.size()) + " vertices)");
  r.dropped_nonfinite = drop_nonfinite(m);
  const bool had_triangles = !m.triangles.empty();
  Eigen::Vector3d lo, hi;
  finite_bounds(m, r, lo, hi);
  r.weld_tolerance = kWeldRelative * (hi - lo).norm();
  size_t near = 0;
  r.welded = weld_near(m, r.weld_tolerance, &near);
  r.welded_near = near;
  if (!had_triangles) return to_point_cloud(m, r, nullptr);
  std::vector<uint32_t> dropped_corners;  // corners of every triangle, in case none survives
  for (const auto& t : m.triangles) dropped_corners.insert(dropped_corners.end(), t.begin(), t.end());
  drop_degenerate_and_duplicates(m, r);
  // Every triangle was a point or a segment: what is left is its corners, a point cloud.
  if (m.triangles.empty()) return to_point_cloud(m, r, &dropped_corners);

  // Cracks between parts: open edges of different parts within kCrackCloseRelative of the model's size are
  // joined (counted as welded within tolerance), and what that makes degenerate or duplicate is dropped.
  std::vector<EdgeUse> uses = edge_uses(m);
  if (const size_t moved = close_cracks(m, uses, kCrackCloseRelative * (hi - lo).norm())) {
    r.welded += moved;
    r.welded_near += moved;
    near += moved;
    drop_degenerate_and_duplicates(m, r);
    uses = edge_uses(m);
  }
  const CellDecision cells = resolve_nonmanifold(m, uses, r);
  if (r.dropped_internal) uses = edge_uses(m);
  Patches patches = orient_patches(m, uses, cells);
  std::vector<EdgeUse> after = std::move(uses);  // the same edges; a reversed triangle runs each the other way
  const std::vector<char> closed = closed_patches(after, patches, r);
  const size_t reversed = orient_outward(m, patches, closed);
  if (reversed == m.size())
    r.flipped = true;
  else
    r.reoriented = reversed;
  mark_sheets(m, patches, after, closed, lo, hi, r);
  r.components = count_components(m);
  drop_unused_vertices(m);
  r.vertices = m.vertices.size();
  r.triangles = m.triangles.size();
  r.closed = near == 0 && r.dropped_nonfinite == 0 && r.dropped_repeated == 0 && r.dropped_collinear == 0 &&
             r.dropped_duplicate == 0 && r.open_edges == 0 && r.nonmanifold_edges == 0 &&
             r.inconsistent_edges == 0 && r.reoriented == 0;
  return r;
}

}  // namespace voxcd
