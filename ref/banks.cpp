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

namespace {

// The eight node words of cell (x, y, z) of a dense distance map.
void dense_node_words(const DeviceConfig& cfg, const Job& job, const Located& l, std::vector<uint64_t>& out) {
  const uint64_t x = uint64_t(l.index[0]), y = uint64_t(l.index[1]), z = uint64_t(l.index[2]);
  for (int c = 0; c < 8; ++c) out.push_back(node_address(cfg, job, x + (c & 1), y + (c >> 1 & 1), z + (c >> 2)).word);
}

}  // namespace

void point_reads(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const ShellWord& p,
                 std::vector<uint64_t>& table, std::vector<uint64_t>& brick) {
  const Transformed tr = transform(cfg, job, p);
  const Located l = locate(cfg, job, tr);
  if (!l.inside) return;
  if (!job.sparse_map()) {
    if (cfg.distance())
      dense_node_words(cfg, job, l, table);
    else
      table.push_back(l.word);
    return;
  }
  const TableRef t = table_ref(cfg, job, l);
  table.push_back(t.word);
  const Cell c = read_cell(cfg, map, job, t);
  if (c.level < 0) return;  // a uniform cell reads no brick
  if (!cfg.distance()) {
    brick.push_back(brick_ref(cfg, c, l).word);
    return;
  }
  const SubCell s = sub_cell(cfg, c, l, tr);
  for (int k = 0; k < 8; ++k)
    brick.push_back(brick_node_address(cfg, c, s.X[0] + (k & 1), s.X[1] + (k >> 1 & 1), s.X[2] + (k >> 2)).word);
}

SlotRounds slot_rounds(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job,
                       const std::vector<ShellWord>& points, const JobSlots& slots, uint64_t g) {
  SlotRounds r;
  if (!cfg.banked()) return r;
  std::vector<uint64_t> table, brick;
  for (uint64_t k = slots.begin(g); k < slots.end(g); ++k) point_reads(cfg, map, job, points[k], table, brick);
  r.table = bank_rounds(memory_banks(cfg), table);
  r.brick = bank_rounds(memory_banks(cfg), brick);
  return r;
}

uint64_t read_groups(const JobSlots& slots, const Job& job, const JobHits& hits, uint32_t done_hits) {
  if (job.mode == Mode::First && done_hits > 0 && hits.first_group < slots.groups) return hits.first_group + 1;
  return slots.groups;
}

BankCycles job_bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                           const std::vector<uint64_t>& map, const Job& job, const JobHits& hits, uint32_t done_hits) {
  BankCycles b;
  if (!cfg.banked()) return b;
  const JobSlots slots = job_slots(cfg, shell, job);
  const std::vector<ShellWord> points = job_points(cfg, shell, job);
  auto rounds = [&](uint64_t g) { return slot_rounds(cfg, map, job, points, slots, g); };
  const uint64_t read = read_groups(slots, job, hits, done_hits);
  for (uint64_t g = 0; g < read; ++g) b.conflicts += rounds(g).waits();
  if (read == slots.groups) return b;
  // A FIRST job that hit in slot read - 1: its later slots read until the hit is known.
  b.window = first_window(cfg, read - 1, slots.groups, rounds);
  b.conflicts += b.window;
  return b;
}

std::vector<BankCycles> bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                    const std::vector<uint64_t>& map, const std::vector<Job>& jobs,
                                    const std::vector<Record>& records) {
  std::vector<BankCycles> out(jobs.size());
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const size_t first = r;
    while (r < records.size() && records[r].kind == Record::Hit) ++r;
    if (r == records.size() || records[r].tag != jobs[j].tag)
      throw std::invalid_argument("bank conflicts: no completion record for job " + std::to_string(j));
    const JobHits h =
        job_hits(job_slots(cfg, shell, jobs[j]), jobs[j], j, records.data() + first, r - first, first);
    out[j] = job_bank_cycles(cfg, shell, map, jobs[j], h, records[r].hits);
    ++r;
  }
  if (r != records.size()) throw std::invalid_argument("bank conflicts: records left over after the last job");
  return out;
}

std::vector<uint64_t> bank_conflicts(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs,
                                     const std::vector<Record>& records) {
  std::vector<uint64_t> out;
  for (const BankCycles& b : bank_cycles(cfg, mem, jobs, records)) out.push_back(b.conflicts);
  return out;
}

}  // namespace voxcd
