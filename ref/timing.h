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

// Slot registers between the issue stage and the hit-test stage on a 2-bit device (voxcd_pkg::PipeSlots).
constexpr int kPipelineSlots = 6;
// Cycles from a job's acceptance to its first slot at the hit-test stage: the queue register, then the slots.
constexpr int kFirstSlotLatency = 1 + kPipelineSlots;
// A distance device (SB > 2) adds three registers after the voxmap read (voxcd_pkg::DistSlots): node select and
// the x interpolation, the y interpolation, the z interpolation.
constexpr int kDistanceSlots = 3;
// The slot registers of cfg's device: kPipelineSlots, plus kDistanceSlots on a distance device.
inline int pipeline_slots(const DeviceConfig& cfg) { return kPipelineSlots + (cfg.distance() ? kDistanceSlots : 0); }

struct JobTiming {
  uint64_t slots = 0;   // lane groups issued for the job (FIRST: up to the early stop), plus its empty slot
  uint64_t cycles = 0;  // the completion record's cycles: since the previous completion (job 0: acceptance)
  uint64_t points = 0;  // points that reached the hit test before the completion (the record's informative count)
};

// Timing of every job of `jobs`, given the stream `records` that ref/ produced for them (hits in order, then a
// completion per job). Throws std::invalid_argument when the stream does not belong to the jobs.
std::vector<JobTiming> job_timing(const DeviceConfig& cfg, const std::vector<Job>& jobs,
                                  const std::vector<Record>& records);

// Fills the cycles (and the informative points and zero stalls) of every completion record in `records`.
void annotate_cycles(const DeviceConfig& cfg, const std::vector<Job>& jobs, std::vector<Record>& records);

// Cycles of the whole stream: from the first job's acceptance to the cycle the last completion record is taken.
uint64_t stream_cycles(const std::vector<JobTiming>& t);

}  // namespace voxcd
