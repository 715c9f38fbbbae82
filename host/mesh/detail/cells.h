// Internal to host/mesh (repair.cpp): the cells of space that a part with non-manifold edges bounds, and what
// each of its triangles is in the solid they make (docs/objects.md, "Non-manifold parts").
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::detail {

enum class FaceRole : uint8_t {
  kBoundary,  // solid on one side, empty on the other
  kInternal,  // solid on both sides: a face inside the solid (a shared face, a membrane)
  kFin,       // empty on both sides: a sheet (a fin, a flap)
};

struct CellRoles {
  std::vector<FaceRole> role;    // per triangle of the part, in the order given
  std::vector<uint8_t> reverse;  // per triangle: 1 when a boundary triangle must be reversed to face the empty side
  size_t cells = 0;              // regions of space found, the unbounded one included
};

// The cells of an edge-connected part `tris` of m (indices into m.triangles) and each triangle's role. Around every
// edge the triangles are sorted by angle, and the two sides that face one wedge between neighbours belong to one
// cell (triangles lying on one another at an edge, as coplanar faces of touching parts do, bound no wedge between
// them); the side a ray from beyond the part's box meets first faces the unbounded cell. Cells alternate empty and
// solid from the unbounded one inwards: a cell is solid when the fewest triangles a path from outside must cross is
// odd, as for nested closed surfaces. An edge of one triangle (a hole) joins nothing: the hole's two sides stay
// apart, as if capped. Orientation of the input plays no part; overlapping closed parts that share an edge keep
// each its own inside (their union). Deterministic.
CellRoles classify_cells(const Mesh& m, const std::vector<uint32_t>& tris);

}  // namespace voxcd::detail
