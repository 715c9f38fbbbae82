#include "voxcd/host/view/repair_places.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <set>

namespace voxcd::view {

namespace {

// A point's exact bit pattern, so that equal coordinates compare equal across the two meshes.
using Key = std::array<uint64_t, 3>;
Key key_of(const Eigen::Vector3d& p) {
  Key k;
  for (int i = 0; i < 3; ++i) std::memcpy(&k[size_t(i)], &p[i], 8);
  return k;
}

// A triangle by its corners' keys: sorted (which three points) and whether its order is an even rotation of it.
struct TriKey {
  std::array<Key, 3> sorted;
  bool even;
};
TriKey tri_key(const Mesh& m, size_t t) {
  std::array<Key, 3> c = {key_of(m.corner(t, 0)), key_of(m.corner(t, 1)), key_of(m.corner(t, 2))};
  TriKey k{c, true};
  std::sort(k.sorted.begin(), k.sorted.end());
  // The orientation is the parity of the permutation from c to sorted.
  int inversions = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) inversions += c[size_t(i)] > c[size_t(j)];
  k.even = inversions % 2 == 0;
  return k;
}

Eigen::Vector3d finite_centroid(const Mesh& m, size_t t) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int k = 0; k < 3; ++k)
    if (m.corner(t, k).allFinite()) sum += m.corner(t, k), ++n;
  return n ? Eigen::Vector3d(sum / n) : sum;
}

bool zero_area(const Mesh& m, size_t t) {
  const auto& tri = m.triangles[t];
  if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) return true;
  return (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).squaredNorm() == 0;
}

void mark_edges(const Mesh& r, RepairPlaces& p) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const auto& t : r.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [e, n] : uses) {
    if (n == 1) p.open_edges.push_back({r.vertices[e.first], r.vertices[e.second]});
    if (n > 2) p.nonmanifold_edges.push_back({r.vertices[e.first], r.vertices[e.second]});
  }
}

}  // namespace

RepairPlaces repair_places(const Mesh& input, const Mesh& repaired, const MeshReport& report) {
  RepairPlaces p;
  std::set<Key> kept;
  for (const auto& v : repaired.vertices) kept.insert(key_of(v));
  std::map<std::array<Key, 3>, bool> after;  // the repaired triangles by their corners, with their orientation
  for (size_t t = 0; t < repaired.size(); ++t) {
    const TriKey k = tri_key(repaired, t);
    after[k.sorted] = k.even;
  }
  std::set<std::array<Key, 3>> seen;
  std::vector<char> moved(input.vertices.size(), 0);
  for (size_t t = 0; t < input.size(); ++t) {
    const auto& tri = input.triangles[t];
    if (std::any_of(tri.begin(), tri.end(), [&](uint32_t v) { return v >= input.vertices.size(); })) continue;
    const bool finite = input.corner(t, 0).allFinite() && input.corner(t, 1).allFinite() && input.corner(t, 2).allFinite();
    if (!finite || zero_area(input, t)) {
      p.dropped.push_back(finite_centroid(input, t));
      continue;
    }
    for (uint32_t v : tri)
      if (!kept.count(key_of(input.vertices[v]))) moved[v] = 1;
    const TriKey k = tri_key(input, t);
    if (!seen.insert(k.sorted).second) {
      p.dropped.push_back(finite_centroid(input, t));  // an exact duplicate
      continue;
    }
    const auto it = after.find(k.sorted);
    if (it != after.end() && it->second != k.even && !report.flipped) p.reoriented.push_back(finite_centroid(input, t));
  }
  for (size_t v = 0; v < moved.size(); ++v)
    if (moved[v]) p.moved.push_back(input.vertices[v]);
  mark_edges(repaired, p);
  for (size_t t = 0; t < repaired.size(); ++t)
    if (repaired.is_sheet(t)) p.sheet_triangles.push_back(uint32_t(t));
  return p;
}

}  // namespace voxcd::view
