// Internal to host/object (the sparse shell and its file section): a unit normal in 32 bits, octahedral (Meyer et al.
// 2010): the normal projected onto the octahedron |x| + |y| + |z| = 1, its lower half folded over the upper, the two
// coordinates as 16-bit signed integers. Angular error below 1e-4 radian (tests/host/object/test_sparse_shell.cpp).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace voxcd::detail {

inline double sign_not_zero(double v) { return v < 0 ? -1.0 : 1.0; }

// The normal's 32 bits: u in the low 16, v in the high 16, each round(coordinate * 32767). A zero vector encodes +z.
inline uint32_t encode_normal(const Eigen::Vector3d& n) {
  const double s = std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z());
  double u = s > 0 ? n.x() / s : 0, v = s > 0 ? n.y() / s : 0;
  if (s > 0 && n.z() < 0) {
    const double fu = (1 - std::abs(v)) * sign_not_zero(u), fv = (1 - std::abs(u)) * sign_not_zero(v);
    u = fu;
    v = fv;
  }
  const auto q = [](double c) { return uint32_t(uint16_t(int16_t(std::lround(c * 32767.0)))); };
  return q(u) | q(v) << 16;
}

// The unit normal of 32 encoded bits.
inline Eigen::Vector3d decode_normal(uint32_t w) {
  double u = double(int16_t(uint16_t(w & 0xffff))) / 32767.0, v = double(int16_t(uint16_t(w >> 16))) / 32767.0;
  const double z = 1 - std::abs(u) - std::abs(v);
  if (z < 0) {
    const double fu = (1 - std::abs(v)) * sign_not_zero(u), fv = (1 - std::abs(u)) * sign_not_zero(v);
    u = fu;
    v = fv;
  }
  return Eigen::Vector3d(u, v, z).normalized();
}

}  // namespace voxcd::detail
