// The point shell (the paper's second voxmap): the centres of the surface voxels of the mesh voxelised at a finer
// spacing, each with an outward normal; or, for objects with a distance field, those centres projected onto the
// surface. docs/objects.md states exactly which cubes cannot pass through it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
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
  bool on_surface = false;         // project the points onto the surface (surface_shell)

  double spacing() const { return target_voxel / ratio; }
};

// Fraction bits of the grid coordinates of a surface shell's points (the object file's shell words).
constexpr int kShellFrac = 8;

struct PointShell {
  // The shell grid, the frame of the device's shell words (units: the shell spacing, origin: grid.origin).
  // Without on_surface, point k is the centre of its voxel cells[k] (grid coordinates cells[k] + 0.5), cells in
  // strictly increasing linear-index order x + nx*(y + ny*z). With on_surface, point k is at grid coordinates
  // coords[k] / 2^kShellFrac, and cells[k] is the voxel whose closed cube holds it (coords / 2^kShellFrac floored,
  // at most dims - 1), in non-decreasing linear-index order (then z, y, x of coords; no two points equal).
  GridPlacement grid;
  std::vector<std::array<uint32_t, 3>> cells;
  std::vector<Eigen::Vector3d> points;   // the same points in the object's frame: origin + spacing * grid_point(k)
  std::vector<Eigen::Vector3d> normals;  // unit, outward, object frame
  bool on_surface = false;
  std::vector<std::array<int32_t, 3>> coords;  // on_surface only: grid coordinates, kShellFrac fraction bits

  size_t size() const { return cells.size(); }
  GridFrame frame() const { return grid.frame(); }
  // Grid coordinates of point k, exactly (half-integers, or multiples of 2^-kShellFrac on the surface).
  Eigen::Vector3d grid_point(size_t k) const {
    if (on_surface)
      return Eigen::Vector3d(coords[k][0], coords[k][1], coords[k][2]) / double(1 << kShellFrac);
    return Eigen::Vector3d(cells[k][0] + 0.5, cells[k][1] + 0.5, cells[k][2] + 0.5);
  }
  // Largest grid coordinate of any point (0 for an empty shell): the extent the fixed-point error bound takes.
  double max_grid_coordinate() const;
  // Shell memory words for cfg: grid_point(k) quantised to PF fraction bits, exact when PF >= 1 (cell centres) or
  // PF >= kShellFrac (surface points; fewer bits round them once more, ties away from zero). RangeError names the
  // point that does not fit.
  std::vector<ShellWord> words(const DeviceConfig& cfg) const;
};

// Builds the shell of a validated mesh. A point's normal is the outward normal of the nearest triangle among
// those that pass through its voxel (ties: the lowest triangle index). Throws MeshError as place_grid does.
// With opt.on_surface, surface_shell.
PointShell point_shell(const Mesh& mesh, const ShellOptions& opt);

// The shell on the surface: the centre of each surface voxel of point_shell's grid moved to its closest point on the
// mesh (ties: the lowest triangle index) and rounded to 2^-kShellFrac of the spacing per axis, equal points merged
// (the first voxel's kept); a point's normal is the angle-weighted pseudo-normal of the closest feature (the face's
// normal inside a face). Every point lies within sqrt(3) * 2^-(kShellFrac+1) spacings of the surface. MeshError as
// point_shell, and for a point cloud.
PointShell surface_shell(const Mesh& mesh, const ShellOptions& opt);

}  // namespace voxcd
