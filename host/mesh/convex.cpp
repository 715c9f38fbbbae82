#include "voxcd/host/mesh/convex.h"

#include <numeric>
#include <unordered_map>
#include <vector>

namespace voxcd {

namespace {

uint64_t edge_key(uint32_t a, uint32_t b) { return (uint64_t{a} << 32) | b; }

// Union-find root with path halving.
uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

bool is_convex(const Mesh& mesh) {
  const size_t n = mesh.triangles.size();
  if (n < 4) return false;
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  const double tol = 1e-9 * (hi - lo).norm();
  // Directed edge -> its triangle. A closed consistently oriented surface has each directed edge once and its
  // reverse once.
  std::unordered_map<uint64_t, uint32_t> directed;
  directed.reserve(3 * n);
  for (uint32_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto& tri = mesh.triangles[t];
      if (!directed.emplace(edge_key(tri[k], tri[(k + 1) % 3]), t).second) return false;
    }
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (uint32_t t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d a = mesh.vertices[tri[0]];
    const Eigen::Vector3d normal = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).normalized();
    for (int k = 0; k < 3; ++k) {
      const auto across = directed.find(edge_key(tri[(k + 1) % 3], tri[k]));
      if (across == directed.end()) return false;  // an open edge
      const uint32_t u = across->second;
      parent[root(parent, t)] = root(parent, u);
      const auto& other = mesh.triangles[u];
      for (uint32_t v : other)
        if (normal.dot(mesh.vertices[v] - a) > tol) return false;  // a reflex edge
    }
  }
  const uint32_t first = root(parent, 0);
  for (uint32_t t = 1; t < n; ++t)
    if (root(parent, t) != first) return false;
  return true;
}

}  // namespace voxcd
