// Random conformance vectors with hard cases mixed in: voxel faces, -1/4 voxel, exact +-1 matrix entries, quarter
// and half turns, far and aliasing translations, full-range fields, 1x1x1 and odd-sized maps, maps mid-memory,
// empty shells, every mode and every hit mask. Expectations come from ref/ (the caller runs them).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

struct GenerateOptions {
  uint64_t seed = 1;
  size_t jobs = 200;
  size_t cloud_points = 2000;  // size of the random point cloud block of the shell memory
  DeviceConfig config{};
  // Coverage-directed stimulus (docs/verification.md): stimulus bins to aim at, the ones a coverage report found
  // empty. Every second job is then made for one of them in turn, by a template (aimable_bin); the other jobs are
  // the random ones, and with no aim the vectors are exactly those of before.
  std::vector<std::string> aim;
};

// True for the stimulus bins a template can aim at (host/regress/stimulus_bins.h's names): face.A.K, far.A.wraps,
// floor.A.negative (A x, y or z; K -1, 0, n-1 or n), first.position.P, distance.below/at/above, job.map.dense/sparse,
// job.shell.dense/sparse, job.map.top and job.shell.top (a copy of a map or a shell block at the top of its memory,
// made when aimed at), job.tag.top (a tag with its top bit set), job.points.max (a job of every shell word, each a
// hit). A configuration that cannot reach a bin (a distance bin on a 2-bit device, a position past
// the slot) gets random jobs in its place.
bool aimable_bin(const std::string& name);

struct GeneratedVectors {
  DeviceConfig config;
  DeviceMemory memory;
  std::vector<Job> jobs;
};

// Deterministic for a seed and options.
GeneratedVectors generate_vectors(const GenerateOptions& opt);

}  // namespace voxcd
