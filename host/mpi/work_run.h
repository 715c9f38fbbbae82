// Numbered work items over the ranks of a World (campaign_run.h runs a campaign's shards with it): rank 0 hands out items
// one at a time, runs items itself on a second thread, and takes every result (one line of text) on its own
// thread, in the order they finish; the other ranks run what they are given and send each result back. A rank that
// fails or says nothing within the timeout ends every rank with an error naming it and its item. `voxcd sweep` runs
// its points with it, `voxcd regress` its shards.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <string>

#include "voxcd/host/mpi/world.h"

namespace voxcd::mpi {

// Runs one item and gives its result as one line (it may throw: the run ends naming the rank and the item).
using RunItem = std::function<std::string(uint64_t item)>;

struct WorkPlan {
  std::string setup;             // sent to every other rank before any item (what make_runner is given there)
  std::deque<uint64_t> todo;     // the items, in the order they are handed out
  std::function<std::string(uint64_t)> describe;  // "point 7 (lanes 2, ...)", for errors
  std::string resume_hint;       // appended to a fault's message ("every point finished before is in ...")
  std::string unknown = "an item";  // names the item in a fault when none is known
  double timeout = 600;          // seconds a rank may take over one item
  uint64_t stop_after = 0;       // hand out at most this many items now (0 = all)
};

// Rank 0: runs the plan's items (run here, the other ranks' runners there) and calls finished(item, line, rank) on
// this thread for each result as it arrives. Returns the number of items left undone (stop_after). A fault prints
// "voxcd: error: ..." with the rank and its item and ends every rank (exit code 2).
uint64_t coordinate_work(World& w, const WorkPlan& plan, const RunItem& run,
                         const std::function<void(uint64_t, const std::string&, int)>& finished);
// Rank 0, when it has nothing to hand out (bad input): tells the other ranks to end.
void release_work(World& w);
// Ranks other than 0: makes a runner from rank 0's setup and runs the items it sends until it says stop.
void serve_work(World& w, const std::function<RunItem(const std::string& setup)>& make_runner);

}  // namespace voxcd::mpi
