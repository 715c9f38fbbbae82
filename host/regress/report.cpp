#include "voxcd/host/regress/report.h"

#include <algorithm>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxcd/host/regress/detail/shard_json.h"

namespace voxcd {

Report::Report(const Campaign& c) : campaign_(c), done_(c.shards(), false) {}

bool Report::add(const ShardResult& r, bool earlier) {
  if (r.shard >= done_.size() || done_[r.shard]) return false;
  done_[r.shard] = true;
  ++shards_done_;
  from_file_ += earlier;
  jobs_ += r.jobs;
  lookups_ += r.lookups;
  records_ += r.records;
  if (!r.ok()) failures_.push_back(r);
  return true;
}

std::vector<ShardResult> Report::sorted_failures() const {
  std::vector<ShardResult> f = failures_;
  std::sort(f.begin(), f.end(), [](const ShardResult& a, const ShardResult& b) { return a.shard < b.shard; });
  return f;
}

std::string Report::text(const std::string& program) const {
  const Campaign& c = campaign_;
  std::ostringstream s;
  s << "campaign: " << c.seeds.size() << " seeds x " << c.configs.size() << " configs x " << c.lanes.size()
    << " lane counts x " << c.backends.size() << " backends = " << c.shards() << " shards of " << c.jobs_per_shard
    << " jobs" << (c.cycles ? ", cycles compared" : "") << '\n';
  s << "shards: " << shards_done_ << " of " << c.shards() << " (" << from_file_ << " from the results file, "
    << shards_done_ - from_file_ << " run now on " << ranks << (ranks == 1 ? " rank" : " ranks") << " in "
    << seconds << " s)\n";
  if (ranks > 1)
    s << "messages: " << bytes_between_ranks << " bytes between ranks ("
      << (shards_done_ > from_file_ ? bytes_between_ranks / (shards_done_ - from_file_) : 0) << " per shard run now)\n";
  s << "jobs: " << jobs_ << "  lookups: " << lookups_ << "  records: " << records_ << '\n';
  const auto f = sorted_failures();
  s << "failures: " << f.size() << '\n';
  for (const ShardResult& r : f) {
    const Shard sh = shard_at(c, r.shard);
    s << "FAIL shard " << r.shard << " (" << describe(sh) << "): " << r.error << '\n'
      << "  reproduce: " << reproduce_command(c, sh, program, reproduce_file_name(c, sh)) << '\n';
  }
  if (!stopped.empty()) s << "incomplete: " << stopped << '\n';
  return s.str();
}

std::string Report::json(const std::string& program) const {
  nlohmann::ordered_json j;
  j["campaign"] = nlohmann::json::parse(campaign_json(campaign_));
  j["shards"] = campaign_.shards();
  j["shards_done"] = shards_done_;
  j["shards_from_results_file"] = from_file_;
  j["complete"] = complete();
  j["jobs"] = jobs_;
  j["lookups"] = lookups_;
  j["records"] = records_;
  j["failures"] = nlohmann::json::array();
  for (const ShardResult& r : sorted_failures()) {
    const Shard sh = shard_at(campaign_, r.shard);
    nlohmann::ordered_json f = detail::shard_json(sh);
    if (r.differs) f["first_difference"] = {{"job", r.job}, {"tag", r.tag}};
    f["error"] = r.error;
    f["reproduce"] = reproduce_command(campaign_, sh, program, reproduce_file_name(campaign_, sh));
    j["failures"].push_back(f);
  }
  j["ranks"] = ranks;
  j["seconds"] = seconds;
  j["bytes_between_ranks"] = bytes_between_ranks;
  j["stopped"] = stopped;
  return j.dump(2);
}

}  // namespace voxcd
