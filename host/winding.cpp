// The caps' part of the generalized winding number (host/winding.h): boundary loops, their cones, and a tree that
// evaluates and bounds the cones' solid angles.
#include "host/winding.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace voxcd::detail {

namespace {

constexpr double kFourPi = 4 * M_PI;
// A node is far for value() beyond kFar radii (dipole), and for certify() beyond kFarBlock times radius + block.
constexpr double kFar = 3.0;
constexpr double kFarBlock = 2.0;
constexpr uint32_t kLeaf = 8;

Eigen::Vector3d to_voxels(const GridPoint& p, int frac) {
  return Eigen::Vector3d(std::ldexp(double(p[0]), -frac), std::ldexp(double(p[1]), -frac),
                         std::ldexp(double(p[2]), -frac));
}

}  // namespace

std::vector<ChainTriangle> boundary_caps(const std::vector<GridPoint>& q,
                                         const std::vector<std::array<uint32_t, 3>>& tris, int frac_bits) {
  (void)frac_bits;
  // Net uses of each undirected edge: +1 for lo -> hi, -1 for hi -> lo.
  std::vector<std::pair<uint64_t, int>> uses;
  uses.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), a < b ? 1 : -1});
    }
  std::sort(uses.begin(), uses.end());
  // The boundary as directed edges with multiplicity, grouped by their start vertex.
  std::map<uint32_t, std::vector<uint32_t>> out;  // ordered: the walks below are deterministic
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    int net = 0;
    while (j < uses.size() && uses[j].first == uses[i].first) net += uses[j++].second;
    const uint32_t lo = uint32_t(uses[i].first >> 32), hi = uint32_t(uses[i].first);
    for (int k = 0; k < std::abs(net); ++k) {
      if (net > 0)
        out[lo].push_back(hi);
      else
        out[hi].push_back(lo);
    }
    i = j;
  }
  std::vector<ChainTriangle> caps;
  // Every vertex has as many boundary edges in as out, so a walk from any vertex returns to it.
  for (auto it = out.begin(); it != out.end(); ++it) {
    while (!it->second.empty()) {
      const uint32_t start = it->first;
      std::vector<uint32_t> loop = {start};
      uint32_t v = start;
      do {
        auto& o = out[v];
        const uint32_t w = o.back();
        o.pop_back();
        v = w;
        loop.push_back(v);
      } while (v != start && !out[v].empty());
      // (A walk ends at its start; the second test only guards a malformed boundary.)
      __int128 s[3] = {0, 0, 0};
      for (size_t k = 0; k + 1 < loop.size(); ++k)
        for (int a = 0; a < 3; ++a) s[a] += q[loop[k]][a];
      const int64_t n = int64_t(loop.size() - 1);
      GridPoint apex{};
      for (int a = 0; a < 3; ++a) {
        const __int128 h = s[a] >= 0 ? (s[a] + n / 2) / n : -((-s[a] + n / 2) / n);
        apex[a] = int64_t(h);
      }
      for (size_t k = 0; k + 1 < loop.size(); ++k) caps.push_back({apex, q[loop[k]], q[loop[k + 1]], 1});
    }
  }
  return caps;
}

double triangle_winding(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double det = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2 * std::atan2(det, den) / kFourPi;
}

CapField::CapField(const std::vector<ChainTriangle>& caps, int frac_bits) {
  tris_.reserve(caps.size());
  for (const auto& c : caps)
    tris_.push_back({to_voxels(c.a, frac_bits), to_voxels(c.b, frac_bits), to_voxels(c.c, frac_bits), double(c.weight)});
  if (!tris_.empty()) {
    nodes_.reserve(2 * tris_.size() / kLeaf + 2);
    build(0, uint32_t(tris_.size()));
  }
}

uint32_t CapField::build(uint32_t first, uint32_t count) {
  const uint32_t id = uint32_t(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo, clo = lo, chi = hi;
  Node n;
  n.dipole.setZero();
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (uint32_t i = first; i < first + count; ++i) {
    const Tri& t = tris_[i];
    lo = lo.cwiseMin(t.a).cwiseMin(t.b).cwiseMin(t.c);
    hi = hi.cwiseMax(t.a).cwiseMax(t.b).cwiseMax(t.c);
    const Eigen::Vector3d mid = (t.a + t.b + t.c) / 3;
    clo = clo.cwiseMin(mid);
    chi = chi.cwiseMax(mid);
    const Eigen::Vector3d va = (t.b - t.a).cross(t.c - t.a) / 2;
    const double area = va.norm() * std::abs(t.weight);
    n.abs_area += area;
    n.dipole += t.weight * va;
    weighted += area * mid;
  }
  n.centre = (lo + hi) / 2;
  n.radius = (hi - lo).norm() / 2;
  n.centroid = n.abs_area > 0 ? Eigen::Vector3d(weighted / n.abs_area) : n.centre;
  // The dipole is taken about the centroid, which must lie within the node's sphere for the far-field bound.
  if ((n.centroid - n.centre).norm() > n.radius) n.centroid = n.centre;
  if (count <= kLeaf) {
    n.first = first;
    n.count = count;
    nodes_[id] = n;
    return id;
  }
  int axis = 0;
  const Eigen::Vector3d ext = chi - clo;
  if (ext[1] > ext[axis]) axis = 1;
  if (ext[2] > ext[axis]) axis = 2;
  const uint32_t half = count / 2;
  std::nth_element(tris_.begin() + first, tris_.begin() + first + half, tris_.begin() + first + count,
                   [axis](const Tri& x, const Tri& y) {
                     return x.a[axis] + x.b[axis] + x.c[axis] < y.a[axis] + y.b[axis] + y.c[axis];
                   });
  n.count = 0;
  nodes_[id] = n;
  const uint32_t l = build(first, half);
  const uint32_t r = build(first + half, count - half);
  nodes_[id].left = l;
  nodes_[id].right = r;
  return id;
}

double CapField::value(const Eigen::Vector3d& p) const {
  if (nodes_.empty()) return 0;
  double w = 0;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top) {
    const Node& n = nodes_[stack[--top]];
    const Eigen::Vector3d d = n.centroid - p;
    const double dist = (n.centre - p).norm();
    if (dist > kFar * n.radius && n.radius > 0) {
      const double r = d.norm();
      w += n.dipole.dot(d) / (kFourPi * r * r * r);
    } else if (n.count) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Tri& t = tris_[i];
        w += t.weight * triangle_winding(t.a - p, t.b - p, t.c - p);
      }
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return w;
}

void CapField::uncertain_voxels(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, double limit,
                                const std::function<void(uint32_t, uint32_t, uint32_t)>& need) const {
  if (nodes_.empty()) return;
  certify(lo, hi, {0}, 0, limit, need);
}

void CapField::certify(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi,
                       std::vector<uint32_t> nodes, double bound, double limit,
                       const std::function<void(uint32_t, uint32_t, uint32_t)>& need) const {
  // The block's voxel centres lie in a ball of radius rho around c.
  Eigen::Vector3d c, half;
  for (int a = 0; a < 3; ++a) {
    c[a] = (double(lo[a]) + double(hi[a])) / 2;
    half[a] = (double(hi[a]) - double(lo[a]) - 1) / 2;
  }
  const double rho = half.norm();
  std::vector<uint32_t> open;
  while (!nodes.empty() && bound < limit) {
    const uint32_t id = nodes.back();
    nodes.pop_back();
    const Node& n = nodes_[id];
    const double dist = (n.centre - c).norm();
    const double gap = dist - rho - n.radius;
    if (gap > 0 && dist > kFarBlock * (rho + n.radius)) {
      // |solid angle of a triangle| <= its area / (distance to it)^2.
      bound += n.abs_area / (kFourPi * gap * gap);
    } else if (n.count) {
      open.push_back(id);
    } else {
      nodes.push_back(n.left);
      nodes.push_back(n.right);
    }
  }
  if (bound < limit && open.empty()) return;
  const bool single = hi[0] - lo[0] == 1 && hi[1] - lo[1] == 1 && hi[2] - lo[2] == 1;
  if (single || bound >= limit) {
    for (uint32_t z = lo[2]; z < hi[2]; ++z)
      for (uint32_t y = lo[1]; y < hi[1]; ++y)
        for (uint32_t x = lo[0]; x < hi[0]; ++x) need(x, y, z);
    return;
  }
  // Open leaves stay open for the children, with the bound gathered so far.
  for (uint32_t id : nodes) open.push_back(id);
  for (int oz = 0; oz < 2; ++oz)
    for (int oy = 0; oy < 2; ++oy)
      for (int ox = 0; ox < 2; ++ox) {
        std::array<uint32_t, 3> l = lo, h = hi;
        const int o[3] = {ox, oy, oz};
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
          const uint32_t mid = lo[a] + (hi[a] - lo[a] + 1) / 2;
          if (hi[a] - lo[a] == 1) {
            if (o[a]) empty = true;
            continue;
          }
          if (o[a])
            l[a] = mid;
          else
            h[a] = mid;
        }
        if (!empty) certify(l, h, open, bound, limit, need);
      }
}

}  // namespace voxcd::detail
