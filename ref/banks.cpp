#include "voxcd/ref/banks.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "voxcd/ref/pipeline.h"

namespace voxcd {

uint64_t bank_rounds(int banks, const std::vector<uint64_t>& words) {
  if (banks <= 0) return 1;
  // One read of a word serves every lane that asks for it; each bank reads one word a round.
  std::vector<uint64_t> distinct = words;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  std::vector<uint64_t> per_bank(size_t(banks), 0);
  uint64_t rounds = 1;
  for (uint64_t w : distinct) rounds = std::max(rounds, ++per_bank[size_t(w % uint64_t(banks))]);
  return rounds;
}

uint64_t job_bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                            uint64_t groups) {
  if (!cfg.banked()) return 0;
  const uint64_t L = uint64_t(cfg.LANES);
  uint64_t conflicts = 0;
  std::vector<uint64_t> words;
  for (uint64_t g = 0; g < groups; ++g) {
    words.clear();
    for (uint64_t k = g * L; k < std::min<uint64_t>((g + 1) * L, job.shell_count); ++k) {
      const Located l = locate(cfg, job, transform(cfg, job, shell[job.shell_base + k]));
      if (l.inside) words.push_back(l.word);
    }
    conflicts += bank_rounds(cfg.BANKS, words) - 1;
  }
  return conflicts;
}

uint64_t read_groups(const DeviceConfig& cfg, const Job& job, const JobHits& hits, uint32_t done_hits) {
  const uint64_t groups = job_groups(cfg, job);
  if (job.mode == Mode::First && done_hits > 0 && hits.first_group < groups) return hits.first_group + 1;
  return groups;
}

std::vector<uint64_t> bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                     const std::vector<Job>& jobs, const std::vector<Record>& records) {
  std::vector<uint64_t> out(jobs.size(), 0);
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const size_t first = r;
    while (r < records.size() && records[r].kind == Record::Hit) ++r;
    if (r == records.size() || records[r].tag != jobs[j].tag)
      throw std::invalid_argument("bank conflicts: no completion record for job " + std::to_string(j));
    const JobHits h = job_hits(cfg, jobs[j], j, records.data() + first, r - first, first);
    out[j] = job_bank_conflicts(cfg, shell, jobs[j], read_groups(cfg, jobs[j], h, records[r].hits));
    ++r;
  }
  if (r != records.size()) throw std::invalid_argument("bank conflicts: records left over after the last job");
  return out;
}

}  // namespace voxcd
