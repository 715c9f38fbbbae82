// Internal to host/object (distance_build.cpp, sparse_build.cpp): the cells a distance field cannot resolve, made
// conservative, so that a distance voxmap never misses what the 2-bit voxmap of the same grid finds there
// (docs/objects.md, "Conservative cells"; docs/pairs.md). The test itself works on any interpolant and any cell size,
// so that a sparse field's refined bricks use it on their sub-cells (docs/objects.md, "Sparse distance field").
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

// The largest value, in voxels, that the field's interpolant may take on the surface inside a cell the surface
// crosses (beyond half the field's quantisation step) before the cell counts as unresolved.
constexpr double kResolvedTolerance = 0.25;
// How far inside the surface, in voxels, along the surface's inward normal, the interpolant must be at most 0 in a
// resolved cell: the shell's covering radius sqrt(3)/2 h (h = 1/sqrt(2) voxel), so that a crossing body's shell has
// a point in the hits there. Parts thinner than this are unresolved.
constexpr double kResolvedDepth = 0.6124;

using Polygon = std::vector<Eigen::Vector3d>;

// Triangle abc (grid coordinates) clipped to the closed cube [lo, lo + size]^3 (Sutherland-Hodgman, six planes).
Polygon piece_in_cube(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& lo, double size);

// The piece's corners and centroid x lie on the surface within `tolerance` of the interpolant `sample` (a callable
// from grid coordinates to voxels), and each passes `deep(x)`, the test a little inside the surface (callers say
// where and what: make_unresolved_conservative's and the sparse bricks' differ). An empty piece (a cell that holds
// the triangle only through the voxeliser's growth) is resolved.
template <class Sample, class Deep>
bool piece_resolved(const Sample& sample, const Polygon& piece, double tolerance, const Deep& deep) {
  if (piece.empty()) return true;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : piece) centroid += x;
  centroid /= double(piece.size());
  auto fine = [&](const Eigen::Vector3d& x) { return sample(x) <= tolerance && deep(x); };
  if (!fine(centroid)) return false;
  for (const Eigen::Vector3d& x : piece)
    if (!fine(x)) return false;
  return true;
}

// The unit inward normal of triangle abc (repair orients every non-sheet triangle outward), or false for a
// degenerate triangle, which has no inside to test.
bool inward_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d& n);

// Sets every node of every unresolved cell of f to at most 0 (touching), so that the interpolant is <= 0 on the
// whole cell and every point in it is a hit at any margin >= 0, as in a 2-bit surface voxel. A cell is unresolved
// when a triangle crosses it and belongs to a sheet (no inside: the field is unsigned), or at a corner or the
// centroid of the triangle's piece inside the cell the interpolant of f exceeds kResolvedTolerance + step / 2, or
// exceeds 0 at kResolvedDepth inside along the triangle's inward normal (a part thinner than that, a sharp edge or
// spike). The cells are those of voxelize on g (f's grid). Returns how many cells were made conservative. Never
// depends on `threads`.
uint64_t make_unresolved_conservative(const Mesh& mesh, const GridPlacement& g, DistanceField& f, unsigned threads);

}  // namespace voxcd::detail
