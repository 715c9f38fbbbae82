// Choosing the pipeline depth for a clock: the shallowest depth whose measured clock on the implementation target
// (the timing table, device/timing_table.h) is at least the clock asked for, among the rows measured at the device's
// LANES and BANKS (or those that stand in for them), and the latency that depth costs. docs/size.md, "Depth and
// target".
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "voxcd/host/device/timing_table.h"
#include "voxcd/ref/config.h"

namespace voxcd {

struct DepthChoice {
  std::string target;
  double clock_mhz = 0;              // the clock asked for
  TimingRow row;                     // the chosen depth's measurement
  std::vector<TimingRow> shallower;  // the shallower depths' measurements, deepest first: each misses the clock
  std::string table;                 // where the rows come from (TimingTable::where)
  // "" when the rows were measured at the device's LANES and BANKS; else the rows that stand in for them: "the
  // clocks of LANES 4, none measured at LANES 32".
  std::string stand_in;
  int depth() const { return row.depth; }
  // Why this depth: "depth 2: 263 MHz >= 250; depth 1: 201 MHz < 250; depth 0: 120 MHz < 250", then "; " and
  // stand_in when there is one.
  std::string why() const;
};

// The shallowest depth of `target` in `table` whose clock is at least clock_mhz, among the depths `base`'s device
// offers (those that DeviceConfig takes at base's other parameters), from the rows measured at base's LANES and
// BANKS; when the target has none that the device offers, from those of LANES 4 BANKS 0 (bench/timing.sh's default
// configuration), else from those of the target's first row's LANES and BANKS (the iCE40's LANES 1), named in
// stand_in. At a depth with rows of several configurations, the one nearest base (nearest_row). std::invalid_argument
// for a target that is not one of timing_targets() or a clock that is not a positive number; TimingTableError when
// the table has no row the device offers for the target; SizeError "clock" (size.h) when no depth meets the clock,
// naming the fastest depth.
DepthChoice choose_depth(const TimingTable& table, const std::string& target, double clock_mhz,
                         const DeviceConfig& base = {});
// The same for the default configuration among the depths for which `offered` is true.
DepthChoice choose_depth(const TimingTable& table, const std::string& target, double clock_mhz,
                         const std::function<bool(int)>& offered);

// The depth of a configuration (DeviceConfig::depth) and the configuration at another depth (ConfigError outside
// 0 .. kMaxDepth).
int depth_of(const DeviceConfig& cfg);
DeviceConfig at_depth(const DeviceConfig& cfg, int depth);

// Cycles from a one-point job's acceptance to its hit record on the output pins with an always-ready consumer: the
// queue register, the slot registers (ref/timing.h, pipeline_slots: with the depth's added stages) and the output
// register.
int latency_cycles(const DeviceConfig& cfg);

}  // namespace voxcd
