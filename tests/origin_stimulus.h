// A stimulus whose result is known whatever the device's widths, shared by the rtl and SystemC fault suites.
#pragma once

#include <cstddef>
#include <cstdint>

#include "voxcd/ref/pipeline.h"

namespace voxcd::test {

// `points` shell points at the origin and a 4x4x4 voxmap of surface voxels: with M = 0 and t = 0 every point of a
// job hits voxel (0, 0, 0), whatever the widths.
inline DeviceMemory origin_memory(const DeviceConfig& cfg, size_t points) {
  DeviceMemory m;
  m.shell.assign(points, ShellWord{});
  const uint64_t per_word = uint64_t(cfg.MEMW) / 2;
  const uint64_t surface = cfg.MEMW == 64 ? 0x5555555555555555ull : 0x5555555555555555ull & ((1ull << cfg.MEMW) - 1);
  m.map.assign((64 + per_word - 1) / per_word, surface);
  return m;
}

inline Job origin_job(uint32_t tag, Mode mode, uint32_t count) {
  Job j;
  j.tag = tag;
  j.mode = mode;
  j.shell_count = count;
  j.nx = j.ny = j.nz = 4;
  return j;
}

}  // namespace voxcd::test
