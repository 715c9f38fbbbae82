// Exact geometry by brute force, for tests and benchmarks that check results against the meshes themselves:
// point in a closed mesh by ray parity, and the distance from a point to a mesh's surface (Euclidean and max norm).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "voxcd/host/object/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::test {

// Point in a closed mesh by the parity of crossings along a fixed generic direction (Moller-Trumbore).
inline bool inside_reference(const Mesh& m, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = Eigen::Vector3d(0.5773, 0.3119, 0.7549).normalized();
  int n = 0;
  for (size_t t = 0; t < m.size(); ++t) {
    const Eigen::Vector3d a = m.corner(t, 0), e1 = m.corner(t, 1) - a, e2 = m.corner(t, 2) - a;
    const Eigen::Vector3d q = d.cross(e2);
    const double det = e1.dot(q);
    if (det == 0) continue;
    const Eigen::Vector3d s = p - a;
    const double u = s.dot(q) / det;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d r = s.cross(e1);
    const double v = d.dot(r) / det;
    if (v < 0 || u + v > 1) continue;
    if (e2.dot(r) / det > 0) ++n;
  }
  return n % 2;
}

// The distance from p to the triangle a, b, c (Ericson, Real-Time Collision Detection, 5.1.5: the closest point by
// Voronoi regions).
inline double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  // Ericson, Real-Time Collision Detection, 5.1.5: the closest point by Voronoi regions.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

inline double mesh_distance(const Mesh& m, const Eigen::Vector3d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < m.size(); ++t) d = std::min(d, point_triangle_distance(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)));
  return d;
}

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
