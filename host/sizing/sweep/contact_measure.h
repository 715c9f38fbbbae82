// The contact error measured against exact geometry: how far outside the other object's mesh the contacts of a
// scene's frames lie, for the bound of contact_bound.h to be checked against (`voxcd sweep`, docs/sweep.md).
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/ref/config.h"

namespace voxcd {

struct ContactMeasure {
  double worst_outside = 0;  // world units: the largest signed distance of a checked contact outside the other
                             // object's mesh (0 when every one lies inside or on it)
  uint64_t contacts = 0;     // contacts checked (those in conservative cells apart, below)
  // Contacts in or next to a conservative cell of a distance voxmap (a surface its nodes do not resolve: the 2-bit
  // voxmap's bound applies there, docs/pairs.md, DistanceField::near_conservative), and the largest distance of one
  // outside the other mesh.
  double worst_outside_conservative = 0;
  uint64_t conservative = 0;
  uint64_t pairs = 0;        // pairs tested in the sampled frames
  uint64_t frames = 0;       // frames sampled (each with at least one contact)
};

// Steps the scene (as measure_frames does, on the cpu backend with cfg) for `frames` frames and, at `samples` of
// them spread evenly (a due frame without contacts passes its turn to the next frame that has some), tests every
// broadphase pair of the frame on the same device and checks up to
// `per_pair` contacts of each (evenly spaced) against the other type's mesh (meshes[type], in the type's frame:
// scene_meshes): point-triangle distance, and inside by ray parity.
ContactMeasure measure_contacts(const Scene& scene, const RunConfig& f, const DeviceConfig& cfg,
                                const std::vector<Mesh>& meshes, uint64_t frames, uint64_t samples,
                                uint64_t per_pair = 64);

}  // namespace voxcd
