// The memories of a configuration as the RTL builds them (one shell bank per lane; a voxmap copy per lane, 8 parity
// banks per lane on a distance device, or BANKS shared banks), and how many block RAMs each implementation target
// needs for them: 7-series RAMB36 (a RAMB18 is a half), iCE40 SB_RAM40_4K, or one SRAM macro per memory on an
// ASIC. Counted from the shapes: each memory takes the fewest blocks of any one aspect ratio of the block.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"

namespace voxcd {

struct MemoryShape {
  std::string what;    // "shell bank", "voxmap copy", "voxmap parity bank", "voxmap bank"
  uint64_t words = 0;  // depth
  int width = 0;       // bits per word
  int count = 0;       // how many the device has
};
std::vector<MemoryShape> memory_shapes(const DeviceConfig& cfg);

struct BlockRams {
  double count = 0;
  std::string unit;   // "RAMB36", "SB_RAM40_4K (4 kbit)", "SRAM macros"
  int available = 0;  // what the target's part has (iCE40 HX8K 32, UP5K 30); 0: no fixed part
};
// For one of timing_targets() (timing_table.h); std::invalid_argument for another.
BlockRams block_rams(const DeviceConfig& cfg, const std::string& target);

}  // namespace voxcd
