#include "voxcd/host/regress/results_file.h"

#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "voxcd/host/regress/detail/shard_json.h"

namespace voxcd {

namespace {

constexpr const char* kFormatKey = "voxcd_regress_results";

std::string header_line(const Campaign& c) {
  return nlohmann::ordered_json{{kFormatKey, 1}, {"campaign", nlohmann::ordered_json::parse(campaign_json(c))}}.dump();
}

}  // namespace

std::string shard_result_line(const ShardResult& r, const Shard& s) {
  nlohmann::ordered_json j = detail::shard_json(s);
  j["jobs"] = r.jobs;
  j["lookups"] = r.lookups;
  j["records"] = r.records;
  j["cycles"] = r.cycles;
  j["ok"] = r.ok();
  j["error"] = r.error;
  if (r.differs) j["first_difference"] = {{"job", r.job}, {"tag", r.tag}};
  j["rank"] = r.rank;
  j["seconds"] = r.seconds;
  return j.dump();
}

ShardResult parse_shard_result(const std::string& line, const Campaign& c, const std::string& where) {
  ShardResult r;
  try {
    const nlohmann::json j = nlohmann::json::parse(line);
    r.shard = j.at("shard").get<uint64_t>();
    if (r.shard >= c.shards())
      throw CampaignError(where + ": shard " + std::to_string(r.shard) + " is not in the campaign (it has " +
                          std::to_string(c.shards()) + " shards)");
    const Shard s = shard_at(c, r.shard);
    const std::string cfg = j.at("config").get<std::string>();
    if (j.at("seed").get<uint64_t>() != s.seed || cfg != (s.config.empty() ? "default" : s.config) ||
        j.at("lanes").get<int>() != s.lanes || j.at("backend").get<std::string>() != s.backend)
      throw CampaignError(where + ": shard " + std::to_string(r.shard) + " is not " + describe(s) +
                          " in this campaign");
    r.jobs = j.at("jobs").get<uint64_t>();
    r.lookups = j.at("lookups").get<uint64_t>();
    r.records = j.at("records").get<uint64_t>();
    r.cycles = j.at("cycles").get<bool>();
    r.error = j.at("error").get<std::string>();
    if (j.at("ok").get<bool>() != r.error.empty())
      throw CampaignError(where + ": \"ok\" disagrees with \"error\"");
    if (j.contains("first_difference")) {
      r.differs = true;
      r.job = j["first_difference"].at("job").get<uint64_t>();
      r.tag = j["first_difference"].at("tag").get<uint32_t>();
    }
    r.rank = j.at("rank").get<int>();
    r.seconds = j.at("seconds").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw CampaignError(where + ": not a shard result: " + e.what());
  }
  return r;
}

ResultsFile::ResultsFile(const std::string& path, const Campaign& c) : journal_(path) {
  std::vector<bool> seen(c.shards(), false);
  auto wrong_header = [&](const std::string& line) {
    std::string theirs = line;
    try {
      const nlohmann::ordered_json j = nlohmann::ordered_json::parse(line);
      if (!j.contains(kFormatKey)) throw std::runtime_error("");
      theirs = j.at("campaign").dump();
    } catch (const std::exception&) {
      throw CampaignError(path + " is not a voxcd regress results file (its first line is not the header)");
    }
    throw CampaignError(path + " holds the results of another campaign (" + theirs + "; this one is " +
                        campaign_json(c) + "): give another --results file, or the campaign it was made for");
  };
  read_journal_rows(journal_, path, header_line(c), wrong_header, [&](const std::string& line, const std::string& where) {
    ShardResult r = parse_shard_result(line, c, where);
    if (seen[r.shard]) return;
    seen[r.shard] = true;
    finished_.push_back(std::move(r));
  });
  journal_.open(header_line(c));
}

void ResultsFile::append(const ShardResult& r, const Shard& s) { journal_.append(shard_result_line(r, s)); }

}  // namespace voxcd
