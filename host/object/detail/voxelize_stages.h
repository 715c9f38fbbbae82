// Internal to host/object (the voxeliser's files): the stages voxelize() and its variants share, each defined in
// the file of its concern: the surface voxels (voxelize_surface.cpp) and the solid fill (voxelize_solid.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/detail/voxel_geometry.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd::detail {

// The surface voxels (voxelize_surface.cpp): bit i set for every voxel a triangle of m overlaps, on the pool.
std::vector<uint64_t> surface_bits_grid(const GridMesh& gm, const Mesh& m, const GridPlacement& gp,
                                        ThreadPool& pool);
// Bit i set for every voxel whose cube, grown by kGrow, holds a vertex (a point cloud's surface).
std::vector<uint64_t> point_bits(const Mesh& m, const GridPlacement& gp);
// Surface voxels override whatever the fill gave.
void apply_surface(Voxmap& vm, const std::vector<uint64_t>& sb);

// The solid fill (voxelize_solid.cpp).
// Sets voxels [b, e) of an all-empty-or-interior word array to interior.
void fill_interior(std::vector<uint64_t>& w, uint64_t b, uint64_t e);
// Steps 1-4 of the voxeliser on grid gp: every voxel whose centre has a generalized winding number of the non-sheet
// triangles of at least 1/2 becomes interior in vm (all empty before). Step 4 leaves out the voxels set in *skip
// (the surface voxels, which voxelize overrides anyway); with skip null every voxel is decided.
void fill_solid(const Mesh& mesh, const GridMesh& gm, const GridPlacement& gp, ThreadPool& pool,
                const std::vector<uint64_t>* skip, Voxmap& vm, VoxelizeReport& rep);

}  // namespace voxcd::detail
