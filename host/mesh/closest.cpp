// Closest points on a triangle mesh (host/object/detail/closest.h): the point-triangle query, a median-split tree
// over the triangles searched nearest child first, and pseudo-normals.
#include "voxcd/host/mesh/closest.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "voxcd/host/mesh/median_split.h"

namespace voxcd::detail {

namespace {

constexpr uint32_t kLeafSize = 4;

Eigen::Vector3d unit_or_zero(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return n > 0 && std::isfinite(n) ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

}  // namespace

Closest closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  Closest r;
  auto at = [&](const Eigen::Vector3d& q, Feature f, uint8_t k) {
    r.point = q;
    r.d2 = (p - q).squaredNorm();
    r.feature = f;
    r.index = k;
    return r;
  };
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return at(a, Feature::kVertex, 0);
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return at(b, Feature::kVertex, 1);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(a + ab * (d1 / (d1 - d3)), Feature::kEdge, 0);
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return at(c, Feature::kVertex, 2);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(a + ac * (d2 / (d2 - d6)), Feature::kEdge, 2);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return at(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), Feature::kEdge, 1);
  const double denom = 1 / (va + vb + vc);
  return at(a + ab * (vb * denom) + ac * (vc * denom), Feature::kFace, 0);
}

Closest snap_feature(Closest c, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& cc,
                     double eps) {
  if (c.feature == Feature::kVertex) return c;
  const Eigen::Vector3d* v[3] = {&a, &b, &cc};
  const double eps2 = eps * eps;
  for (uint8_t k = 0; k < 3; ++k)
    if ((c.point - *v[k]).squaredNorm() <= eps2) {
      c.feature = Feature::kVertex;
      c.index = k;
      return c;
    }
  if (c.feature == Feature::kEdge) return c;
  for (uint8_t k = 0; k < 3; ++k) {
    const Eigen::Vector3d& p = *v[k];
    const Eigen::Vector3d e = *v[(k + 1) % 3] - p;
    const double t = std::clamp((c.point - p).dot(e) / e.squaredNorm(), 0.0, 1.0);
    if ((c.point - (p + t * e)).squaredNorm() <= eps2) {
      c.feature = Feature::kEdge;
      c.index = k;
      return c;
    }
  }
  return c;
}

TriangleTree::TriangleTree(const std::vector<Eigen::Vector3d>& vertices,
                           const std::vector<std::array<uint32_t, 3>>& triangles) {
  tris_.reserve(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    tris_.push_back({vertices[triangles[t][0]], vertices[triangles[t][1]], vertices[triangles[t][2]], uint32_t(t)});
  if (!tris_.empty()) {
    nodes_.reserve(2 * (tris_.size() / kLeafSize + 1));
    build(0, uint32_t(tris_.size()));
  }
}

uint32_t TriangleTree::build(uint32_t first, uint32_t count) {
  const uint32_t id = uint32_t(nodes_.size());
  nodes_.emplace_back();
  Node n;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo, clo = lo, chi = hi;
  for (uint32_t i = first; i < first + count; ++i) {
    const Tri& t = tris_[i];
    lo = lo.cwiseMin(t.a).cwiseMin(t.b).cwiseMin(t.c);
    hi = hi.cwiseMax(t.a).cwiseMax(t.b).cwiseMax(t.c);
    const Eigen::Vector3d mid = t.a + t.b + t.c;
    clo = clo.cwiseMin(mid);
    chi = chi.cwiseMax(mid);
  }
  for (int k = 0; k < 3; ++k) n.lo[k] = lo[k], n.hi[k] = hi[k];
  if (count > kLeafSize) {
    // Ties in the key go by triangle index, so the tree depends on the mesh alone.
    const uint32_t half = median_split(tris_, first, count, chi - clo,
                                       [](const Tri& x, const Tri& y) { return x.index < y.index; });
    nodes_[id] = n;
    build(first, half);
    nodes_[id].right = build(first + half, count - half);
    return id;
  }
  n.first = first;
  n.count = count;
  nodes_[id] = n;
  return id;
}

Closest TriangleTree::closest(const Eigen::Vector3d& p, double max_d2) const {
  Closest best;
  best.d2 = max_d2;
  if (nodes_.empty()) return best;
  auto box_d2 = [&p](const Node& n) {
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double g = std::max({n.lo[k] - p[k], p[k] - n.hi[k], 0.0});
      s += g * g;
    }
    return s;
  };
  uint32_t stack[128];
  double stack_d2[128];
  int top = 0;
  stack[top] = 0;
  stack_d2[top++] = box_d2(nodes_[0]);
  while (top > 0) {
    --top;
    if (stack_d2[top] > best.d2) continue;
    const Node& n = nodes_[stack[top]];
    if (n.count) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Tri& t = tris_[i];
        Closest c = closest_on_triangle(p, t.a, t.b, t.c);
        if (c.d2 < best.d2 || (c.d2 == best.d2 && t.index < best.triangle)) {
          c.triangle = t.index;
          best = c;
        }
      }
      continue;
    }
    const uint32_t l = stack[top] + 1, r = n.right;
    const double dl = box_d2(nodes_[l]), dr = box_d2(nodes_[r]);
    // The nearer child is searched first (pushed last).
    if (dl <= dr) {
      if (dr <= best.d2) stack[top] = r, stack_d2[top++] = dr;
      if (dl <= best.d2) stack[top] = l, stack_d2[top++] = dl;
    } else {
      if (dl <= best.d2) stack[top] = l, stack_d2[top++] = dl;
      if (dr <= best.d2) stack[top] = r, stack_d2[top++] = dr;
    }
  }
  return best;
}

uint32_t TriangleTree::first_hit(const Eigen::Vector3d& o, const Eigen::Vector3d& d, uint32_t skip, double min_l,
                                 double* l_out, bool* front_out) const {
  uint32_t best = UINT32_MAX;
  double best_l = HUGE_VAL;
  bool best_front = false;
  if (nodes_.empty()) return best;
  const Eigen::Vector3d inv(1 / d[0], 1 / d[1], 1 / d[2]);
  // The ray's parameter interval inside a node's box (slabs); empty when the box is missed or beyond best_l.
  auto enter = [&](const Node& n) {
    double t0 = min_l, t1 = best_l;
    for (int k = 0; k < 3; ++k) {
      double a = (n.lo[k] - o[k]) * inv[k], b = (n.hi[k] - o[k]) * inv[k];
      if (a > b) std::swap(a, b);
      if (!(a <= t1 && b >= t0)) return HUGE_VAL;  // NaN (a ray in the box's plane) enters too
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0;
  };
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const uint32_t id = stack[--top];
    const Node& n = nodes_[id];
    if (enter(n) == HUGE_VAL) continue;
    if (n.count) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Tri& t = tris_[i];
        if (t.index == skip) continue;
        // Moller-Trumbore.
        const Eigen::Vector3d e1 = t.b - t.a, e2 = t.c - t.a, h = d.cross(e2);
        const double det = e1.dot(h);
        if (det == 0) continue;
        const Eigen::Vector3d s = o - t.a;
        const double u = s.dot(h) / det;
        if (u < 0 || u > 1) continue;
        const Eigen::Vector3d q = s.cross(e1);
        const double v = d.dot(q) / det;
        if (v < 0 || u + v > 1) continue;
        const double l = e2.dot(q) / det;
        if (l > min_l && (l < best_l || (l == best_l && t.index < best))) {
          best = t.index;
          best_l = l;
          best_front = det > 0;  // det = -d . (e1 x e2): positive when the ray comes from the normal's side
        }
      }
      continue;
    }
    stack[top++] = n.right;
    stack[top++] = id + 1;  // the left child follows its parent
  }
  if (l_out) *l_out = best_l;
  if (front_out) *front_out = best_front;
  return best;
}

PseudoNormals::PseudoNormals(const std::vector<Eigen::Vector3d>& vertices,
                             const std::vector<std::array<uint32_t, 3>>& triangles)
    : triangles_(triangles), face_(triangles.size()), edge_(3 * triangles.size()),
      vertex_(vertices.size(), Eigen::Vector3d::Zero()) {
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Vector3d& a = vertices[triangles[t][0]];
    const Eigen::Vector3d& b = vertices[triangles[t][1]];
    const Eigen::Vector3d& c = vertices[triangles[t][2]];
    face_[t] = unit_or_zero((b - a).cross(c - a));
    const Eigen::Vector3d* v[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = *v[(k + 1) % 3] - *v[k], e2 = *v[(k + 2) % 3] - *v[k];
      const double n1 = e1.norm(), n2 = e2.norm();
      if (!(n1 > 0 && n2 > 0)) continue;
      const double angle = std::acos(std::clamp(e1.dot(e2) / (n1 * n2), -1.0, 1.0));
      vertex_[triangles[t][k]] += angle * face_[t];
    }
  }
  for (auto& n : vertex_) n = unit_or_zero(n);
  // Edges: every use of an undirected edge, sorted, so that the uses of one edge are adjacent.
  struct Use {
    uint32_t lo, hi, slot;
  };
  std::vector<Use> uses;
  uses.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), uint32_t(3 * t + k)});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.slot < y.slot;
  });
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) sum += face_[uses[j++].slot / 3];
    const Eigen::Vector3d n = unit_or_zero(sum);
    for (size_t k = i; k < j; ++k) edge_[uses[k].slot] = n;
    i = j;
  }
}

Eigen::Vector3d PseudoNormals::at(const Closest& c) const {
  Eigen::Vector3d n = face_[c.triangle];
  if (c.feature == Feature::kEdge) n = edge_[3 * size_t(c.triangle) + c.index];
  if (c.feature == Feature::kVertex) n = vertex_[triangles_[c.triangle][c.index]];
  // Opposite faces meeting at a feature (a sheet folded onto itself) cancel: fall back to the face's normal.
  return n.squaredNorm() > 0 ? n : face_[c.triangle];
}

}  // namespace voxcd::detail
