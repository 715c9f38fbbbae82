// Internal to host/object (sparse_build.cpp): one coarse cell of a sparse distance field, measured at level 0 and
// rebuilt at finer levels until its interpolant resolves the surface that crosses it (docs/objects.md, "Sparse
// distance field").
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "voxcd/host/object/detail/brick_signs.h"
#include "voxcd/host/object/detail/node_value.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

// How far outside the surface, in voxels, a point of a crossed sub-cell may lie where the interpolant reads at most 0
// (a contact at margin 0) before the brick is refined: a contact's 1/4 voxel, less the device's weight truncation
// (3 (h + s) 2^-WB) and the fixed-point path's share.
constexpr double kOutsideTolerance = 0.2;

// What every brick of one field shares.
struct BrickContext {
  const Mesh& mesh;
  const GridPlacement& g;         // the voxmap's grid
  std::array<uint32_t, 3> cells;  // coarse cells per axis
  const NodeMeasure& measure;     // distances (grid coordinates) and quantisation
  const PseudoNormals& normals;   // of the mesh in grid coordinates: which side of the surface a point lies on
  const BrickSigns& signs;        // level-0 nodes: the layer of the cell must be loaded
  double step;                    // voxels per node unit
  int max_level;                  // 0 .. 3
  bool resolve;                   // test (and refine, and make conservative) at all
};

// A cell as the field stores it: code 0 / 1 (uniform), or 2 + level with its brick's nodes (X + n (Y + n Z),
// n = 8 2^level + 1) and the keys of its conservative sub-cells (SparseDistanceField::conservative_key, cell index
// `t`).
struct BrickResult {
  uint8_t code = 0;
  std::vector<int16_t> nodes;
  std::vector<uint64_t> conservative;
};

// Cell c (table index t) whose nodes may lie within the band: its nodes measured at level 0; then, while some sub-cell
// that a triangle of `tris` (the triangles meeting the cell) crosses is unresolved at the brick's level, the brick
// measured again at the next level (straight to max_level when a sheet crosses it: a sheet resolves at none); at
// max_level the unresolved sub-cells' nodes are lowered to at most 0. A sub-cell of side h = 2^-l voxel is resolved
// when the triangle is not a sheet's and, at the corners and centroid x of the triangle's piece in it, the
// interpolant is at most kResolvedTolerance + step / 2 (the same bound at every level) and reads at most 0 at
// min(kResolvedDepth h, half the part's thickness along the inward normal) inside x, unless that point lies nearer
// the surface than half that depth (docs/objects.md, "Sparse distance field"). Refined too, and never lowered: a
// crossed sub-cell where the interpolant reads at most 0 at a point (its centre, a face centre or an edge midpoint)
// that lies outside, farther than kOutsideTolerance from the surface; a sub-cell no triangle crosses whose nodes hold
// both signs (the boundary of a hole's filling).
BrickResult build_brick(const BrickContext& ctx, const std::array<uint32_t, 3>& c, uint64_t t,
                        const std::vector<uint32_t>& tris);

// Cell c wholly beyond the band (no triangle within it of any node): uniform by the sign of its level-0 nodes, or
// (where the solid's boundary crosses it far from any triangle: a hole's filling) a brick of clamped values at
// max_level (level 0 when the resolution test is off).
BrickResult far_cell(const BrickContext& ctx, const std::array<uint32_t, 3>& c);

}  // namespace voxcd::detail
