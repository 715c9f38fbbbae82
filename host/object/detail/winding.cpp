// The caps' part of the generalized winding number (host/object/detail/winding.h): boundary loops, their cones, and a tree that
// evaluates and bounds the cones' solid angles.
#include "voxcd/host/object/detail/winding.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "voxcd/host/mesh/median_split.h"

namespace voxcd::detail {

namespace {

constexpr double kFourPi = 4 * M_PI;
// A node is far for value() beyond kFar radii (dipole), and for certify() beyond kFarBlock times radius + block.
constexpr double kFar = 3.0;
constexpr double kFarBlock = 2.0;
constexpr uint32_t kLeaf = 1;

Eigen::Vector3d to_voxels(const GridPoint& p, int frac) {
  return Eigen::Vector3d(std::ldexp(double(p[0]), -frac), std::ldexp(double(p[1]), -frac),
                         std::ldexp(double(p[2]), -frac));
}

}  // namespace

namespace {

// splitmix64's finaliser with a fixed key.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull ^ 0x5bd1e9955bd1e995ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Sorts keys below 2^bits (LSD radix, digits of at most 11 bits, few enough buckets to stay in cache).
void radix_sort(std::vector<uint64_t>& keys, int bits) {
  std::vector<uint64_t> tmp(keys.size());
  const int passes = (bits + 10) / 11;
  const int digit = (bits + passes - 1) / passes;
  const uint64_t mask = (uint64_t(1) << digit) - 1;
  std::vector<size_t> count(size_t(mask) + 2);
  for (int shift = 0; shift < bits; shift += digit) {
    std::fill(count.begin(), count.end(), 0);
    for (uint64_t k : keys) ++count[((k >> shift) & mask) + 1];
    for (size_t i = 0; i <= mask; ++i) count[i + 1] += count[i];
    for (uint64_t k : keys) tmp[count[(k >> shift) & mask]++] = k;
    keys.swap(tmp);
  }
}

}  // namespace

namespace {

// Each use of an undirected edge as a key: lo, hi, and whether it runs lo -> hi (bit 0 clear) or back.
struct EdgeKeys {
  int vbits = 1;
  explicit EdgeKeys(size_t vertices) {
    while (vbits < 32 && (uint64_t(1) << vbits) < vertices) ++vbits;
  }
  uint64_t operator()(uint32_t a, uint32_t b) const {
    return (uint64_t(std::min(a, b)) << vbits | std::max(a, b)) << 1 | (a < b ? 0 : 1);
  }
};

// The boundary of a chain of triangles: directed edges with multiplicity (uses that do not cancel), sorted.
std::vector<std::pair<uint32_t, uint32_t>> boundary_edges(const std::vector<std::array<uint32_t, 3>>& tris,
                                                          const EdgeKeys& key_of) {
  std::vector<uint64_t> keys;
  keys.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) keys.push_back(key_of(t[k], t[(k + 1) % 3]));
  const int vbits = key_of.vbits;
  radix_sort(keys, 2 * vbits + 1);
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  const uint64_t vmask = (uint64_t(1) << vbits) - 1;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i;
    int net = 0;
    while (j < keys.size() && keys[j] >> 1 == keys[i] >> 1) net += (keys[j++] & 1) ? -1 : 1;
    const uint32_t lo = uint32_t(keys[i] >> (vbits + 1)), hi = uint32_t((keys[i] >> 1) & vmask);
    for (int k = 0; k < std::abs(net); ++k) edges.push_back(net > 0 ? std::make_pair(lo, hi) : std::make_pair(hi, lo));
    i = j;
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// A cone over one closed loop of boundary vertices: its apex the loop's mean (rounded to the grid).
void add_cone(const std::vector<GridPoint>& q, const std::vector<uint32_t>& loop, std::vector<ChainTriangle>& caps) {
  __int128 sum[3] = {0, 0, 0};
  for (size_t k = 0; k + 1 < loop.size(); ++k)
    for (int a = 0; a < 3; ++a) sum[a] += q[loop[k]][a];
  const int64_t n = int64_t(std::max<size_t>(loop.size() - 1, 1));
  GridPoint apex{};
  for (int a = 0; a < 3; ++a) {
    const __int128 h = sum[a] >= 0 ? (sum[a] + n / 2) / n : -((-sum[a] + n / 2) / n);
    apex[a] = int64_t(h);
  }
  for (size_t k = 0; k + 1 < loop.size(); ++k) caps.push_back({apex, q[loop[k]], q[loop[k + 1]], 1});
}

// The boundary's closed loops, each capped by add_cone.
std::vector<ChainTriangle> cap_loops(const std::vector<GridPoint>& q,
                                     const std::vector<std::pair<uint32_t, uint32_t>>& edges) {
  std::vector<ChainTriangle> caps;
  // Outgoing boundary edges per vertex (CSR over the vertices that have any).
  std::vector<uint32_t> verts;
  for (const auto& e : edges)
    if (verts.empty() || verts.back() != e.first) verts.push_back(e.first);
  std::vector<size_t> next(verts.size()), end(verts.size());
  for (size_t i = 0, v = 0; i < edges.size(); ++v) {
    next[v] = i;
    while (i < edges.size() && edges[i].first == verts[v]) ++i;
    end[v] = i;
  }
  auto slot = [&](uint32_t v) { return size_t(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin()); };
  // Every vertex has as many boundary edges in as out, so a walk from any vertex returns to it.
  for (size_t sv = 0; sv < verts.size(); ++sv) {
    while (next[sv] < end[sv]) {
      const uint32_t start = verts[sv];
      std::vector<uint32_t> loop = {start};
      uint32_t v = start;
      do {
        const size_t k = slot(v);
        if (k == verts.size() || verts[k] != v || next[k] == end[k]) break;  // only for a malformed boundary
        v = edges[next[k]++].second;
        loop.push_back(v);
      } while (v != start);
      add_cone(q, loop, caps);
    }
  }
  return caps;
}

}  // namespace

std::vector<ChainTriangle> boundary_caps(const std::vector<GridPoint>& q,
                                         const std::vector<std::array<uint32_t, 3>>& tris, int frac_bits) {
  (void)frac_bits;
  const EdgeKeys key_of(q.size());
  // A closed chain first, in linear time: the sum over every use of a keyed hash of its directed edge minus that
  // of the reverse is zero when every edge's uses cancel, and nonzero otherwise but with probability 2^-64.
  uint64_t balance = 0;
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      balance += mix(key_of(a, b)) - mix(key_of(b, a));
    }
  if (balance == 0) return {};
  const std::vector<std::pair<uint32_t, uint32_t>> edges = boundary_edges(tris, key_of);
  if (edges.empty()) return {};
  return cap_loops(q, edges);
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
  const uint32_t half = median_split(tris_, first, count, chi - clo, [](const Tri&, const Tri&) { return false; });
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
                                const NeedFn& need) const {
  if (nodes_.empty()) return;
  // Each level of the recursion works in its own list, kept by the thread from block to block: no allocation per
  // block once the lists have grown (a block recurses down to single voxels, hundreds of levels' lists each).
  thread_local std::vector<std::vector<uint32_t>> lists;
  if (lists.empty()) lists.resize(1);
  lists[0].assign(1, 0);
  certify(lo, hi, 0, lists, 0, limit, need);
}

void CapField::certify(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, size_t depth,
                       std::vector<std::vector<uint32_t>>& lists, double bound, double limit,
                       const NeedFn& need) const {
  // lists[depth]: the nodes to visit here (as the parent left them); lists[depth + 1]: the children's.
  if (lists.size() < depth + 2) lists.resize(depth + 2);
  std::vector<uint32_t>& nodes = lists[depth];
  std::vector<uint32_t>& open = lists[depth + 1];
  open.clear();
  // The block's voxel centres lie in a ball of radius rho around c.
  Eigen::Vector3d c, half;
  for (int a = 0; a < 3; ++a) {
    c[a] = (double(lo[a]) + double(hi[a])) / 2;
    half[a] = (double(hi[a]) - double(lo[a]) - 1) / 2;
  }
  const double rho = half.norm();
  const bool single = rho == 0;
  double near = 0;  // a single voxel: the exact winding number of the open leaves
  while (!nodes.empty() && bound < limit) {
    const uint32_t id = nodes.back();
    nodes.pop_back();
    const Node& n = nodes_[id];
    const double dist = (n.centre - c).norm();
    const double gap = dist - rho - n.radius;
    // |solid angle of a triangle| <= its area / (distance to it)^2.
    const double b = gap > 0 ? n.abs_area / (kFourPi * gap * gap) : HUGE_VAL;
    if (gap > 0 && (dist > kFarBlock * (rho + n.radius) || b < limit / 64)) {
      bound += b;
    } else if (n.count) {
      if (single) {
        for (uint32_t i = n.first; i < n.first + n.count; ++i) {
          const Tri& t = tris_[i];
          near += t.weight * triangle_winding(t.a - c, t.b - c, t.c - c);
        }
      } else {
        open.push_back(id);
      }
    } else {
      nodes.push_back(n.left);
      nodes.push_back(n.right);
    }
  }
  if (bound + std::abs(near) < limit && open.empty()) return;
  if (single) {
    need(lo[0], lo[1], lo[2], bound < limit ? near : NAN, bound);
    return;
  }
  if (bound >= limit) {
    for (uint32_t z = lo[2]; z < hi[2]; ++z)
      for (uint32_t y = lo[1]; y < hi[1]; ++y)
        for (uint32_t x = lo[0]; x < hi[0]; ++x) need(x, y, z, NAN, bound);
    return;
  }
  // Open leaves stay open for the children, with the bound gathered so far.
  for (uint32_t id : nodes) open.push_back(id);
  certify_children(lo, hi, depth, lists, bound, limit, need);
}

void CapField::certify_children(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, size_t depth,
                                std::vector<std::vector<uint32_t>>& lists, double bound, double limit,
                                const NeedFn& need) const {
  // Each child of the block starts from a copy of lists[depth + 1].
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
        if (empty) continue;
        if (lists.size() < depth + 3) lists.resize(depth + 3);
        lists[depth + 2].assign(lists[depth + 1].begin(), lists[depth + 1].end());
        certify(l, h, depth + 2, lists, bound, limit, need);
      }
}

}  // namespace voxcd::detail
