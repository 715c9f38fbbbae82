// How far outside the other object's surface a reported contact can lie (docs/contract.md "Error bound of a
// distance voxmap"), and the smallest voxmap kind that meets a requested bound: `voxcd size --contact-accuracy`
// chooses SB, WB and the band with it. docs/size.md derives each term.
#pragma once

#include <string>
#include <vector>

#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"

namespace voxcd {

// The interpolation term of a non-convex object, voxels: the contract's worst case at a concave corner of three
// faces, for pockets and gaps wider than a cell (narrower ones: up to sqrt(3)/2).
constexpr double kConcaveInterpolation = 0.385;

// A voxmap kind: SB = 2 (the paper's 2-bit states) or a distance voxmap of SB bits, WB weight bits, band voxels.
struct VoxmapKind {
  int SB = 2, WB = 8;
  double band = 0;  // voxels (0 for SB = 2)
  bool distance() const { return SB > 2; }
  double step() const;  // the distance field's quantisation step, voxels: band * 2^(1-SB)
  std::string text() const;  // "2-bit states" or "SB 8 WB 8, band 4 voxels (step 0.03125 voxel)"
};

// The terms of the bound for one object B, voxels of B (the fixed-point term is added by the caller).
struct ContactTerms {
  double cell = 0;           // 2-bit: a hit voxel's diagonal, sqrt(3); distance: 0
  double quantisation = 0;   // s / 2
  double weights = 0;        // (1 + s) * 3 * 2^-WB
  double interpolation = 0;  // 0 over a convex B, kConcaveInterpolation otherwise
  double total() const { return cell + quantisation + weights + interpolation; }
};
ContactTerms contact_terms(const VoxmapKind& k, bool convex_b);

// Per type of a scene (in the scene file's order): whether its mesh bounds a convex solid (is_convex on the mesh
// the scene file names). MeshError as load_source throws it.
std::vector<bool> types_convex(const RunConfig& f);

// The band that covers one frame's relative motion of any two bodies in B's voxels ((speed + spin) * radius per
// body and frame, docs/simulate.md), so that a penetration reached in one frame still has its depth and the ccd
// bound vouches for a whole frame; at least 3 voxels (a point within a voxel of the surface then interpolates
// between unclamped nodes).
double band_for_motion(const Scene& scene, const RunConfig& f);

// The cheapest kind whose bound voxel_B * terms + fixed meets `accuracy` (world units) for every type B: 2-bit
// states when they do (and the scene does not ask for ccd), else the smallest SB of 4, 8, 16 and then the smallest
// WB (up to max_wb) at `band`. SizeError "contact" when none does, naming the type and the voxel that would.
VoxmapKind choose_voxmap(const Scene& scene, const std::vector<bool>& convex, double accuracy, double fixed,
                         double band, bool need_distance, int max_wb = 16);

}  // namespace voxcd
