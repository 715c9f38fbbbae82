#include "voxcd/ref/timing.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {

namespace {

uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

}  // namespace

PipelinePlaces pipeline_places(const DeviceConfig& cfg) {
  PipelinePlaces p;
  const int P = pipeline_slots(cfg);
  // R4 follows R0 (after the shell word register on a sparse device), PROD, ACC and R3, and the depth's IN, SUM,
  // FLOOR and ADDR stages.
  p.table_read = (cfg.sparse() ? 1 : 0) + 4 + (cfg.depth > kRankIn) + (cfg.depth > kRankSum) +
                 (cfg.depth > kRankFloor) + (cfg.depth > kRankAddr);
  // R5, the entry, on a distance device the rows: then the brick word.
  if (cfg.sparse()) p.brick_read = p.table_read + (cfg.distance() ? 3 : 2);
  p.hit_known = (!cfg.distance() && cfg.depth > kRankRead) ? P - 2 : P - 1;
  return p;
}

uint64_t JobSlots::slot_of(uint64_t point) const {
  if (starts.empty()) return point / lanes;
  // The last slot that begins at or before the point: an empty slot (an origin word) shares its beginning with the
  // slot after it, which holds the point.
  return uint64_t(std::upper_bound(starts.begin(), starts.end() - 1, uint32_t(point)) - starts.begin()) - 1;
}

JobSlots job_slots(const DeviceConfig& cfg, const Job& job) {
  if (job.sparse_shell())
    throw std::invalid_argument("timing: job tag " + std::to_string(job.tag) +
                                " has a sparse shell, whose slots follow its words: time it with the shell memory");
  JobSlots s;
  s.lanes = uint64_t(cfg.dense_slot_points());
  s.points = job.shell_count;
  s.groups = s.points == 0 ? 1 : ceil_div(s.points, s.lanes);
  return s;
}

JobSlots job_slots(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job) {
  if (!job.sparse_shell()) return job_slots(cfg, job);
  std::vector<uint32_t> pops;
  shell_points(cfg, shell, job, &pops);
  JobSlots s;
  s.lanes = uint64_t(cfg.LANES);
  uint32_t point = 0;
  for (uint32_t pop : pops) {
    const uint64_t n = pop == 0 ? 1 : ceil_div(pop, s.lanes);
    for (uint64_t k = 0; k < n; ++k) s.starts.push_back(point + uint32_t(std::min<uint64_t>(k * s.lanes, pop)));
    point += pop;
  }
  if (s.starts.empty()) s.starts.push_back(0);  // an empty job: one empty slot
  s.groups = s.starts.size();
  s.points = point;
  s.starts.push_back(point);
  return s;
}

uint64_t job_groups(const DeviceConfig& cfg, const Job& job) { return job_slots(cfg, job).groups; }

JobHits job_hits(const JobSlots& slots, const Job& job, size_t j, const Record* hits, size_t n, size_t first) {
  const uint64_t groups = slots.groups;
  JobHits s;
  s.first_group = s.last_group = groups;
  for (size_t k = 0; k < n; ++k) {
    const Record& h = hits[k];
    if (h.tag != job.tag || h.point >= slots.points)
      throw std::invalid_argument("timing: hit record " + std::to_string(first + k) + " does not belong to job " +
                                  std::to_string(j));
    const uint64_t g = slots.slot_of(h.point);
    if (s.records && g < s.last_group)
      throw std::invalid_argument("timing: hit record " + std::to_string(first + k) + " of job " + std::to_string(j) +
                                  " is not in ascending point order");
    ++s.records;
    if (g != s.last_group) ++s.groups, s.last_group = g;
    if (s.first_group == groups) s.first_group = g;
  }
  return s;
}

JobHits job_hits(const DeviceConfig& cfg, const Job& job, size_t j, const Record* hits, size_t n, size_t first) {
  return job_hits(job_slots(cfg, job), job, j, hits, n, first);
}

JobHits job_hits(const JobSlots& slots, const uint32_t* points, size_t n) {
  const uint64_t L = slots.lanes;
  JobHits s;
  s.first_group = s.last_group = slots.groups;
  if (n == 0) return s;
  s.records = n;
  uint64_t last = slots.slot_of(points[0]), distinct = 1;
  s.first_group = last;
  auto count = [&](auto group) {  // a shift where the lanes are a power of two: a division a hit costs more
    for (size_t k = 1; k < n; ++k) {
      const uint64_t g = group(points[k]);
      distinct += g != last;
      last = g;
    }
  };
  if (!slots.starts.empty()) {
    count([&slots](uint64_t p) { return slots.slot_of(p); });
  } else if ((L & (L - 1)) == 0) {
    const int shift = __builtin_ctzll(L);
    count([shift](uint64_t p) { return p >> shift; });
  } else {
    count([L](uint64_t p) { return p / L; });
  }
  s.groups = distinct;
  s.last_group = last;
  return s;
}

JobHits job_hits(const DeviceConfig& cfg, const Job& job, const uint32_t* points, size_t n) {
  return job_hits(job_slots(cfg, job), points, n);
}

JobHits join_job_hits(const JobHits& a, const JobHits& b) {
  if (!a.records) return b;
  if (!b.records) return a;
  JobHits s;
  s.records = a.records + b.records;
  s.groups = a.groups + b.groups - (a.last_group == b.first_group ? 1 : 0);
  s.first_group = a.first_group;
  s.last_group = b.last_group;
  return s;
}

JobSpan job_span(const DeviceConfig& cfg, const Job& job, size_t j, const JobHits& h, uint32_t done_hits,
                 const BankCycles& bank) {
  return job_span(cfg, job, job_slots(cfg, job), j, h, done_hits, bank);
}

JobSpan job_span(const DeviceConfig& cfg, const Job& job, const JobSlots& slots, size_t j, const JobHits& h,
                 uint32_t done_hits, const BankCycles& bank) {
  const uint64_t P = uint64_t(pipeline_slots(cfg));
  const uint64_t count = slots.points;
  const uint64_t groups = slots.groups;
  JobSpan s;
  if (job.mode == Mode::First && done_hits > 0) {
    if (h.first_group == groups)
      throw std::invalid_argument("timing: FIRST job " + std::to_string(j) + " reports a hit but has no record");
    const uint64_t f = h.first_group;
    // The groups before the hit, one cycle each (and their conflict cycles); the hit record, then the completion
    // record. Behind the hit the P - 1 slot registers before the hit test hold the job's later groups, squashed
    // (one cycle each), and the empty slots their reads left (the window); when the job has groups left beyond
    // them, the issue stage leaves it with one more empty slot. A job with fewer groups left is followed by the
    // next one's first slot right after them.
    const uint64_t rest = groups - 1 - f, window = bank.window;
    const uint64_t drain = rest + window >= P ? P : rest + window;
    s.done = f + 1 + (bank.conflicts - window);
    s.advance = s.done + 1 + drain;
    s.slots = f + 1 + drain - window;
    s.points = slots.end(f);
    return s;
  } else {
    // A slot takes max(1, its records) cycles: its hit records (ALL only), and the completion record on the
    // job's last slot. Summed over the slots without a loop over them.
    const bool all = job.mode == Mode::All;
    const uint64_t recs = (all ? h.records : 0) + 1;
    const uint64_t busy = (all ? h.groups : 0) + ((all && h.last_group == groups - 1) ? 0 : 1);
    const uint64_t total = recs + (groups - busy);
    s.done = total - 1;
    s.advance = total;
    s.slots = groups;
    s.points = count;
  }
  s.done += bank.conflicts;
  s.advance += bank.conflicts;
  return s;
}

uint64_t span_cycles(const DeviceConfig& cfg, const JobSpan* prev, const JobSpan& cur) {
  // `t`, the cycle in which a job's first slot may reach the hit-test stage, counted from job 0's acceptance:
  // 1 + P for job 0 (kFirstSlotLatency on a 2-bit device), then the previous job's plus its advance.
  if (!prev) return 1 + uint64_t(pipeline_slots(cfg)) + cur.done;
  return prev->advance - prev->done + cur.done;
}

namespace {

// `shell`: the shell memory the jobs read (null: dense shells only).
std::vector<JobTiming> timing_of(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                 const std::vector<Record>& records, const std::vector<BankCycles>* bank,
                                 const std::vector<ShellWord>* shell) {
  if (bank && bank->size() != jobs.size())
    throw std::invalid_argument("timing: " + std::to_string(bank->size()) + " bank conflict counts for " +
                                std::to_string(jobs.size()) + " jobs");
  std::vector<JobTiming> out(jobs.size());
  JobSpan prev;
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const Job& job = jobs[j];
    const size_t first = r;
    while (r < records.size() && records[r].kind == Record::Hit) ++r;
    const JobSlots slots = shell ? job_slots(cfg, *shell, job) : job_slots(cfg, job);
    const JobHits h = job_hits(slots, job, j, records.data() + first, r - first, first);
    if (r == records.size() || records[r].tag != job.tag)
      throw std::invalid_argument("timing: no completion record for job " + std::to_string(j));
    const Record& done = records[r++];
    const JobSpan s = job_span(cfg, job, slots, j, h, done.hits, bank ? (*bank)[j] : BankCycles{});
    out[j].cycles = span_cycles(cfg, j ? &prev : nullptr, s);
    out[j].slots = s.slots;
    out[j].points = s.points;
    prev = s;
  }
  if (r != records.size()) throw std::invalid_argument("timing: records left over after the last job");
  return out;
}

void require_unbanked(const DeviceConfig& cfg) {
  if (cfg.banked())
    throw std::invalid_argument("timing: a banked device's cycles (BANKS " + std::to_string(cfg.BANKS) +
                                ") depend on its voxmap reads: time it with the memory or the bank conflicts");
}

void annotate(const std::vector<JobTiming>& t, std::vector<Record>& records) {
  size_t j = 0;
  for (Record& rec : records) {
    if (rec.kind != Record::Done) continue;
    rec.cycles = t[j].cycles;
    rec.points = t[j].points;
    rec.stalls = 0;
    ++j;
  }
}

}  // namespace

std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records) {
  require_unbanked(cfg);
  return timing_of(cfg, jobs, records, nullptr, nullptr);
}

std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records, const std::vector<BankCycles>& bank) {
  return timing_of(cfg, jobs, records, &bank, nullptr);
}

std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                  const std::vector<Job>& jobs, const std::vector<Record>& records,
                                  const std::vector<BankCycles>& bank) {
  return timing_of(cfg, jobs, records, &bank, &shell);
}

std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records) {
  if (!cfg.banked()) return timing_of(cfg, jobs, records, nullptr, &mem.shell);
  const std::vector<BankCycles> bank = bank_cycles(cfg, mem, jobs, records);
  return timing_of(cfg, jobs, records, &bank, &mem.shell);
}

void annotate_cycles(const DeviceConfig& cfg, const std::vector<Job>& jobs, std::vector<Record>& records) {
  annotate(job_timing(cfg, jobs, records), records);
}

void annotate_cycles(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs,
                     std::vector<Record>& records) {
  annotate(job_timing(cfg, mem, jobs, records), records);
}

void annotate_cycles(const DeviceConfig& cfg, const std::vector<Job>& jobs, std::vector<Record>& records,
                     const std::vector<BankCycles>& bank) {
  annotate(job_timing(cfg, jobs, records, bank), records);
}

void annotate_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const std::vector<Job>& jobs,
                     std::vector<Record>& records, const std::vector<BankCycles>& bank) {
  annotate(job_timing(cfg, shell, jobs, records, bank), records);
}

uint64_t stream_cycles(const std::vector<JobTiming>& t) {
  uint64_t sum = 0;
  for (const JobTiming& j : t) sum += j.cycles;
  return t.empty() ? 0 : sum + 1;  // the last completion record is taken one cycle after it is emitted
}

}  // namespace voxcd
