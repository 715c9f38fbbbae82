#include "voxcd/host/sizing/block_rams.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

namespace voxcd {

namespace {

int log2_of(int v) {
  int l = 0;
  while ((1 << (l + 1)) <= v) ++l;
  return l;
}

// One aspect ratio of a block RAM: depth x width, and what one block counts for.
struct Aspect {
  uint64_t words;
  int width;
  double cost;
};

// Simple dual-port shapes (one write port, one read port, as voxcd_ram); with two read ports (voxcd_ram2) a 7-series
// block is true dual-port, whose ports are at most 36 bits wide (18 on a RAMB18).
const std::vector<Aspect>& aspects(const std::string& target, int read_ports) {
  static const std::vector<Aspect> xilinx = {
      {32768, 1, 1}, {16384, 2, 1}, {8192, 4, 1}, {4096, 9, 1}, {2048, 18, 1}, {1024, 36, 1}, {512, 72, 1},
      {16384, 1, 0.5}, {8192, 2, 0.5}, {4096, 4, 0.5}, {2048, 9, 0.5}, {1024, 18, 0.5}, {512, 36, 0.5}};
  static const std::vector<Aspect> xilinx_tdp = {
      {32768, 1, 1}, {16384, 2, 1}, {8192, 4, 1}, {4096, 9, 1}, {2048, 18, 1}, {1024, 36, 1},
      {16384, 1, 0.5}, {8192, 2, 0.5}, {4096, 4, 0.5}, {2048, 9, 0.5}, {1024, 18, 0.5}};
  static const std::vector<Aspect> ice40 = {{256, 16, 1}, {512, 8, 1}, {1024, 4, 1}, {2048, 2, 1}};
  if (target != "xilinx-7") return ice40;
  return read_ports > 1 ? xilinx_tdp : xilinx;
}

}  // namespace

double memory_blocks(const MemoryShape& m, const std::string& target) {
  if (target != "xilinx-7" && target != "ice40-hx8k" && target != "ice40-up5k")
    throw std::invalid_argument("target '" + target + "' has no block RAMs that voxcd counts");
  double best = std::numeric_limits<double>::infinity();
  for (const Aspect& a : aspects(target, m.read_ports)) {
    const uint64_t rows = (m.words + a.words - 1) / a.words;
    const uint64_t cols = (uint64_t(m.width) + uint64_t(a.width) - 1) / uint64_t(a.width);
    best = std::min(best, double(rows * cols) * a.cost);
  }
  // An iCE40 block has one read port: a memory read at two ports is two copies.
  return target == "xilinx-7" ? best : best * m.read_ports;
}

std::vector<MemoryShape> memory_shapes(const DeviceConfig& cfg) {
  std::vector<MemoryShape> m;
  m.push_back({"shell bank", cfg.shell_depth() >> log2_of(cfg.LANES), 3 * cfg.PW, cfg.LANES});
  if (cfg.banked())
    m.push_back({"voxmap bank", cfg.map_depth() >> log2_of(cfg.BANKS), cfg.MEMW, cfg.BANKS});
  else if (cfg.distance())
    m.push_back({"voxmap parity bank", uint64_t{1} << (cfg.MAW > 3 ? cfg.MAW - 3 : 1), cfg.MEMW, 8 * cfg.LANES});
  else
    m.push_back({"voxmap copy", cfg.map_depth(), cfg.MEMW, cfg.LANES});
  m.back().read_ports = cfg.sparse() ? 2 : 1;  // the table port and the brick port
  return m;
}

BlockRams block_rams(const DeviceConfig& cfg, const std::string& target) {
  BlockRams b;
  if (target == "asic-osu018") {
    b.unit = "SRAM macros";
    for (const MemoryShape& m : memory_shapes(cfg)) b.count += m.count;
    return b;
  }
  if (target == "xilinx-7")
    b.unit = "RAMB36";
  else if (target == "ice40-hx8k" || target == "ice40-up5k")
    b.unit = "SB_RAM40_4K (4 kbit)", b.available = target == "ice40-hx8k" ? 32 : 30;
  else
    throw std::invalid_argument("target '" + target + "' has no block RAMs that voxcd counts");
  for (const MemoryShape& m : memory_shapes(cfg)) b.count += m.count * memory_blocks(m, target);
  return b;
}

}  // namespace voxcd
