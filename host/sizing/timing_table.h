// The timing table: the largest clock and the area of each pipeline depth on each implementation target, as the
// timing tools measured them (bench/timing.sh writes host/sizing/timing.tsv, which is compiled into the library and
// installed as share/voxcd/timing.tsv; docs/hardware.md, "Timing and area per depth", has the same figures).
// `voxcd size --target` chooses a depth from it (depth.h).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxcd {

// A timing table that cannot be used; the message starts with "FILE:LINE: " (or "FILE: ") and names the column.
struct TimingTableError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The targets a table may name, in the order reports list them: "asic-osu018", "ice40-hx8k", "ice40-up5k",
// "xilinx-7".
const std::vector<std::string>& timing_targets();

// One measured (target, depth): the configuration the tools implemented and what they found.
struct TimingRow {
  std::string target;
  int depth = 0;
  double mhz = 0;            // the largest clock
  std::string source;        // how mhz was found: "OpenSTA, OSU 0.18 um", "nextpnr-ice40, ...", "estimate: ..."
  int lanes = 0;             // the implemented configuration's LANES
  std::optional<double> area_mm2;       // standard-cell area (ASIC targets)
  std::optional<double> luts, ffs, dsps, brams;  // LUTs or logic cells, flip-flops, DSP blocks, block RAMs / macros
  std::optional<int> lut_levels;        // LUT levels on the longest path (FPGA synthesis)
  std::string config;        // the implemented configuration (DeviceConfig text, its depth apart)
  int line = 0;              // where in the table
  bool estimate() const { return source.rfind("estimate", 0) == 0; }
};

struct TimingTable {
  std::string where;  // the file, or "host/sizing/timing.tsv (built in)"
  std::vector<TimingRow> rows;
  // The target's rows by ascending depth (empty when the table has none).
  std::vector<TimingRow> target_rows(const std::string& target) const;
};

// Parses a table: '#' lines are comments; the first other line is the header, exactly the columns
// "target depth mhz source lanes area_mm2 luts ffs dsps brams lut_levels config" separated by tabs; every row the
// same columns, "-" for a figure the target does not have. TimingTableError for a missing or unknown column, a
// target not in timing_targets(), a depth that is not a whole number from 0, a clock that is not a positive number,
// a figure that is neither "-" nor a number >= 0, a (target, depth) given twice, or a table with no row.
TimingTable parse_timing_table(const std::string& text, const std::string& where);
// The same for a file; TimingTableError "<path>: cannot read" when it cannot be read.
TimingTable read_timing_table(const std::string& path);
// The table compiled into the library (host/sizing/timing.tsv as bench/timing.sh last wrote it).
const TimingTable& builtin_timing_table();

}  // namespace voxcd
