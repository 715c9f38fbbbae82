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

int memory_banks(const DeviceConfig& cfg) { return cfg.banked() ? (cfg.distance() ? 8 : 1) * cfg.BANKS : 0; }

uint64_t slot_rounds(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job, uint64_t g) {
  if (!cfg.banked()) return 1;
  const uint64_t L = uint64_t(cfg.LANES);
  std::vector<uint64_t> words;
  for (uint64_t k = g * L; k < std::min<uint64_t>((g + 1) * L, job.shell_count); ++k) {
    const Located l = locate(cfg, job, transform(cfg, job, shell[job.shell_base + k]));
    if (!l.inside) continue;
    if (!cfg.distance()) {
      words.push_back(l.word);
      continue;
    }
    // The eight nodes around the cell, one in each parity bank.
    const uint64_t x = uint64_t(l.index[0]), y = uint64_t(l.index[1]), z = uint64_t(l.index[2]);
    for (int c = 0; c < 8; ++c) words.push_back(node_address(cfg, job, x + (c & 1), y + (c >> 1 & 1), z + (c >> 2)).word);
  }
  return bank_rounds(memory_banks(cfg), words);
}

uint64_t job_bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                            uint64_t groups) {
  if (!cfg.banked()) return 0;
  uint64_t conflicts = 0;
  for (uint64_t g = 0; g < groups; ++g) conflicts += slot_rounds(cfg, shell, job, g) - 1;
  return conflicts;
}

uint64_t read_groups(const DeviceConfig& cfg, const Job& job, const JobHits& hits, uint32_t done_hits) {
  const uint64_t groups = job_groups(cfg, job);
  if (job.mode == Mode::First && done_hits > 0 && hits.first_group < groups) return hits.first_group + 1;
  return groups;
}

uint64_t first_read_window(const DeviceConfig& cfg) {
  // The slot registers after R5 (the words): the node select's (depth's READ stage) and the interpolations'.
  return cfg.distance() ? uint64_t(kDistanceSlots) + (cfg.depth > kRankRead ? 1 : 0) : 0;
}

BankCycles job_bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                           const JobHits& hits, uint32_t done_hits) {
  BankCycles b;
  if (!cfg.banked()) return b;
  const uint64_t groups = job_groups(cfg, job), read = read_groups(cfg, job, hits, done_hits);
  b.conflicts = job_bank_conflicts(cfg, shell, job, read);
  if (read == groups) return b;
  // A FIRST job that hit in slot read - 1: in each of the window's rounds the slot register before the read (R4)
  // holds the job's next slot, which leaves after its last round and otherwise leaves an empty slot behind it.
  uint64_t rounds = first_read_window(cfg);
  for (uint64_t g = read; g < groups && rounds > 0; ++g) {
    const uint64_t r = slot_rounds(cfg, shell, job, g);
    b.window += std::min(r, rounds) - (r <= rounds ? 1 : 0);
    rounds -= std::min(r, rounds);
  }
  b.conflicts += b.window;
  return b;
}

std::vector<BankCycles> bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                    const std::vector<Job>& jobs, const std::vector<Record>& records) {
  std::vector<BankCycles> out(jobs.size());
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const size_t first = r;
    while (r < records.size() && records[r].kind == Record::Hit) ++r;
    if (r == records.size() || records[r].tag != jobs[j].tag)
      throw std::invalid_argument("bank conflicts: no completion record for job " + std::to_string(j));
    const JobHits h = job_hits(cfg, jobs[j], j, records.data() + first, r - first, first);
    out[j] = job_bank_cycles(cfg, shell, jobs[j], h, records[r].hits);
    ++r;
  }
  if (r != records.size()) throw std::invalid_argument("bank conflicts: records left over after the last job");
  return out;
}

std::vector<uint64_t> bank_conflicts(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                     const std::vector<Job>& jobs, const std::vector<Record>& records) {
  std::vector<uint64_t> out;
  for (const BankCycles& b : bank_cycles(cfg, shell, jobs, records)) out.push_back(b.conflicts);
  return out;
}

}  // namespace voxcd
