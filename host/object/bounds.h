// Enclosing spheres: the smallest sphere around a point set (exact, Welzl's algorithm), and the paper's sphere
// (half the longest vertex-to-vertex line), which does not always enclose its object.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace voxcd {

struct Sphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  // Closed ball, with a relative tolerance for the rounding of its own construction.
  bool contains(const Eigen::Vector3d& p, double tol = 1e-9) const {
    return (p - centre).norm() <= radius * (1 + tol) + tol;
  }
};

// The smallest sphere that encloses every point (empty input: radius 0 at the origin). Deterministic: the points
// are visited in an order fixed by `seed`.
Sphere min_sphere(const std::vector<Eigen::Vector3d>& points, uint64_t seed = 1);

// The sphere centred on the midpoint of the two vertices farthest apart, with half their distance as radius (the
// paper's bounding sphere). It encloses every vertex of some objects and misses vertices of others.
Sphere longest_chord_sphere(const std::vector<Eigen::Vector3d>& points);

}  // namespace voxcd
