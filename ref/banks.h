// Shared voxmap banks (docs/contract.md, "Shared voxmap banks"): when the lanes share one voxmap memory split into
// banks, the lanes of a slot that read different words of one bank take turns, and the slot reaches the hit test
// that many cycles later. These functions count those cycles from the addresses, for the cycle model.
//
// A 2-bit device with BANKS = B has B banks, word w in bank w % B; a distance device has 8 parity banks split B
// ways, 8B in all, word w in bank w % 8B, and each of its lanes reads the 8 words of its cell's nodes. A sparse device
// (BL > 0) reads at two ports of every bank: the table port (a sparse map's table word; a dense map's words) and then
// the brick port (the words of the cell's brick; nothing for a uniform cell or a dense map), each in rounds of its
// own, the brick port first (docs/contract.md, "Sparse voxmaps and shells").
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// Rounds a slot's reads take: the largest number of distinct words any one bank is asked for (word w is in bank
// w % banks); 1 when no lane reads (lanes outside the map read nothing). `words` holds every word the lanes read.
uint64_t bank_rounds(int banks, const std::vector<uint64_t>& words);

// The banks of cfg's voxmap memory: BANKS on a 2-bit device, 8 * BANKS on a distance device (0 with a copy per lane).
int memory_banks(const DeviceConfig& cfg);

// Appends the words point p of a job reads at the table port and at the brick port (nothing for a point outside the
// map). The job must be valid for the map (validate_job).
void point_reads(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const ShellWord& p,
                 std::vector<uint64_t>& table, std::vector<uint64_t>& brick);

// Rounds of one slot at each port: bank_rounds of the words its points read there (1 and 1 with a copy per lane).
struct SlotRounds {
  uint64_t table = 1, brick = 1;
  uint64_t waits() const { return table - 1 + brick - 1; }  // the slot's bank conflict cycles
};
// Slot g of a job whose points (job_points) are `points` and slots `slots`.
SlotRounds slot_rounds(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job,
                       const std::vector<ShellWord>& points, const JobSlots& slots, uint64_t g);

// The slots of a job whose reads reach the banks before its completion: all of them, or for a FIRST job that hit
// (done_hits > 0) those up to the slot of its hit (`hits` summarises its records, job_hits).
uint64_t read_groups(const JobSlots& slots, const Job& job, const JobHits& hits, uint32_t done_hits);

// The empty slots a FIRST job's slots behind its hit (slot f) leave while they still read, before the hit is known
// (`rounds(g)`: slot g's rounds, for g > f; `groups`: the job's slots): the slot registers followed cycle by cycle,
// from the cycle the hit leaves the table port (pipeline_places) to the cycle it reaches `hit_known`. In each cycle
// the brick port's slot takes a round, and if it still waits the registers up to it hold and the ones after it move
// on, leaving an empty slot behind it; else the table port's slot does the same; else every slot moves on.
template <class Rounds>
uint64_t first_window(const DeviceConfig& cfg, uint64_t f, uint64_t groups, Rounds&& rounds);

// A job's bank conflict cycles (BankCycles, ref/timing.h): those of its read groups, and for a FIRST job that hit, the
// empty slots its later slots left (first_window). `shell` and `map` are the memories the job reads.
BankCycles job_bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                           const std::vector<uint64_t>& map, const Job& job, const JobHits& hits, uint32_t done_hits);

// Every job's bank cycles, given the stream `records` that ref/ produced for them. Throws std::invalid_argument when
// the stream does not belong to the jobs.
std::vector<BankCycles> bank_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                    const std::vector<uint64_t>& map, const std::vector<Job>& jobs,
                                    const std::vector<Record>& records);
inline std::vector<BankCycles> bank_cycles(const DeviceConfig& cfg, const DeviceMemory& mem,
                                           const std::vector<Job>& jobs, const std::vector<Record>& records) {
  return bank_cycles(cfg, mem.shell, mem.map, jobs, records);
}
// Every job's bank conflict cycles (BankCycles::conflicts): what the device's conflict counter counts for it.
std::vector<uint64_t> bank_conflicts(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs,
                                     const std::vector<Record>& records);

// ---- first_window ----

template <class Rounds>
uint64_t first_window(const DeviceConfig& cfg, uint64_t f, uint64_t groups, Rounds&& rounds) {
  const PipelinePlaces at = pipeline_places(cfg);
  // The hit slot has just left the table port; the job's later slots follow it with no gap (the issue stage issues
  // one a cycle), so slot f + k is at table_read + 1 - k (below 0: not issued yet, issued as the registers move).
  struct Slot {
    int64_t pos;
    uint64_t table_waits, brick_waits;
    bool known;  // its rounds computed
  };
  std::vector<Slot> behind;  // slots f+1, f+2, ... as far as the window can reach
  const int64_t reach = int64_t(at.hit_known) + 1;
  for (uint64_t g = f + 1; g < groups && int64_t(g - f) <= reach; ++g)
    behind.push_back({int64_t(at.table_read) + 1 - int64_t(g - f), 0, 0, false});
  int64_t hit = at.table_read + 1;
  uint64_t hit_brick_waits = 0;
  if (at.brick_read >= 0) hit_brick_waits = rounds(f).brick - 1;
  uint64_t window = 0;
  auto fetch = [&](size_t k) {
    if (!behind[k].known) {
      const SlotRounds r = rounds(f + 1 + k);
      behind[k].table_waits = r.table - 1;
      behind[k].brick_waits = r.brick - 1;
      behind[k].known = true;
    }
  };
  while (hit < at.hit_known) {
    int64_t held_up_to = -1;  // registers at or below it hold this cycle
    if (at.brick_read >= 0 && hit == at.brick_read && hit_brick_waits > 0) {
      --hit_brick_waits;
      held_up_to = at.brick_read;
    }
    for (size_t k = 0; k < behind.size() && held_up_to < 0; ++k) {
      if (at.brick_read < 0 || behind[k].pos != at.brick_read) continue;
      fetch(k);
      if (behind[k].brick_waits > 0) --behind[k].brick_waits, held_up_to = at.brick_read, ++window;
    }
    for (size_t k = 0; k < behind.size() && held_up_to < 0; ++k) {
      if (behind[k].pos != at.table_read) continue;
      fetch(k);
      if (behind[k].table_waits > 0) --behind[k].table_waits, held_up_to = at.table_read, ++window;
    }
    if (hit > held_up_to) ++hit;
    for (Slot& s : behind)
      if (s.pos > held_up_to) ++s.pos;
  }
  return window;
}

}  // namespace voxcd
