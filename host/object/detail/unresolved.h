// Internal to host/object (distance_build.cpp): the cells a distance field cannot resolve, made conservative, so that a
// distance voxmap never misses what the 2-bit voxmap of the same grid finds there (docs/objects.md, "Conservative
// cells"; docs/pairs.md).
#pragma once

#include <cstdint>

#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

// The largest value, in voxels, that the field's interpolant may take on the surface inside a cell the surface
// crosses before the cell counts as unresolved: a part thinner than a voxel, a sharp edge or spike, a sheet.
constexpr double kResolvedTolerance = 0.25;

// Sets every node of every unresolved cell of f to at most 0 (touching), so that the interpolant is <= 0 on the
// whole cell and every point in it is a hit at any margin >= 0, as in a 2-bit surface voxel. A cell is unresolved
// when a triangle crosses it and either belongs to a sheet (no inside: the field is unsigned) or the interpolant of
// f exceeds kResolvedTolerance at a corner or the centroid of the triangle's piece inside the cell. The cells are
// those of voxelize on g (f's grid). Returns how many cells were made conservative. Never depends on `threads`.
uint64_t make_unresolved_conservative(const Mesh& mesh, const GridPlacement& g, DistanceField& f, unsigned threads);

}  // namespace voxcd::detail
