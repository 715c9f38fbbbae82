// classify_cells() (host/object/detail/cells.h): sides joined around edges by angle; the unbounded cell found by one
// ray; cells labelled by their distance from it.
#include "voxcd/host/mesh/detail/cells.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "voxcd/host/mesh/closest.h"
#include "voxcd/host/mesh/detail/union_find.h"

namespace voxcd::detail {

namespace {

// Triangles around an edge whose angles differ by at most this (radians) lie on one another.
constexpr double kSameAngle = 1e-9;
constexpr double kPi = 3.14159265358979323846;


// Side s of local triangle i: 2i is the side its normal points to, 2i + 1 the other.
inline uint32_t side(uint32_t i, bool front) { return 2 * i + (front ? 0 : 1); }

struct Use {
  uint64_t key;  // lo << 32 | hi
  uint32_t tri;  // local index
};

struct Around {
  double angle;
  uint32_t tri;
  bool front_ahead;  // the side facing increasing angle is the normal's
};

// The uses [i, j) of one edge, sorted by the angle of their triangles around it.
void around_edge(const Mesh& m, const std::vector<uint32_t>& tris, const std::vector<Use>& uses, size_t i, size_t j,
                 std::vector<Around>& around) {
  const uint32_t va = uint32_t(uses[i].key >> 32), vb = uint32_t(uses[i].key);
  const Eigen::Vector3d& a = m.vertices[va];
  const Eigen::Vector3d e = (m.vertices[vb] - a).normalized();
  const Eigen::Vector3d u = e.unitOrthogonal(), w = e.cross(u);
  around.clear();
  for (size_t k = i; k < j; ++k) {
    const auto& t = m.triangles[tris[uses[k].tri]];
    Eigen::Vector3d c = m.vertices[t[0]];  // the corner off the edge
    for (uint32_t v : t)
      if (v != va && v != vb) c = m.vertices[v];
    const Eigen::Vector3d r = (c - a) - (c - a).dot(e) * e;
    const Eigen::Vector3d n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    around.push_back({std::atan2(r.dot(w), r.dot(u)), uses[k].tri, n.dot(e.cross(r)) > 0});
  }
  std::sort(around.begin(), around.end(),
            [](const Around& x, const Around& y) { return x.angle != y.angle ? x.angle < y.angle : x.tri < y.tri; });
}

// Joins, around every edge used by two triangles or more, the two sides facing each wedge between neighbours in
// angular order. Triangles at the same angle (within kSameAngle: coplanar faces on one side of the edge, as two
// touching parts give them) form a stack: the wedges on either side are bounded by its first and its last
// triangle, and the sides facing each other inside the stack bound no space and are joined to nothing here.
void join_around_edges(const Mesh& m, const std::vector<uint32_t>& tris, UnionFind& sides) {
  std::vector<Use> uses;
  uses.reserve(3 * tris.size());
  for (uint32_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[tris[i]][k], b = m.triangles[tris[i]][(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), i});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) { return x.key != y.key ? x.key < y.key : x.tri < y.tri; });
  std::vector<Around> around;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i >= 2) {
      around_edge(m, tris, uses, i, j, around);
      // Stacks: runs of equal angles (the last run may continue the first across the angle's wrap).
      std::vector<std::pair<size_t, size_t>> stacks;  // [first, last] in `around`
      for (size_t k = 0; k < around.size();) {
        size_t e = k;
        while (e + 1 < around.size() && around[e + 1].angle - around[e].angle <= kSameAngle) ++e;
        stacks.push_back({k, e});
        k = e + 1;
      }
      if (stacks.size() > 1 &&
          around.front().angle + 2 * kPi - around.back().angle <= kSameAngle) {  // the wrap joins two runs
        stacks.front().first = stacks.back().first;
        stacks.pop_back();
      }
      for (size_t k = 0; k < stacks.size(); ++k) {
        const Around& p = around[stacks[k].second];                        // the last of this stack
        const Around& q = around[stacks[(k + 1) % stacks.size()].first];   // the first of the next
        sides.unite(side(p.tri, p.front_ahead), side(q.tri, !q.front_ahead));
      }
    }
    i = j;
  }
}

// The side of the part that a ray from beyond its box meets first, towards the centroid of the triangle with the
// largest centroid x: it faces the unbounded cell.
uint32_t outer_side(const Mesh& m, const std::vector<uint32_t>& tris) {
  std::vector<std::array<uint32_t, 3>> local(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) local[i] = m.triangles[tris[i]];
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  uint32_t far = 0;
  double far_x = -HUGE_VAL;
  for (uint32_t i = 0; i < local.size(); ++i) {
    for (uint32_t v : local[i]) lo = lo.cwiseMin(m.vertices[v]), hi = hi.cwiseMax(m.vertices[v]);
    const double x = m.vertices[local[i][0]].x() + m.vertices[local[i][1]].x() + m.vertices[local[i][2]].x();
    if (x > far_x) far_x = x, far = i;
  }
  const Eigen::Vector3d target =
      (m.vertices[local[far][0]] + m.vertices[local[far][1]] + m.vertices[local[far][2]]) / 3;
  // A direction off the axes and off simple ratios, so that the ray seldom meets an edge.
  const Eigen::Vector3d d = Eigen::Vector3d(-1, 0.0071, -0.0137).normalized();
  const Eigen::Vector3d o = target - d * ((hi.x() - target.x() + (hi - lo).norm() + 1) / -d.x());
  const TriangleTree tree(m.vertices, local);
  bool front = false;
  const uint32_t hit = tree.first_hit(o, d, UINT32_MAX, 0, nullptr, &front);
  // (The ray aims at the inside of a triangle of the part, so it meets one.)
  return hit == UINT32_MAX ? side(far, true) : side(hit, front);
}

}  // namespace

CellRoles classify_cells(const Mesh& m, const std::vector<uint32_t>& tris) {
  CellRoles r;
  const size_t n = tris.size();
  r.role.assign(n, FaceRole::kBoundary);
  r.reverse.assign(n, 0);
  if (n == 0) return r;
  UnionFind sides(2 * n);
  join_around_edges(m, tris, sides);
  const uint32_t outer = sides.find(outer_side(m, tris));
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
