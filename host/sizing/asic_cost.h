// The standard-cell area of a configuration at 0.18 um (voxcd size --cost with a target): yosys maps voxcd_device
// onto the OSU 0.18 um cells (Debian qflow-tech-osu018) as bench/timing.sh does, adders as Kogge-Stone prefixes
// (host/sizing/kogge_stone.v), ABC sizing and buffering for the clock, but without that script's buffer trees on
// register outputs and without static timing; the RAMs are black boxes (SRAM macros), not in the area.
// docs/size.md, "Depth and target".
#pragma once

#include <string>

#include "voxcd/ref/config.h"

namespace voxcd {

// The liberty file of the OSU 0.18 um standard cells that Debian's qflow-tech-osu018 installs.
inline constexpr const char* kOsu018Liberty = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";

struct AsicCost {
  double area_mm2 = 0;   // standard cells, from the liberty file's cell areas
  uint64_t cells = 0;    // standard cells
  uint64_t flip_flops = 0;
  double clock_mhz = 0;  // the clock ABC mapped for
  double seconds = 0;
  std::string version, command;
};

// Synthesises cfg (every parameter by chparam, its depth included) from rtl_dir's voxcd.f ("" = the package's) for
// clock_mhz. std::runtime_error when the liberty file is missing (naming the Debian package), or yosys is missing
// or fails.
AsicCost asic_cost(const DeviceConfig& cfg, double clock_mhz, const std::string& rtl_dir = "");

// The ASIC flows' techmap of yosys's carry unit ($lcu) into a Kogge-Stone prefix: host/sizing/kogge_stone.v, as the
// library has it compiled in.
const char* kogge_stone_map();
// The yosys commands of `synth -flatten` with that map in its techmap step (bench/timing.sh runs the same), for a
// design read, with its parameters set, whose top is voxcd_device.
std::string asic_synth_commands();

}  // namespace voxcd
