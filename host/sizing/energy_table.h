// The energy table: the measured energy per lookup of a synthesised configuration at a depth on each scene's stimulus,
// as bench/energy.sh measured it (host/sizing/energy.tsv, compiled into the library and installed as
// share/voxcd/energy.tsv; docs/hardware.md, "Energy per lookup", says what is measured and what is estimated), and
// the energy per lookup it gives a configuration: measured for one of the same logic, else an estimate from the
// nearest row that says so (chosen as clock_for chooses a timing row). `voxcd size` reports a frame's energy and the
// power at the requested rate from it (size.h).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/error.h"

namespace voxcd {

// An energy table that cannot be used; the message starts with "FILE:LINE: " (or "FILE: ") and names the column.
struct EnergyTableError : Error {
  using Error::Error;
};

// One measured (target, configuration, depth, scene): the figures `voxcd size` uses (the table has more columns).
struct EnergyRow {
  std::string target;     // a timing target (timing_table.h), "asic-osu018"
  int depth = 0;
  double mhz = 0;         // the clock the energy was measured at
  std::string scene;      // the stimulus: "simulate" (voxcd simulate's built-in scene), "room", "tori"
  double lookups = 0;     // the run's lookups
  double pj_per_lookup = 0;  // measured logic power x run time + the SRAM estimate, over the lookups
  double logic_pj = 0, sram_pj = 0;                // its parts
  double pj_45nm = 0, pj_16nm = 0, pj_7nm = 0;     // projections (Stillmaker and Baas 2017), not measurements
  std::string config;     // the synthesised configuration (DeviceConfig text, its depth apart), as written
  DeviceConfig device;    // config parsed, at `depth`
  int line = 0;           // where in the table
};

struct EnergyTable {
  std::string where;  // the file, or "host/sizing/energy.tsv (built in)"
  std::vector<EnergyRow> rows;
};

// Parses a table: '#' lines are comments; the first other line is the header, exactly bench/energy.sh's columns
// "target depth mhz scene cycles lookups jobs pairs internal_mw switching_mw leakage_mw logic_mw sram_nj
// pj_per_lookup logic_pj sram_pj nj_per_pair leakage_share pj_45nm pj_16nm pj_7nm config" separated by tabs; every
// row the same columns. EnergyTableError for a missing or unknown column, a target not in timing_targets(), a depth
// that is not a whole number from 0, a figure that is not a number >= 0 (a clock, lookups or energy per lookup of 0),
// an empty scene, a config that is no DeviceConfig text or names a DEPTH other than the depth column's, a (target,
// configuration, depth, scene) given twice, or a table with no row.
EnergyTable parse_energy_table(const std::string& text, const std::string& where);
// The same for a file; EnergyTableError "<path>: cannot read" when it cannot be read.
EnergyTable read_energy_table(const std::string& path);
// The table compiled into the library (host/sizing/energy.tsv as bench/energy.sh last wrote it).
const EnergyTable& builtin_energy_table();

// The scene whose rows give a configuration its energy: the built-in scene of `voxcd simulate`, the stimulus that is
// a simulated scene's frames as `voxcd size` measures them (room and tori are a robot's and two bodies' workloads).
inline constexpr const char* kEnergyScene = "simulate";

// The energy per lookup a configuration is given, with where it comes from.
struct LookupEnergy {
  double pj = 0;      // at 0.18 um, the table's pj_per_lookup
  double pj_7nm = 0;  // its 7 nm projection
  // "measured for LANES 4 DEPTH 0 (simulate scene), docs/hardware.md", or "estimate: 581.02 pJ a lookup measured
  // for LANES 4 DEPTH 0 (simulate scene), not for LANES 2 PW 16 ..., docs/hardware.md" (what differs, as clock_for
  // names it).
  std::string source;
  bool estimate = false;  // true when the row is of other logic than the configuration's
};

// The energy per lookup of cfg from `table`'s rows of kEnergyScene on asic-osu018: the row of the same logic
// (same_logic: SAW and MAW aside, the depth too), else the nearest (timing_table.h's nearer, table order on a tie),
// an estimate. EnergyTableError when the table has no such row.
LookupEnergy lookup_energy(const DeviceConfig& cfg, const EnergyTable& table);
// The same from builtin_energy_table().
LookupEnergy lookup_energy(const DeviceConfig& cfg);

}  // namespace voxcd
