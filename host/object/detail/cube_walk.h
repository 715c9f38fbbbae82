// Internal to host/object (sparse_build.cpp, detail/brick_build.cpp): the cubes of a regular grid that a triangle
// meets, found column by column along the triangle's dominant normal axis, so that the work follows its area rather
// than its bounding box (a large slanted triangle's box holds far more cubes than it meets).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

// Calls fn(i, j, k) for every cube (i, j, k), lo <= index < hi per axis, of the grid of cubes of side `size` (cube
// (i, j, k) covers [i, i + 1] x [j, j + 1] x [k, k + 1] times size, in a, b, c's coordinates) whose closed cube grown
// by `grow` on every side meets triangle abc (triangle_meets_cube).
template <class Fn>
void for_each_cube_meeting(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double size,
                           double grow, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& hi, Fn&& fn) {
  const Eigen::Vector3d tlo = a.cwiseMin(b).cwiseMin(c), thi = a.cwiseMax(b).cwiseMax(c);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  int ax = 0;
  if (std::abs(n[1]) > std::abs(n[ax])) ax = 1;
  if (std::abs(n[2]) > std::abs(n[ax])) ax = 2;
  const int u = (ax + 1) % 3, v = (ax + 2) % 3;
  const double half = size / 2 + grow, slack = 1e-9 * size;
  // The cubes along `axis` whose grown extent meets [l, r].
  auto range = [&](double l, double r, int axis, int64_t& i0, int64_t& i1) {
    i0 = std::max<int64_t>(lo[size_t(axis)], int64_t(std::floor((l - grow - slack) / size)));
    i1 = std::min<int64_t>(hi[size_t(axis)] - 1, int64_t(std::floor((r + grow + slack) / size)));
  };
  int64_t u0, u1, v0, v1;
  range(tlo[u], thi[u], u, u0, u1);
  range(tlo[v], thi[v], v, v0, v1);
  const double d = n.dot(a);
  const bool flat = n[ax] == 0;  // degenerate: walk the (small) bounding box
  std::array<int64_t, 3> idx;
  for (int64_t iv = v0; iv <= v1; ++iv)
    for (int64_t iu = u0; iu <= u1; ++iu) {
      double amin = tlo[ax], amax = thi[ax];
      if (!flat) {
        // The plane's extent along the dominant axis over the column's grown square.
        double pmin = HUGE_VAL, pmax = -HUGE_VAL;
        for (double pu : {iu * size - grow, (iu + 1) * size + grow})
          for (double pv : {iv * size - grow, (iv + 1) * size + grow}) {
            const double pa = (d - n[u] * pu - n[v] * pv) / n[ax];
            pmin = std::min(pmin, pa);
            pmax = std::max(pmax, pa);
          }
        amin = std::max(amin, pmin);
        amax = std::min(amax, pmax);
        if (amin > amax + slack) continue;
      }
      int64_t a0, a1;
      range(amin, amax, ax, a0, a1);
      idx[size_t(u)] = iu;
      idx[size_t(v)] = iv;
      for (int64_t ia = a0; ia <= a1; ++ia) {
        idx[size_t(ax)] = ia;
        const Eigen::Vector3d centre((idx[0] + 0.5) * size, (idx[1] + 0.5) * size, (idx[2] + 0.5) * size);
        if (triangle_meets_cube(centre, half, a, b, c)) fn(idx[0], idx[1], idx[2]);
      }
    }
}

}  // namespace voxcd::detail
