// The results file of a sweep (docs/sweep.md, "Resume"): JSON lines, a header naming the sweep, then one row per
// finished point, each flushed and fsync'd before the next point is counted, so that a sweep stopped or killed at
// any point resumes without running a finished point again.
#pragma once

#include <string>
#include <vector>

#include "voxcd/host/regress/journal.h"
#include "voxcd/host/sizing/sweep/sweep.h"

namespace voxcd {

class SweepResults {
 public:
  // Opens `path` for sweep s: a missing or empty file gets the header; an existing one must hold s's header
  // (SweepError naming the file and both sweeps otherwise) and its rows are read back. A last line without its
  // newline (a writer stopped mid-line) is cut off and its point runs again; a malformed complete line, or a row
  // that is not the point of s it names, is a SweepError naming its line. A point written twice counts once.
  SweepResults(const std::string& path, const SweepSpec& s);

  // The rows the file held when opened, each point once, in file order.
  const std::vector<SweepRow>& finished() const { return finished_; }
  // Appends the row's line and flushes it to the disk (fsync); std::runtime_error naming the file when it cannot.
  void append(const SweepRow& r);

 private:
  Journal journal_;
  std::vector<SweepRow> finished_;
};

}  // namespace voxcd
