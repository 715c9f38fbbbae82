#include "voxcd/host/regress/results_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace voxcd {

namespace {

constexpr const char* kFormatKey = "voxcd_regress_results";

std::string header_line(const Campaign& c) {
  return std::string("{\"") + kFormatKey + "\":1,\"campaign\":" + campaign_json(c) + "}";
}

std::string system_error(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

// Writes all of `bytes` to fd; false on an error.
bool write_all(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

}  // namespace

std::string shard_result_line(const ShardResult& r, const Shard& s) {
  nlohmann::ordered_json j;
  j["shard"] = r.shard;
  j["seed"] = s.seed;
  j["config"] = s.config.empty() ? "default" : s.config;
  j["lanes"] = s.lanes;
  j["backend"] = s.backend;
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

ResultsFile::ResultsFile(const std::string& path, const Campaign& c) : path_(path) {
  std::string text;
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::ostringstream s;
      s << in.rdbuf();
      text = s.str();
    }
  }
  // A writer stopped mid-line leaves a last line without its newline: it never counted.
  const size_t keep = text.empty() ? 0 : text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  const bool cut = keep != text.size();
  text.resize(keep);
  std::vector<bool> seen(c.shards(), false);
  std::istringstream lines(text);
  std::string line;
  size_t n = 0;
  while (std::getline(lines, line)) {
    ++n;
    const std::string where = path + ":" + std::to_string(n);
    if (n == 1) {
      if (line != header_line(c)) {
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
      }
      continue;
    }
    ShardResult r = parse_shard_result(line, c, where);
    if (seen[r.shard]) continue;
    seen[r.shard] = true;
    finished_.push_back(std::move(r));
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd_ < 0) throw std::runtime_error(system_error("cannot open the results file", path));
  if ((cut || keep == 0) && ::ftruncate(fd_, off_t(keep)) != 0)
    throw std::runtime_error(system_error("cannot cut the unfinished last line of", path));
  if (::lseek(fd_, 0, SEEK_END) < 0) throw std::runtime_error(system_error("cannot seek in", path));
  if (keep == 0 && (!write_all(fd_, header_line(c) + "\n") || ::fsync(fd_) != 0))
    throw std::runtime_error(system_error("cannot write the results file", path));
}

ResultsFile::~ResultsFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ResultsFile::append(const ShardResult& r, const Shard& s) {
  if (!write_all(fd_, shard_result_line(r, s) + "\n") || ::fsync(fd_) != 0)
    throw std::runtime_error(system_error("cannot write the results file", path_));
}

}  // namespace voxcd
