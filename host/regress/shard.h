// One shard of a campaign: generate the vectors of (seed, configuration, lanes) in memory, run them on the shard's
// backend and compare with ref/'s expectations; and the command that does the same on one machine.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "voxcd/host/regress/campaign.h"

namespace voxcd {

struct ShardResult {
  uint64_t shard = 0;
  uint64_t jobs = 0, lookups = 0;
  uint64_t records = 0;    // records in the backend's stream
  bool cycles = false;     // cycles were compared
  std::string error;       // "" when the backend's stream equals ref/'s, else the first difference or why not run
  bool differs = false;    // the streams were compared and differ: job and tag are the first differing job
  uint64_t job = 0;
  uint32_t tag = 0;
  int rank = 0;            // informative: the rank that ran it
  double seconds = 0;      // informative: its wall time
  bool ok() const { return error.empty(); }
};

// How a rank runs its shards: the cpu backend's threads (0 = one per hardware thread); and, when coverage is a directory,
// the rtl backend on the coverage models, each shard writing its counts there (<campaign digest>-shard-<index>.dat)
// beside the stimulus bins of its vectors (the same name, .bins; docs/verification.md).
struct ShardOptions {
  unsigned threads = 1;
  std::string coverage;
};

// The vectors of the last (seed, configuration, lanes) a rank generated, kept for the next shard on another backend.
class ShardVectors {
 public:
  ShardVectors();
  ~ShardVectors();
  ShardVectors(const ShardVectors&) = delete;
  ShardVectors& operator=(const ShardVectors&) = delete;
  struct Cached;

 private:
  friend ShardResult run_shard(const Campaign& c, const Shard& s, ShardVectors& cache, const ShardOptions& opt);
  std::unique_ptr<Cached> cached_;
};


// Runs shard s of c. Never throws for what the backend does (its error is the result's); std::exception for what
// should not happen, and for the faults of the test build's testing hook (regress/testing_fault.h).
ShardResult run_shard(const Campaign& c, const Shard& s, ShardVectors& cache, const ShardOptions& opt);

// The one-line shell command that reproduces shard s on one machine with `program` (the voxcd tool's path):
// generate its vectors into `vec_file`, then run them on its backend and lanes (with --cycles if c has it).
std::string reproduce_command(const Campaign& c, const Shard& s, const std::string& program,
                              const std::string& vec_file);
// The vector file name reproduce_command uses in reports: regress-<seed>-c<config index>-l<lanes>.vec.
std::string reproduce_file_name(const Campaign& c, const Shard& s);

}  // namespace voxcd
