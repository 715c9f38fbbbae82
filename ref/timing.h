// The device's cycle model: how many cycles each job of a stream takes on the RTL (rtl/voxcd_device.sv), exactly,
// when jobs are presented back to back and the consumer of the output streams is always ready. Under
// back-pressure the RTL's count of a job exceeds this by the stall cycles it reports (cycles in which the
// output slice's registered ready is low and the pipeline holds). docs/hardware.md derives it.
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// Slot registers between the issue stage and the hit-test stage on a 2-bit device (voxcd_arch_pkg::PipeSlots).
constexpr int kPipelineSlots = 6;
// Cycles from a job's acceptance to its first slot at the hit-test stage at depth 0: the queue register, then the
// slots (1 + pipeline_slots(cfg) for any configuration).
constexpr int kFirstSlotLatency = 1 + kPipelineSlots;
// A distance device (SB > 2) adds three registers after the voxmap read (voxcd_arch_pkg::DistSlots): node select and
// the x interpolation, the y interpolation, the z interpolation.
constexpr int kDistanceSlots = 3;
// A sparse device (BL > 0) adds the shell word register before R0, and after the table read (R4 to R5) the entry
// register and the brick word register (voxcd_arch_pkg::SparseSlots); a sparse distance device also the rows
// register between them (voxcd_arch_pkg::SparseDistSlots).
constexpr int kSparseSlots = 3;
constexpr int kSparseDistanceSlots = 4;
// Each unit of DeviceConfig::depth adds one more register stage to every lane, so one more slot register.
// The slot registers of cfg's device: kPipelineSlots + cfg.depth, plus kDistanceSlots on a distance device, plus the
// sparse registers on a sparse one.
inline int pipeline_slots(const DeviceConfig& cfg) {
  return kPipelineSlots + cfg.depth + (cfg.distance() ? kDistanceSlots : 0) +
         (cfg.sparse() ? (cfg.distance() ? kSparseDistanceSlots : kSparseSlots) : 0);
}

// Where the voxmap reads and a FIRST hit's detection sit among the slot registers 0 .. pipeline_slots - 1 (the hit
// test is the last): the table port reads as a slot moves from `table_read` (R4) to the next register, the brick
// port (sparse devices; -1 elsewhere) from `brick_read` (the entry, or the rows register) to the next; a FIRST
// job's hit is known at `hit_known` (the hit test, or the register before the READ stage on a 2-bit device).
struct PipelinePlaces {
  int table_read = 0, brick_read = -1, hit_known = 0;
};
PipelinePlaces pipeline_places(const DeviceConfig& cfg);

// How a job's points fall into slots (lane groups): `groups` slots (at least one: an empty job takes one), slot g
// holding points [begin(g), end(g)). A dense shell's slots are LANES consecutive points each; a sparse shell's
// follow its words (docs/contract.md, "Shell bricks": each word max(1, ceil(pop / LANES)) slots).
struct JobSlots {
  uint64_t lanes = 1, groups = 1, points = 0;
  std::vector<uint32_t> starts;  // a sparse shell: slot g begins at starts[g]; starts[groups] = points

  uint64_t begin(uint64_t g) const { return starts.empty() ? g * lanes : starts[g]; }
  uint64_t end(uint64_t g) const {
    return starts.empty() ? (g + 1) * lanes < points ? (g + 1) * lanes : points : starts[g + 1];
  }
  // The slot of a point (< points).
  uint64_t slot_of(uint64_t point) const;
};
// A dense-shell job's slots; std::invalid_argument for a sparse shell (its slots depend on its words).
JobSlots job_slots(const DeviceConfig& cfg, const Job& job);
// Any job's slots, from the shell memory it reads (valid for it: validate_job).
JobSlots job_slots(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job);

struct JobTiming {
  uint64_t slots = 0;   // lane groups issued for the job (FIRST: up to the early stop), plus its empty slot
  uint64_t cycles = 0;  // the completion record's cycles: since the previous completion (job 0: acceptance)
  uint64_t points = 0;  // points that reached the hit test before the completion (the record's informative count)
};

// What a job's timing takes from its own hit records: how many, how many lane groups hold one, the first and the
// last of those groups (both = the job's group count when it has none).
struct JobHits {
  uint64_t records = 0, groups = 0, first_group = 0, last_group = 0;
};
// The summary of job `j`'s hit records [hits, hits + n) (its records before its completion record), its slots
// `slots`. Throws std::invalid_argument as job_timing does when a record is not the job's or not in ascending point
// order; `first` is the index of hits[0] in the stream, for the message. The overload without the slots takes a
// dense shell's.
JobHits job_hits(const JobSlots& slots, const Job& job, size_t j, const Record* hits, size_t n, size_t first = 0);
JobHits job_hits(const DeviceConfig& cfg, const Job& job, size_t j, const Record* hits, size_t n, size_t first = 0);
// The same summary from a job's hit points alone (each relative to its shell_base, ascending, as a run gives them;
// not checked): for a host that holds its hits in columns (ref/fast/hits.h).
JobHits job_hits(const JobSlots& slots, const uint32_t* points, size_t n);
JobHits job_hits(const DeviceConfig& cfg, const Job& job, const uint32_t* points, size_t n);
// The summary of two consecutive runs of one job's hit records (a before b), as job_hits of the whole run gives it;
// the two runs are not checked against each other.
JobHits join_job_hits(const JobHits& a, const JobHits& b);
// The lane groups of a dense-shell job (at least one): job_slots(cfg, job).groups.
uint64_t job_groups(const DeviceConfig& cfg, const Job& job);

// A job's place on the stream's clock, from its own hit records alone (job_hits) and its completion record's hits:
// cycles from the moment its first slot may reach the hit-test stage to its completion record (`done`) and to the
// moment the next job's first slot may (`advance`), its slots and points. A job's completion cycles are its `done`
// plus the previous job's `advance` less the previous job's `done` (span_cycles), so jobs can be timed apart and in
// any order. Throws std::invalid_argument when a FIRST job reports a hit without a hit record (`j` names it).
struct JobSpan {
  uint64_t done = 0, advance = 0, slots = 0, points = 0;
};
// A job's bank conflict cycles on a banked device (ref/banks.h): every one, as the device counts them, and of those
// the `window`: on a distance device, the empty slots its slots behind a FIRST hit left while they still read.
struct BankCycles {
  uint64_t conflicts = 0, window = 0;
};
// Each conflict cycle before the completion delays the job's next slot by one cycle at the hit test, so both `done`
// and `advance` grow by it; a window cycle takes the place of a squashed slot behind a FIRST hit, and delays the
// next job only when the job runs out of slots to squash first.
JobSpan job_span(const DeviceConfig& cfg, const Job& job, const JobSlots& slots, size_t j, const JobHits& hits,
                 uint32_t done_hits, const BankCycles& bank = {});
// A dense-shell job's span (job_slots(cfg, job)).
JobSpan job_span(const DeviceConfig& cfg, const Job& job, size_t j, const JobHits& hits, uint32_t done_hits,
                 const BankCycles& bank = {});
// The completion record's cycles of a job of span `cur` after a job of span `prev` (null: the stream's first job,
// whose slots may start kFirstSlotLatency cycles, plus the distance slots, after its acceptance).
uint64_t span_cycles(const DeviceConfig& cfg, const JobSpan* prev, const JobSpan& cur);

// Timing of every job of `jobs`, given the stream `records` that ref/ produced for them (hits in order, then a
// completion per job). Throws std::invalid_argument when the stream does not belong to the jobs, on a banked
// device (whose cycles depend on the reads) and for a sparse-shell job (whose slots depend on its words): use the
// overloads with the memory.
std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records);
// The same with each job's bank cycles (bank_cycles; all 0 on a device with a copy per lane); dense shells only.
std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records, const std::vector<BankCycles>& bank);
// The same for any job (sparse shells too: `shell` is the shell memory they read), with each job's bank cycles.
std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<ShellWord>& shell,
                                  const std::vector<Job>& jobs, const std::vector<Record>& records,
                                  const std::vector<BankCycles>& bank);
// The same for any device, counting a banked device's conflicts from the memory the jobs ran on.
std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records);

// Fills the cycles (and the informative points and zero stalls) of every completion record in `records`. Throws
// on a banked device, as job_timing does; the overload with the memory times any device.
void annotate_cycles(const DeviceConfig& cfg, const std::vector<Job>& jobs, std::vector<Record>& records);
void annotate_cycles(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs,
                     std::vector<Record>& records);
void annotate_cycles(const DeviceConfig& cfg, const std::vector<Job>& jobs, std::vector<Record>& records,
                     const std::vector<BankCycles>& bank);
void annotate_cycles(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const std::vector<Job>& jobs,
                     std::vector<Record>& records, const std::vector<BankCycles>& bank);

// Cycles of the whole stream: from the first job's acceptance to the cycle the last completion record is taken.
uint64_t stream_cycles(const std::vector<JobTiming>& t);

}  // namespace voxcd
