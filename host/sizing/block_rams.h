// The memories of a configuration as the RTL builds them (one shell bank per lane; a voxmap copy per lane, 8 parity
// banks per lane on a distance device, or BANKS shared banks), and how many block RAMs each implementation target
// needs for them: 7-series RAMB36 (a RAMB18 is a half), iCE40 SB_RAM40_4K, or one SRAM macro per memory on an
// ASIC. Counted from the shapes: each memory takes the fewest blocks of any one aspect ratio of the block. A sparse
// device's voxmap memories have two read ports (voxcd_ram2: the table port and the brick port): on a 7-series part a
// true dual-port block (ports at most 36 bits wide), on an iCE40, whose blocks have one read port, a copy per port.
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
  int read_ports = 1;  // 2: a sparse device's voxmap memory (voxcd_ram2)
  uint64_t bits() const { return words * uint64_t(width) * uint64_t(count); }
};
std::vector<MemoryShape> memory_shapes(const DeviceConfig& cfg);

struct BlockRams {
  double count = 0;
  std::string unit;   // "RAMB36", "SB_RAM40_4K (4 kbit)", "SRAM macros"
  int available = 0;  // what the target's part has (iCE40 HX8K 32, UP5K 30); 0: no fixed part
};
// For one of timing_targets() (device/timing_table.h); std::invalid_argument for another.
BlockRams block_rams(const DeviceConfig& cfg, const std::string& target);
// The blocks one memory of that shape takes (m.count of them take count times as many), on "xilinx-7" or an iCE40
// target; std::invalid_argument for another.
double memory_blocks(const MemoryShape& m, const std::string& target);

}  // namespace voxcd
