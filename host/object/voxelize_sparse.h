// The sparse voxeliser: voxelize()'s states, voxel for voxel, built straight into a SparseVoxmap layer by layer, so
// that memory grows with the surface and the coarse table, never with the box (docs/objects.md, "Sparse objects").
#pragma once

#include "voxcd/host/object/sparse_voxmap.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd {

// The voxmap voxelize(mesh, opt) gives, as a canonical sparse map of bricks of 2^bl voxels per axis (equal to
// SparseVoxmap::from_dense of it), and the same report. MeshError as voxelize throws them; std::invalid_argument for
// bl outside kMinBrickLog..kMaxBrickLog. The result never depends on opt.threads.
SparseVoxmap voxelize_sparse(const Mesh& mesh, const VoxelizeOptions& opt, VoxelizeReport* report = nullptr,
                             int bl = kDefaultBrickLog);

}  // namespace voxcd
