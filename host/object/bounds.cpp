#include "voxcd/host/object/bounds.h"

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>
#include <random>

namespace voxcd {

namespace {

Sphere from2(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return {0.5 * (a + b), 0.5 * (a - b).norm()}; }

// The smallest sphere with a, b, c on its boundary: the circumcircle's sphere (or the widest pair's when the three
// are (nearly) collinear).
Sphere from3(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, n = ab.cross(ac);
  const double d = 2 * n.squaredNorm();
  if (d < 1e-300) {
    Sphere s = from2(a, b);
    for (const Sphere& t : {from2(a, c), from2(b, c)})
      if (t.radius > s.radius) s = t;
    return s;
  }
  const Eigen::Vector3d o = (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / d;
  return {a + o, o.norm()};
}

// The sphere through four points (the circumsphere), or the best of the 3-point spheres when they are coplanar.
Sphere from4(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& e) {
  Eigen::Matrix3d m;
  m.row(0) = b - a;
  m.row(1) = c - a;
  m.row(2) = e - a;
  const double det = m.determinant();
  if (std::abs(det) < 1e-14 * m.cwiseAbs().maxCoeff() * m.cwiseAbs().maxCoeff() * m.cwiseAbs().maxCoeff()) {
    Sphere best;
    best.radius = -1;
    const Eigen::Vector3d p[4] = {a, b, c, e};
    for (int i = 0; i < 4; ++i) {
      Sphere s = from3(p[(i + 1) % 4], p[(i + 2) % 4], p[(i + 3) % 4]);
      if (s.contains(p[i], 1e-12) && (best.radius < 0 || s.radius < best.radius)) best = s;
    }
    return best.radius >= 0 ? best : from3(a, b, c);
  }
  const Eigen::Vector3d rhs(0.5 * (b - a).squaredNorm(), 0.5 * (c - a).squaredNorm(), 0.5 * (e - a).squaredNorm());
  const Eigen::Vector3d o = m.partialPivLu().solve(rhs);
  return {a + o, o.norm()};
}

}  // namespace

Sphere min_sphere(const std::vector<Eigen::Vector3d>& input, uint64_t seed) {
  if (input.empty()) return {};
  std::vector<Eigen::Vector3d> p = input;
  std::shuffle(p.begin(), p.end(), std::mt19937_64(seed));
  // Welzl's algorithm, iterative: each point outside the current sphere becomes a boundary point.
  Sphere s{p[0], 0};
  for (size_t i = 1; i < p.size(); ++i) {
    if (s.contains(p[i])) continue;
    s = {p[i], 0};
    for (size_t j = 0; j < i; ++j) {
      if (s.contains(p[j])) continue;
      s = from2(p[i], p[j]);
      for (size_t k = 0; k < j; ++k) {
        if (s.contains(p[k])) continue;
        s = from3(p[i], p[j], p[k]);
        for (size_t l = 0; l < k; ++l) {
          if (s.contains(p[l])) continue;
          s = from4(p[i], p[j], p[k], p[l]);
        }
      }
    }
  }
  // Rounding can leave a point a hair outside: grow to the farthest point.
  double r = s.radius;
  for (const auto& q : p) r = std::max(r, (q - s.centre).norm());
  s.radius = r;
  return s;
}

Sphere longest_chord_sphere(const std::vector<Eigen::Vector3d>& p) {
  Sphere best;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) {
      const double r = 0.5 * (p[i] - p[j]).norm();
      if (r > best.radius) best = {0.5 * (p[i] + p[j]), r};
    }
  if (p.size() == 1) best.centre = p[0];
  return best;
}

}  // namespace voxcd
