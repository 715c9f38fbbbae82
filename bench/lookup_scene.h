// The lookup workload of bench_device and bench_kernel: a shell of random points over a cube, a pose (a rotation of
// 30 degrees about z, scaled per axis onto the map's extent, so the points spread over the whole map) and a map of
// random words: about a quarter surface voxels, or random node values on a distance map (SB > 2). Uses ref/ alone,
// so that bench/kernel_revisions.sh can build it against any revision's ref/.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>

#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd::bench {

inline void lookup_scene(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz, size_t points, uint64_t seed,
                         DeviceMemory& mem, Job& job) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double span = std::max({nx, ny, nz});
  mem.shell.clear();
  for (size_t k = 0; k < points; ++k) {
    const double p[3] = {span * u(rng), span * u(rng), span * u(rng)};
    mem.shell.push_back(quantize_point(cfg, p, "p"));
  }
  job = Job{};
  job.mode = Mode::Count;
  job.shell_count = uint32_t(points);
  job.nx = nx, job.ny = ny, job.nz = nz;
  FloatPose pose;
  const double c = std::cos(0.5236), sn = std::sin(0.5236);
  const double sx = nx / span / 1.4, sy = ny / span / 1.4, sz = nz / span;
  pose.M[0][0] = c * sx, pose.M[0][1] = -sn * sx, pose.M[0][2] = 0;
  pose.M[1][0] = sn * sy, pose.M[1][1] = c * sy, pose.M[1][2] = 0;
  pose.M[2][0] = 0, pose.M[2][1] = 0, pose.M[2][2] = sz * 0.999;
  pose.t[0] = nx * 0.3, pose.t[1] = ny * 0.05, pose.t[2] = 0;
  quantize_pose(cfg, pose, job);
  mem.map.resize(map_words(cfg, job));
  for (auto& w : mem.map) w = cfg.distance() ? rng() : (rng() & 0x5555555555555555ull & rng());
}

}  // namespace voxcd::bench
