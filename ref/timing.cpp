#include "voxcd/ref/timing.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace voxcd {

namespace {

uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

}  // namespace

std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records) {
  const uint64_t L = uint64_t(cfg.LANES);
  const uint64_t P = uint64_t(pipeline_slots(cfg));
  std::vector<JobTiming> out(jobs.size());
  // `t` is the cycle in which the next slot reaches the hit-test stage, counted from job 0's acceptance.
  uint64_t t = 1 + P;  // kFirstSlotLatency on a 2-bit device
  uint64_t prev_done = 0;
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const Job& job = jobs[j];
    const uint64_t count = job.shell_count;
    const uint64_t groups = count == 0 ? 1 : ceil_div(count, L);
    uint64_t first_group = groups;  // group of the first hit record
    uint64_t hit_records = 0, hit_groups = 0, last_group = groups;  // groups with a hit record, the latest one
    for (; r < records.size() && records[r].kind == Record::Hit; ++r) {
      const Record& h = records[r];
      if (h.tag != job.tag || h.point >= count)
        throw std::invalid_argument("timing: hit record " + std::to_string(r) + " does not belong to job " +
                                    std::to_string(j));
      const uint64_t g = h.point / L;
      if (hit_records && g < last_group)
        throw std::invalid_argument("timing: hit record " + std::to_string(r) + " of job " + std::to_string(j) +
                                    " is not in ascending point order");
      ++hit_records;
      if (g != last_group) ++hit_groups, last_group = g;
      if (first_group == groups) first_group = g;
    }
    if (r == records.size() || records[r].tag != job.tag)
      throw std::invalid_argument("timing: no completion record for job " + std::to_string(j));
    const Record& done = records[r++];

    JobTiming& jt = out[j];
    uint64_t done_at = 0;
    if (job.mode == Mode::First && done.hits > 0) {
      if (first_group == groups)
        throw std::invalid_argument("timing: FIRST job " + std::to_string(j) + " reports a hit but has no record");
      const uint64_t f = first_group;
      t += f;                 // the groups before the hit: one cycle each
      done_at = t + 1;        // the hit record, then the completion record
      t += 2;
      // Groups issued behind the hit are squashed; the issue stage leaves the job with one empty slot.
      const uint64_t squashed = std::min(groups - 1, f + P - 1) - f;
      const uint64_t bubble = (groups - 1 >= f + P) ? 1 : 0;
      t += squashed + bubble;
      jt.slots = f + 1 + squashed + bubble;
      jt.points = std::min(count, (f + 1) * L);
    } else {
      // A slot takes max(1, its records) cycles: its hit records (ALL only), and the completion record on the
      // job's last slot. Summed over the slots without a loop over them.
      const bool all = job.mode == Mode::All;
      const uint64_t recs = (all ? hit_records : 0) + 1;
      const uint64_t busy = (all ? hit_groups : 0) + ((all && last_group == groups - 1) ? 0 : 1);
      const uint64_t total = recs + (groups - busy);
      done_at = t + total - 1;
      t += total;
      jt.slots = groups;
      jt.points = count;
    }
    jt.cycles = done_at - prev_done;
    prev_done = done_at;
  }
  if (r != records.size()) throw std::invalid_argument("timing: records left over after the last job");
  return out;
}

void annotate_cycles(const DeviceConfig& cfg, const std::vector<Job>& jobs, std::vector<Record>& records) {
  const std::vector<JobTiming> t = job_timing(cfg, jobs, records);
  size_t j = 0;
  for (Record& rec : records) {
    if (rec.kind != Record::Done) continue;
    rec.cycles = t[j].cycles;
    rec.points = t[j].points;
    rec.stalls = 0;
    ++j;
  }
}

uint64_t stream_cycles(const std::vector<JobTiming>& t) {
  uint64_t sum = 0;
  for (const JobTiming& j : t) sum += j.cycles;
  return t.empty() ? 0 : sum + 1;  // the last completion record is taken one cycle after it is emitted
}

}  // namespace voxcd
