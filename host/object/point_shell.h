// The point shell (the paper's second voxmap): the centres of the surface voxels of the mesh voxelised at a finer
// spacing, each with an outward normal. docs/objects.md states exactly which cubes cannot pass through it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "voxcd/host/object/mesh.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

struct ShellOptions {
  double target_voxel = 0;         // voxel size of the voxmaps the shell is tested against; finite, > 0
  double ratio = std::sqrt(2.0);   // shell spacing = target_voxel / ratio: the paper's rule is sqrt(2)
  Eigen::Vector3d shift = Eigen::Vector3d::Constant(0.5);  // placement of the shell grid, as VoxelizeOptions
  uint32_t max_dim = 4096;         // per axis of the shell grid (it is never loaded into the device)
  unsigned threads = 0;            // 0: one per hardware thread; the result never depends on it

  double spacing() const { return target_voxel / ratio; }
};

struct PointShell {
  // The shell grid: point k is the centre of its voxel cells[k], i.e. grid coordinates cells[k] + 0.5, which is
  // the frame of the device's shell words (units: the shell spacing, origin: grid.origin).
  GridPlacement grid;
  std::vector<std::array<uint32_t, 3>> cells;  // in linear-index order x + nx*(y + ny*z)
  std::vector<Eigen::Vector3d> points;         // the same points in the object's frame
  std::vector<Eigen::Vector3d> normals;        // unit, outward, object frame

  size_t size() const { return cells.size(); }
  GridFrame frame() const { return grid.frame(); }
  // Grid coordinates of point k (exact half-integers).
  Eigen::Vector3d grid_point(size_t k) const {
    return Eigen::Vector3d(cells[k][0] + 0.5, cells[k][1] + 0.5, cells[k][2] + 0.5);
  }
  // Shell memory words for cfg (exact: half-integers need PF >= 1). RangeError names the point that does not fit.
  std::vector<ShellWord> words(const DeviceConfig& cfg) const;
};

// Builds the shell of a validated mesh. A point's normal is the outward normal of the nearest triangle among
// those that pass through its voxel (ties: the lowest triangle index). Throws MeshError as place_grid does.
PointShell point_shell(const Mesh& mesh, const ShellOptions& opt);

}  // namespace voxcd
