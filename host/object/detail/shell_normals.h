// Internal to host/object (point_shell.cpp, sparse_shell_build.cpp, object_file.cpp): how a centre shell's points get
// their normals, shared so that the dense and the sparse shell give every point the same one.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "voxcd/host/object/point_shell.h"

namespace voxcd::detail {

// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double dist2_point_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c);

// The nearest triangle seen so far from a shell point.
struct Nearest {
  double d2 = std::numeric_limits<double>::infinity();
  uint32_t tri = UINT32_MAX;
  // Ties go to the lower triangle index, so that the result does not depend on the split over workers.
  bool better_than(const Nearest& o) const { return d2 < o.d2 || (d2 == o.d2 && tri < o.tri); }
};

// The centre of voxel c of the shell grid, in the object's frame (PointShell::points).
inline Eigen::Vector3d centre_of(const GridPlacement& g, const std::array<uint32_t, 3>& c) {
  return g.origin + g.voxel * Eigen::Vector3d(c[0] + 0.5, c[1] + 0.5, c[2] + 0.5);
}

// The unit normal of triangle t in the object's frame: a shell point's whose nearest triangle is t.
Eigen::Vector3d triangle_normal(const Mesh& mesh, size_t t);

// The normals of a point cloud's shell points at `cells` of grid g (point_shell's rule).
std::vector<Eigen::Vector3d> cloud_normals(const Mesh& mesh, const GridPlacement& g,
                                           const std::vector<std::array<uint32_t, 3>>& cells);

// The centre shell of voxels `cells` of grid g (strictly increasing linear index): the points and the normals
// point_shell gives them.
PointShell centre_shell(const Mesh& mesh, const GridPlacement& g, std::vector<std::array<uint32_t, 3>> cells,
                        unsigned threads);

}  // namespace voxcd::detail
