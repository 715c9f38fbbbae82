// A campaign over the ranks of a World: rank 0 hands out shards one at a time, runs shards itself on a second
// thread, writes every finished shard to the results file (the one writer) and merges the report; the other ranks
// run what they are given and send each result back as one JSON line.
#pragma once

#include <cstdint>
#include <string>

#include "voxcd/host/mpi/world.h"
#include "voxcd/host/regress/shard.h"
#include "voxcd/host/regress/campaign.h"
#include "voxcd/host/regress/report.h"

namespace voxcd::mpi {

struct RunOptions {
  std::string results;     // the results file ("" = none: nothing resumes)
  double timeout = 600;    // seconds a rank may take over one shard before the run ends with an error
  uint64_t stop_after = 0; // run at most this many shards now (0 = all)
  unsigned threads = 1;    // cpu backend threads per rank
  std::string coverage;    // rtl: the coverage models, each shard's counts into this directory (ShardOptions)
  ShardOptions shard() const { return {threads, coverage}; }
};

// Rank 0: runs campaign c (the shards the results file does not hold yet) and returns the merged report. A rank
// that fails or says nothing for opt.timeout seconds ends every rank with an error on stderr naming it and its
// shard (exit code 2); everything finished before is in the results file. CampaignError or std::runtime_error for
// a results file that cannot be used (the other ranks are released first).
Report coordinate(World& w, const Campaign& c, const RunOptions& opt);
// Rank 0, when it has no campaign to give (a bad campaign): tells the other ranks to end.
void release_workers(World& w);
// Ranks other than 0: runs the shards rank 0 sends until it says stop.
void serve(World& w, const ShardOptions& opt);

}  // namespace voxcd::mpi
