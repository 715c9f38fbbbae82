// repair()'s orientation (detail/repair_steps.h): non-manifold parts decided by their cells, patches oriented
// consistently, then outward with nested parts alternating (cavities stay cavities).
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

namespace {

// Nesting is tested between every two parts up to this many parts.
constexpr size_t kMaxNestingParts = 4096;

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


}  // namespace

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


}  // namespace voxcd::detail::mesh_repair
