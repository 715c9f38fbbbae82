// Internal to host/object (distance_build.cpp, detail/brick_build.cpp): one node's quantised signed distance, as
// dense and sparse fields both measure it, so that the two give the same value at the same node.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/closest.h"
#include "voxcd/host/mesh/mesh.h"

namespace voxcd {
struct DistanceOptions;
}

namespace voxcd::detail {

// MeshError unless opt's bits are 4, 8 or 16, its band positive and finite, and the mesh has triangles (not a point
// cloud): what every field of a mesh needs.
void check_distance_options(const Mesh& mesh, const DistanceOptions& opt);

// What a node's value needs besides its place: the mesh's triangles in grid coordinates and their tree, the band's
// search radius (a little more than the band, so that a distance at its edge is still measured exactly), 1 / step
// and the clamp.
struct NodeMeasure {
  const Mesh& mesh;
  const std::vector<Eigen::Vector3d>& gv;  // vertices in grid coordinates
  const TriangleTree& tree;
  double radius;
  double inv_step;
  int qmin, qmax;
};

// clamp(round(+-d / step)) at grid point p, d the distance to the nearest triangle (negative when `inside`); the
// clamped extreme when no triangle lies within the radius. `prev` is the nearest triangle of a neighbouring node
// (UINT32_MAX: none), whose distance bounds the search, which still returns the nearest of all (so the value never
// depends on it); it is set to this node's nearest.
inline int16_t node_value(const NodeMeasure& m, const Eigen::Vector3d& p, bool inside, uint32_t& prev) {
  double r2 = m.radius * m.radius;
  if (prev != UINT32_MAX) {
    const auto& t = m.mesh.triangles[prev];
    r2 = std::min(r2, closest_on_triangle(p, m.gv[t[0]], m.gv[t[1]], m.gv[t[2]]).d2);
  }
  const Closest c = m.tree.closest(p, r2);
  prev = c.triangle;
  if (!c.found()) return int16_t(inside ? m.qmin : m.qmax);
  const double d = std::sqrt(c.d2);
  const double v = std::round((inside ? -d : d) * m.inv_step);
  return int16_t(std::clamp(v, double(m.qmin), double(m.qmax)));
}

}  // namespace voxcd::detail
