// Internal to host/object: the voxeliser's solid (host/object/voxelize.cpp) at the centres of any grid's voxels,
// surface voxels included, for the sign of a distance field (distance_build.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

// Bit i (word i / 64, bit i % 64) set when the centre of voxel i of g lies in the solid as voxelize decides it
// (generalized winding number of the non-sheet triangles >= 1/2: the exact integer part plus the caps), for every
// voxel, surface or not. *surface, when given, gets surface_bits(mesh, g). The mesh must lie inside g (as
// place_grid puts it). MeshError for a point cloud. Never depends on `threads`.
std::vector<uint64_t> solid_bits(const Mesh& mesh, const GridPlacement& g, unsigned threads,
                                 std::vector<uint64_t>* surface = nullptr);

}  // namespace voxcd::detail
