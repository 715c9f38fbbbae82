// The merged report of a campaign: every shard counted once, whichever rank ran it and whether it ran now or in an
// earlier run of the same results file; as text and as JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/host/regress/campaign.h"
#include "voxcd/host/regress/shard.h"

namespace voxcd {

class Report {
 public:
  explicit Report(const Campaign& c);
  // Counts r once (false, and nothing counted, when its shard is already in); `earlier`: from the results file.
  bool add(const ShardResult& r, bool earlier);
  bool has(uint64_t shard) const { return done_[shard]; }
  uint64_t failures() const { return failures_.size(); }
  bool complete() const { return shards_done_ == campaign_.shards(); }
  const Campaign& campaign() const { return campaign_; }

  int ranks = 1;         // ranks of this run
  double seconds = 0;    // wall time of this run
  std::string stopped;   // why this run ended before the campaign did ("" = it did not)
  uint64_t bytes_between_ranks = 0;  // payload bytes of every message of this run

  // The report as text; `program` is the voxcd tool's path for the reproduce commands.
  std::string text(const std::string& program) const;
  // The same as one JSON object (docs/regress.md, "Report").
  std::string json(const std::string& program) const;

 private:
  Campaign campaign_;
  std::vector<bool> done_;
  uint64_t shards_done_ = 0, from_file_ = 0, jobs_ = 0, lookups_ = 0, records_ = 0;
  std::vector<ShardResult> failures_;  // sorted by shard when reported
  std::vector<ShardResult> sorted_failures() const;
};

}  // namespace voxcd
