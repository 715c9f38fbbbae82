// Internal to host/object (point_shell.cpp, surface_shell.cpp): the grid a point shell is built on.
#pragma once

#include <cmath>
#include <string>

#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

// MeshError naming the mesh when the target voxel or the ratio is not a positive finite number.
inline void check_shell_options(const Mesh& mesh, const ShellOptions& opt) {
  if (!(std::isfinite(opt.target_voxel) && opt.target_voxel > 0))
    throw MeshError(mesh.name + ": the target voxel size must be a positive finite number, got " +
                    std::to_string(opt.target_voxel));
  if (!(std::isfinite(opt.ratio) && opt.ratio > 0))
    throw MeshError(mesh.name + ": the shell ratio must be a positive finite number, got " + std::to_string(opt.ratio));
}

// The grid of the shell of `mesh` at opt's spacing, shift and size limit (the options checked first).
inline GridPlacement shell_grid(const Mesh& mesh, const ShellOptions& opt) {
  check_shell_options(mesh, opt);
  VoxelizeOptions vo;
  vo.voxel = opt.spacing();
  vo.shift = opt.shift;
  vo.max_dim = opt.max_dim;
  vo.threads = opt.threads;
  return place_grid(mesh, vo);
}

}  // namespace voxcd::detail
