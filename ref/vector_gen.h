// Random conformance vectors with hard cases mixed in: voxel faces, -1/4 voxel, exact +-1 matrix entries, quarter
// and half turns, far and aliasing translations, full-range fields, 1x1x1 and odd-sized maps, maps mid-memory,
// empty shells, every mode and every hit mask. Expectations come from ref/ (the caller runs them).
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

struct GenerateOptions {
  uint64_t seed = 1;
  size_t jobs = 200;
  size_t cloud_points = 2000;  // size of the random point cloud block of the shell memory
  DeviceConfig config{};
};

struct GeneratedVectors {
  DeviceConfig config;
  DeviceMemory memory;
  std::vector<Job> jobs;
};

// Deterministic for a seed and options.
GeneratedVectors generate_vectors(const GenerateOptions& opt);

}  // namespace voxcd
