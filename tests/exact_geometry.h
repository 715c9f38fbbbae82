// Exact geometry by brute force, for tests and benchmarks that check results against the meshes themselves:
// point in a closed mesh by ray parity, and the distance from a point to a mesh's surface (Euclidean and max norm).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/sizing/sweep/detail/exact_distance.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::test {

// The brute-force functions live in the library (the sweep measures contacts with them); the tests use them here.
inline bool inside_reference(const Mesh& m, const Eigen::Vector3d& p) { return detail::inside_mesh(m, p); }
using detail::mesh_distance;
using detail::point_triangle_distance;

// The distance from p to the mesh's surface in the max norm of the mesh's own axes: the half side of the smallest
// axis-aligned cube centred on p that meets a triangle. Between d / sqrt(3) and d for the Euclidean distance d, so
// only triangles within sqrt(3) d can attain it; bisection on the exact cube-triangle test over those.
inline double mesh_distance_max_norm(const Mesh& m, const Eigen::Vector3d& p) {
  const double d = mesh_distance(m, p);
  std::vector<size_t> near;
  for (size_t t = 0; t < m.size(); ++t)
    if (point_triangle_distance(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)) <= std::sqrt(3.0) * d * (1 + 1e-12))
      near.push_back(t);
  double lo = d / std::sqrt(3.0) * (1 - 1e-12), hi = d * (1 + 1e-12);
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    bool meets = false;
    for (size_t t : near)
      if (triangle_meets_cube(p, mid, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2))) {
        meets = true;
        break;
      }
    (meets ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace voxcd::test
