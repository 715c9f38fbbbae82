// Internal to host/mesh (mesh.cpp's validate, repair.cpp): every use of an undirected edge by a triangle.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::detail {

// One use of an undirected edge by a triangle.
struct EdgeUse {
  uint64_t key;  // lo << 32 | hi
  uint32_t tri;
  bool forward;  // lo -> hi in the triangle's winding
};

// Every edge use of m, sorted by edge and then triangle.
inline std::vector<EdgeUse> edge_uses(const Mesh& m) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * m.size());
  for (size_t t = 0; t < m.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(t), a < b});
    }
  std::sort(uses.begin(), uses.end(),
            [](const EdgeUse& x, const EdgeUse& y) { return x.key != y.key ? x.key < y.key : x.tri < y.tri; });
  return uses;
}

}  // namespace voxcd::detail
