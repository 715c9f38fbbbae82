// classify_cells() (host/object/detail/cells.h): sides joined around edges by angle, then by rays; cells labelled
// by their distance from the unbounded cell.
#include "voxcd/host/object/detail/cells.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "voxcd/host/object/detail/closest.h"

namespace voxcd::detail {

namespace {

// Rays cast from each group of joined sides, spread over its triangles.
constexpr size_t kRaysPerGroup = 4;

struct Sets {
  std::vector<uint32_t> parent;
  explicit Sets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Side s of local triangle i: 2i is the side its normal points to, 2i + 1 the other.
inline uint32_t side(uint32_t i, bool front) { return 2 * i + (front ? 0 : 1); }

struct Use {
  uint64_t key;  // lo << 32 | hi
  uint32_t tri;  // local index
};

// Joins, around every edge used by two triangles or more, the two sides facing each wedge between neighbours in
// angular order.
void join_around_edges(const Mesh& m, const std::vector<uint32_t>& tris, Sets& sides) {
  std::vector<Use> uses;
  uses.reserve(3 * tris.size());
  for (uint32_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[tris[i]][k], b = m.triangles[tris[i]][(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), i});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) { return x.key != y.key ? x.key < y.key : x.tri < y.tri; });
  struct Around {
    double angle;
    uint32_t tri;
    bool front_ahead;  // the side facing increasing angle is the normal's
  };
  std::vector<Around> around;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i >= 2) {
      const Eigen::Vector3d& a = m.vertices[uint32_t(uses[i].key >> 32)];
      const Eigen::Vector3d e = (m.vertices[uint32_t(uses[i].key)] - a).normalized();
      const Eigen::Vector3d u = e.unitOrthogonal(), w = e.cross(u);
      around.clear();
      for (size_t k = i; k < j; ++k) {
        const auto& t = m.triangles[tris[uses[k].tri]];
        Eigen::Vector3d c = m.vertices[t[0]];  // the corner off the edge
        for (uint32_t v : t)
          if (v != uint32_t(uses[i].key >> 32) && v != uint32_t(uses[i].key)) c = m.vertices[v];
        const Eigen::Vector3d r = (c - a) - (c - a).dot(e) * e;
        const Eigen::Vector3d n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
        around.push_back({std::atan2(r.dot(w), r.dot(u)), uses[k].tri, n.dot(e.cross(r)) > 0});
      }
      std::sort(around.begin(), around.end(),
                [](const Around& x, const Around& y) { return x.angle != y.angle ? x.angle < y.angle : x.tri < y.tri; });
      for (size_t k = 0; k < around.size(); ++k) {
        const Around& p = around[k];
        const Around& q = around[(k + 1) % around.size()];
        sides.unite(side(p.tri, p.front_ahead), side(q.tri, !q.front_ahead));
      }
    }
    i = j;
  }
}

// Casts rays from a few sides of every group of joined sides along the side's normal: the side a ray meets first
// faces the same cell (joined); a ray that meets nothing marks its cell unbounded. One more ray from outside the
// part's box marks the side it meets first. Returns, per side, whether its cell is the unbounded one (after the
// joins, of its root).
std::vector<uint8_t> join_by_rays(const Mesh& m, const std::vector<uint32_t>& tris, Sets& sides) {
  std::vector<std::array<uint32_t, 3>> local(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) local[i] = m.triangles[tris[i]];
  const TriangleTree tree(m.vertices, local);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (const auto& t : local)
    for (uint32_t v : t) lo = lo.cwiseMin(m.vertices[v]), hi = hi.cwiseMax(m.vertices[v]);
  const double diag = (hi - lo).norm();
  const double min_l = 1e-12 * diag;
  // A direction off the axes and off simple ratios, so that rays seldom graze an edge.
  const Eigen::Vector3d tilt = Eigen::Vector3d(0.0137, -0.0071, 0.0213);
  std::vector<std::vector<uint32_t>> groups(2 * tris.size());
  for (uint32_t s = 0; s < 2 * tris.size(); ++s) groups[sides.find(s)].push_back(s);
  std::vector<uint8_t> unbounded(2 * tris.size(), 0);
  for (const auto& g : groups) {
    if (g.empty()) continue;
    const size_t n = std::min(kRaysPerGroup, g.size());
    for (size_t k = 0; k < n; ++k) {
      const uint32_t s = g[g.size() * k / n], i = s / 2;
      const auto& t = local[i];
      const Eigen::Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
      Eigen::Vector3d d = (b - a).cross(c - a).normalized() + tilt;
      if (s & 1) d = -(d - 2 * tilt);
      d.normalize();
      bool front = false;
      const uint32_t hit = tree.first_hit((a + b + c) / 3, d, i, min_l, nullptr, &front);
      if (hit == UINT32_MAX)
        unbounded[s] = 1;
      else
        sides.unite(s, side(hit, front));
    }
  }
  // From outside: towards the centroid of the triangle with the largest centroid x, from beyond the box.
  uint32_t far = 0;
  double far_x = -HUGE_VAL;
  for (uint32_t i = 0; i < local.size(); ++i) {
    const double x = m.vertices[local[i][0]].x() + m.vertices[local[i][1]].x() + m.vertices[local[i][2]].x();
    if (x > far_x) far_x = x, far = i;
  }
  const Eigen::Vector3d target =
      (m.vertices[local[far][0]] + m.vertices[local[far][1]] + m.vertices[local[far][2]]) / 3;
  const Eigen::Vector3d d = Eigen::Vector3d(-1, tilt.y(), tilt.z()).normalized();
  const Eigen::Vector3d o = target - d * (hi.x() - target.x() + diag + 1);
  bool front = false;
  const uint32_t hit = tree.first_hit(o, d, UINT32_MAX, 0, nullptr, &front);
  if (hit != UINT32_MAX) unbounded[side(hit, front)] = 1;
  std::vector<uint8_t> out(2 * tris.size(), 0);
  for (uint32_t s = 0; s < 2 * tris.size(); ++s)
    if (unbounded[s]) out[sides.find(s)] = 1;
  return out;
}

}  // namespace

CellRoles classify_cells(const Mesh& m, const std::vector<uint32_t>& tris) {
  CellRoles r;
  const size_t n = tris.size();
  r.role.assign(n, FaceRole::kBoundary);
  r.reverse.assign(n, 0);
  if (n == 0) return r;
  Sets sides(2 * n);
  join_around_edges(m, tris, sides);
  const std::vector<uint8_t> unbounded_root = join_by_rays(m, tris, sides);
  // The unbounded cell: every root a ray escaped from, joined.
  uint32_t outer = UINT32_MAX;
  for (uint32_t s = 0; s < 2 * n; ++s)
    if (unbounded_root[s]) {
      if (outer == UINT32_MAX)
        outer = sides.find(s);
      else
        sides.unite(outer, s), outer = sides.find(s);
    }
  // Cells and the triangles between them; breadth first from the unbounded cell.
  std::vector<uint32_t> cell(2 * n);
  std::vector<std::vector<uint32_t>> next(2 * n);
  for (uint32_t s = 0; s < 2 * n; ++s) cell[s] = sides.find(s);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t a = cell[2 * i], b = cell[2 * i + 1];
    if (a == b) continue;
    next[a].push_back(b);
    next[b].push_back(a);
  }
  std::vector<uint32_t> dist(2 * n, UINT32_MAX);
  for (uint32_t s = 0; s < 2 * n; ++s) r.cells += cell[s] == s;
  if (outer == UINT32_MAX) outer = cell[0];  // (no ray reached the part: cannot happen for a finite part)
  std::vector<uint32_t> queue = {outer};
  dist[outer] = 0;
  for (size_t q = 0; q < queue.size(); ++q)
    for (uint32_t c : next[queue[q]])
      if (dist[c] == UINT32_MAX) {
        dist[c] = dist[queue[q]] + 1;
        queue.push_back(c);
      }
  // A cell no path reaches (the part is edge-connected, so none) counts as empty.
  auto solid = [&](uint32_t c) { return dist[c] != UINT32_MAX && dist[c] % 2 == 1; };
  for (uint32_t i = 0; i < n; ++i) {
    const bool front = solid(cell[2 * i]), back = solid(cell[2 * i + 1]);
    if (front && back)
      r.role[i] = FaceRole::kInternal;
    else if (!front && !back)
      r.role[i] = FaceRole::kFin;
    else
      r.reverse[i] = front ? 1 : 0;  // the normal must point to the empty side
  }
  return r;
}

}  // namespace voxcd::detail
