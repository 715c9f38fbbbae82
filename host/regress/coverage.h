// The merged coverage of a campaign (voxcd regress --coverage DIR, docs/verification.md "Coverage"): the counts the
// coverage models wrote (Verilator's coverage data, one file a shard) merged with verilator_coverage, written as lcov
// and as HTML (genhtml), and summed into line, branch, toggle and functional coverage with the waivers applied.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/error.h"

namespace voxcd {

// Coverage data that cannot be read or merged; the message names the file.
struct CoverageError : Error {
  using Error::Error;
};

// Points of one kind: hit, not hit but waived (rtl/coverage.waivers gives each its reason), and missed.
struct CoverageCount {
  uint64_t hit = 0, waived = 0, missed = 0;
  // hit / (hit + missed), in percent (100 with no point).
  double percent() const;
};

struct CoverageReport {
  std::string dir;
  std::map<std::string, CoverageCount> kinds;  // "line", "branch", "toggle", "functional"
  // File (rtl/'s name) -> kind -> count; functional bins of the stimulus are under "stimulus".
  std::map<std::string, std::map<std::string, CoverageCount>> files;
  // Every functional bin and its count: the RTL's cover properties by their place in the device ("u_hit_stage.CoverFullSlot",
  // "g_banks.u_shared_banks.u_table_rounds.CoverSlotReadInTwoRounds") and the stimulus bins (regress/stimulus_bins.h).
  std::map<std::string, uint64_t> bins;
  std::vector<std::string> empty_bins;     // not hit and not waived
  std::vector<std::string> missed_points;  // "file:line kind what" of every code point missed (not waived)
  std::vector<std::string> stale_waivers;  // waivers that match no point: "file:line: the waiver"
  std::vector<std::string> notes;          // what could not be made (the HTML report without genhtml)
  uint64_t data_files = 0;                 // coverage data files merged
  std::string text() const;
};

// Merges every *.dat and *.bins file of `dir` (the shards' counts; any other coverage data written there, such as the
// AXI top's, too) into dir/merged.dat, dir/coverage.info (lcov) and dir/html/ (genhtml), applies the waivers of the
// file `waivers`, and writes dir/bins.txt (every functional bin and its count) and dir/summary.txt (text()).
// CoverageError for a directory without coverage data, a waiver file that does not parse (its line), or a
// verilator_coverage that fails.
CoverageReport merge_coverage(const std::string& dir, const std::string& waivers);

// The empty bins of a report's bins.txt that a template aims at (aimable_bin of ref/vector_gen.h), in its order:
// the holes coverage-directed stimulus goes for. CoverageError naming the file when it cannot be read.
std::vector<std::string> aimable_holes(const std::string& bins_txt);

}  // namespace voxcd
