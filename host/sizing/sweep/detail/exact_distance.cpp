#include "voxcd/host/sizing/sweep/detail/exact_distance.h"

#include <algorithm>
#include <limits>

#include "voxcd/host/mesh/ray_crossing.h"

namespace voxcd::detail {

bool inside_mesh(const Mesh& m, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = Eigen::Vector3d(0.5773, 0.3119, 0.7549).normalized();
  int n = 0;
  for (size_t t = 0; t < m.size(); ++t) n += ray_crosses(m, t, p, d);
  return n % 2;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  // The closest point by Voronoi regions: a corner, an edge, or the face.
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

double mesh_distance(const Mesh& m, const Eigen::Vector3d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < m.size(); ++t)
    d = std::min(d, point_triangle_distance(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)));
  return d;
}

double signed_mesh_distance(const Mesh& m, const Eigen::Vector3d& p) {
  const double d = mesh_distance(m, p);
  return inside_mesh(m, p) ? -d : d;
}

}  // namespace voxcd::detail
