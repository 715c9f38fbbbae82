// The results file of a campaign (docs/regress.md, "Results file"): JSON lines, a header naming the campaign, then
// one line per finished shard, each flushed and fsync'd before the next shard is counted, so that a campaign
// stopped at any point resumes where it was.
#pragma once

#include <string>
#include <vector>

#include "voxcd/host/regress/campaign.h"
#include "voxcd/host/regress/journal.h"
#include "voxcd/host/regress/shard.h"

namespace voxcd {

// A shard's result as one line of JSON (no newline): the results file's line and the message between ranks.
std::string shard_result_line(const ShardResult& r, const Shard& s);
// Parses shard_result_line's form and checks it names shard r.shard of c as shard_at does; CampaignError starting
// with `where` otherwise.
ShardResult parse_shard_result(const std::string& line, const Campaign& c, const std::string& where);

class ResultsFile {
 public:
  // Opens `path` for campaign c: a missing or empty file gets the header; an existing one must hold c's header
  // (CampaignError naming the file and both campaigns otherwise) and its finished shards are read back. A last line
  // without its newline (a writer stopped mid-line) is cut off and its shard runs again; a malformed complete line
  // is a CampaignError naming its line. A shard written twice counts once.
  ResultsFile(const std::string& path, const Campaign& c);

  // The shards the file held when opened, each once, in file order.
  const std::vector<ShardResult>& finished() const { return finished_; }
  // Appends r's line, then flushes it to the disk (fsync); std::runtime_error naming the file when it cannot.
  void append(const ShardResult& r, const Shard& s);

 private:
  Journal journal_;
  std::vector<ShardResult> finished_;
};

}  // namespace voxcd
