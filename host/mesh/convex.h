// Whether a closed mesh bounds a convex solid: `voxcd size` needs it for the interpolation term of a distance
// voxmap's error bound (docs/contract.md: zero over a convex object, whose signed distance is convex).
#pragma once

#include "voxcd/host/mesh/mesh.h"

namespace voxcd {

// True when the mesh is one closed, consistently oriented, edge-connected surface that is locally convex at every
// edge (the fourth vertex across an edge lies on or below the plane of the first triangle, within 1e-9 of the
// bounding box's diagonal): such a surface bounds a convex solid (Tietze-Nakajima). False for a point cloud, an
// open or non-manifold mesh, several parts, or any reflex edge. Linear in the triangles.
bool is_convex(const Mesh& mesh);

}  // namespace voxcd
