// Internal to host/mesh (repair.cpp and its steps): the steps of repair() in their order, each in a file of its own:
// cleaning and welding (repair_weld.cpp), non-manifold parts and orientation (repair_orient.cpp), sheets
// (repair_sheets.cpp).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <array>
#include <vector>

#include "voxcd/host/mesh/detail/edge_uses.h"
#include "voxcd/host/mesh/mesh.h"

namespace voxcd::detail::mesh_repair {

// The key of a cell of a spatial hash.
struct CellKeyHash {
  size_t operator()(const std::array<int64_t, 3>& k) const {
    return size_t((uint64_t(k[0]) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(k[1]) * 0xc2b2ae3d27d4eb4full) ^
                  (uint64_t(k[2]) * 0x165667b19e3779f9ull));
  }
};

// Cleaning and welding (repair_weld.cpp).
// Drops vertices no triangle uses and triangles with a non-finite corner; the finite vertices of a triangle-less
// mesh are kept (a point cloud).
size_t drop_nonfinite(Mesh& m);
// Welds vertices within `tol` (Chebyshev distance, to the first vertex of a cluster in index order, after exactly
// equal vertices are merged); vertices no triangle uses are dropped (all finite vertices are kept for a point cloud).
// Returns the vertices merged, and in *near those not exactly equal to their representative.
size_t weld_near(Mesh& m, double tol, size_t* near);
// Drops degenerate triangles (counted by cause) and exact duplicates (the same three vertices in either
// orientation; the first is kept).
void drop_degenerate_and_duplicates(Mesh& m, MeshReport& r);
// Closes cracks: a vertex on an open edge moves onto the nearest vertex on an open edge of another edge-connected
// part within `tol` (one that comes earlier in index order, so that no two vertices trade places). Returns how
// many vertices moved; the triangles are remapped.
size_t close_cracks(Mesh& m, const std::vector<EdgeUse>& uses, double tol);

// Non-manifold parts and orientation (repair_orient.cpp).
// Per triangle, what the non-manifold parts' cells decided (detail/cells.h).
struct CellDecision {
  std::vector<uint8_t> part;     // 0: a part without non-manifold edges; else 1 + the resolved part's number
  std::vector<uint8_t> fin;      // empty space on both sides: a sheet
  std::vector<uint8_t> reverse;  // a boundary triangle to reverse so that it faces the empty side
  size_t parts = 0;
};

// Parts (edge-connected) with an edge of three triangles or more are decided by their cells: internal triangles
// are dropped, boundary triangles face the empty side, fins become sheets. Counts the non-manifold edges found.
CellDecision resolve_nonmanifold(Mesh& m, const std::vector<EdgeUse>& uses, MeshReport& r);

// Patches: triangles joined across edges of exactly two triangles, each oriented consistently and as most of its
// triangles were given; a resolved non-manifold part is one patch of its boundary triangles, oriented by its cells,
// and one of its fins.
struct Patches {
  std::vector<uint32_t> of;                  // per triangle
  std::vector<std::vector<uint32_t>> list;   // per patch, its triangles
  std::vector<uint8_t> resolved;             // per patch: 1 the boundary of a resolved part, 2 its fins, 0 neither
  std::vector<char> flip;                    // per triangle: reversed
};

Patches orient_patches(Mesh& m, const std::vector<EdgeUse>& uses, const CellDecision& cells);
// The edges after orientation (a reversed triangle runs each of its edges the other way); counts open and
// inconsistent edges. A patch is closed when each of its edges is used by an even number of its triangles, as
// often one way as the other.
std::vector<char> closed_patches(std::vector<EdgeUse>& after, const Patches& p, MeshReport& r);
// Outward, nested parts alternating: a patch inside d closed patches (its box inside theirs, and sampled vertices
// inside by parity) faces outward when d is even and inward when d is odd, so a cavity stays empty whichever way its
// surface was given. Open patches use the volume closed by the cone from their centroid; a resolved part's boundary
// already faces out of its own cells and turns only when nested. Returns the triangles reversed in all.
size_t orient_outward(Mesh& m, Patches& p, const std::vector<char>& closed);

// Sheets (repair_sheets.cpp).
// Sheets: patches grouped with the open patches whose boundary vertices come within kCrackRelative of the model's size
// of theirs (parts split by cracks close each other); a group whose boundary encloses more than kSheetRatio of
// its area (the vector area of its boundary loops, origin-independent for closed loops) encloses nothing. A
// resolved part's fins are sheets whatever their boundary.
void mark_sheets(Mesh& m, const Patches& p, const std::vector<EdgeUse>& after, const std::vector<char>& closed,
                 const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, MeshReport& r);

}  // namespace voxcd::detail::mesh_repair
