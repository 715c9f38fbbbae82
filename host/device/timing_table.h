// The timing table: the largest clock and the area of each pipeline depth of each measured configuration on each
// implementation target, as the timing tools measured them (bench/timing.sh merges its rows into
// host/device/timing.tsv, which is compiled into the library and installed as share/voxcd/timing.tsv;
// docs/hardware.md, "Timing and area per depth", has the same figures). Every modelled rate's default clock comes from
// its asic-osu018 rows (clock.h, clock_for), and `voxcd size --target` chooses a depth from it (sizing/depth.h).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/error.h"

namespace voxcd {

// A timing table that cannot be used; the message starts with "FILE:LINE: " (or "FILE: ") and names the column.
struct TimingTableError : Error {
  using Error::Error;
};

// The targets a table may name, in the order reports list them: "asic-osu018", "ice40-hx8k", "ice40-up5k",
// "xilinx-7".
const std::vector<std::string>& timing_targets();

// One measured (target, configuration, depth): the configuration the tools implemented and what they found.
struct TimingRow {
  std::string target;
  int depth = 0;
  double mhz = 0;            // the largest clock
  std::string source;        // how mhz was found: "OpenSTA, OSU 0.18 um", "nextpnr-ice40, ...", "estimate: ..."
  int lanes = 0;             // the implemented configuration's LANES (the config column's)
  std::optional<double> area_mm2;       // standard-cell area (ASIC targets)
  std::optional<double> luts, ffs, dsps, brams;  // LUTs or logic cells, flip-flops, DSP blocks, block RAMs / macros
  std::optional<int> lut_levels;        // LUT levels on the longest path (FPGA synthesis)
  std::string config;        // the implemented configuration (DeviceConfig text, its depth apart), as written
  DeviceConfig device;       // config parsed, at `depth`
  int line = 0;              // where in the table
  bool estimate() const { return source.rfind("estimate", 0) == 0; }
};

struct TimingTable {
  std::string where;  // the file, or "host/device/timing.tsv (built in)"
  std::vector<TimingRow> rows;
  // The target's rows by ascending depth, in table order within a depth (empty when the table has none).
  std::vector<TimingRow> target_rows(const std::string& target) const;
};

// Parses a table: '#' lines are comments; the first other line is the header, exactly the columns
// "target depth mhz source lanes area_mm2 luts ffs dsps brams lut_levels config" separated by tabs; every row the
// same columns, "-" for a figure the target does not have. A target may have rows of several configurations (each
// bench/timing.sh --config run adds its own). TimingTableError for a missing or unknown column, a target not in
// timing_targets(), a depth that is not a whole number from 0, a clock that is not a positive number, a figure that is
// neither "-" nor a number >= 0, a config that is no DeviceConfig text (parse_config_pairs) or names a DEPTH other
// than the depth column's, a lanes column other than the config's LANES, a (target, configuration, depth) given
// twice, or a table with no row.
TimingTable parse_timing_table(const std::string& text, const std::string& where);
// The same for a file; TimingTableError "<path>: cannot read" when it cannot be read.
TimingTable read_timing_table(const std::string& path);
// The table compiled into the library (host/device/timing.tsv as bench/timing.sh last wrote it).
const TimingTable& builtin_timing_table();

// Whether a row measured for `measured` stands for `cfg`: the same logic, every parameter equal (each width, LANES,
// BANKS, depth, SB, WB on a distance device, BL) but the memory depths SAW and MAW, which the flows model as SRAM
// macros of a stated access time (docs/hardware.md, "The default clock").
bool same_logic(const DeviceConfig& measured, const DeviceConfig& cfg);

// The row of `target` that stands for cfg (same_logic), else the one nearest it: at cfg's depth before another depth,
// then at cfg's LANES, then at its BANKS, then at its other parameters, then the default configuration's; table order
// on a tie. nullptr when the table has no row of the target.
const TimingRow* nearest_row(const TimingTable& table, const std::string& target, const DeviceConfig& cfg);
// Whether a configuration measured as `a` is nearer cfg than one measured as `b`, as nearest_row weighs them (the
// energy table's rows are chosen the same way, sizing/energy_table.h).
bool nearer(const DeviceConfig& a, const DeviceConfig& b, const DeviceConfig& cfg);

// A configuration's logic in brief, as the clocks' sources name it: "LANES 4 DEPTH 0", then each other parameter in
// which cfg differs from the default configuration, in DeviceConfig::to_string's order, SAW and MAW never ("LANES 32
// DEPTH 0 SB 8 BANKS 4").
std::string logic_text(const DeviceConfig& cfg);
// The parameters in which cfg differs from `from` in the same form, SAW and MAW never ("LANES 32"; "" for none).
std::string logic_difference(const DeviceConfig& cfg, const DeviceConfig& from);

}  // namespace voxcd
