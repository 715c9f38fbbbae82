// Internal to host (mesh repair's inside test, sizing's exact distances): whether a ray crosses a triangle, the step
// of a point-in-mesh test by the parity of crossings.
#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::detail {

// Whether the ray from p along d crosses triangle t of m ahead of p (Moller-Trumbore; a ray parallel to the
// triangle's plane never does).
inline bool ray_crosses(const Mesh& m, size_t t, const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  const Eigen::Vector3d a = m.corner(t, 0), e1 = m.corner(t, 1) - a, e2 = m.corner(t, 2) - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (det == 0) return false;
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return false;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return false;
  return e2.dot(q) / det > 0;
}

}  // namespace voxcd::detail
