// The table of a sweep (`voxcd sweep`, docs/sweep.md): its rows in point order, the Pareto front marked, and the
// table as text, CSV and JSON. The same rows give the same table, whatever ran them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "voxcd/host/sizing/sweep/sweep.h"

namespace voxcd {

// Per point (each minimised coordinate: contact error, cycles, memory), whether no other point is at least as
// good in every coordinate and better in one. Equal points are all on the front.
std::vector<bool> pareto_front(const std::vector<std::array<double, 3>>& points);

struct SweepTable {
  SweepSpec spec;
  double clock = 0;       // MHz
  uint64_t frames = 0;    // measured per point
  std::vector<SweepRow> rows;  // sorted by point index, Pareto flags set
  int ranks = 1;          // timing: not part of the table
  double seconds = 0;
  uint64_t from_file = 0;  // rows read back from the results file
};

// Sorts the rows by point index and marks the front over the feasible rows in (contact_bound, max_cycles,
// memory_bits).
void finish_table(SweepTable& t);

// The CSV (a header line, one line per row; no timing), the JSON document (the sweep, the clock and where it comes
// from, the rows with their timing under "timing") and the text table.
std::string sweep_csv(const SweepTable& t);
std::string sweep_table_json(const SweepTable& t);
std::string sweep_text(const SweepTable& t);

}  // namespace voxcd
