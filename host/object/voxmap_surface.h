// The surface of a voxmap's solid: the faces between its non-empty voxels and the rest, as a triangle mesh in the
// object's frame. Recordings and the viewer draw an object with it when its mesh is not at hand.
#pragma once

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd {

// Two triangles per face of a non-empty voxel whose neighbour across it is empty or outside the grid, outward,
// corners shared between faces. An empty voxmap gives an empty mesh.
Mesh voxmap_surface(const Voxmap& v);

}  // namespace voxcd
