// Internal to the library's triangle trees (host/mesh/closest.cpp, host/object/detail/winding.cpp): a node's
// triangles split at the median.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace voxcd::detail {

// Splits tris[first, first + count) at its median along the longest axis of `ext` (the extent of the triangles'
// centres), keyed by the sum of the corners' coordinates on that axis; `tie(x, y)` orders equal keys (a function that
// is always false leaves them to nth_element). Returns the size of the first half, count / 2.
template <class Tri, class Tie>
uint32_t median_split(std::vector<Tri>& tris, uint32_t first, uint32_t count, const Eigen::Vector3d& ext, Tie tie) {
  int axis = 0;
  if (ext[1] > ext[axis]) axis = 1;
  if (ext[2] > ext[axis]) axis = 2;
  const uint32_t half = count / 2;
  std::nth_element(tris.begin() + first, tris.begin() + first + half, tris.begin() + first + count,
                   [axis, &tie](const Tri& x, const Tri& y) {
                     const double kx = x.a[axis] + x.b[axis] + x.c[axis], ky = y.a[axis] + y.b[axis] + y.c[axis];
                     return kx < ky || (kx == ky && tie(x, y));
                   });
  return half;
}

}  // namespace voxcd::detail
