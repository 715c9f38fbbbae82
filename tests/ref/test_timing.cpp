// The cycle model on streams worked out by hand from the pipeline's rules (docs/hardware.md): a job's slots reach
// the hit test one a cycle, kFirstSlotLatency cycles after the first job's acceptance; a slot stays max(1, records)
// cycles; FIRST squashes the kPipelineSlots - 1 slots behind its hit and leaves one empty slot. The RTL is checked
// against the same model in tests/rtl.
#include <gtest/gtest.h>

#include <stdexcept>

#include "voxcd/ref/timing.h"

namespace voxcd {
namespace {

Job job(uint32_t tag, Mode mode, uint32_t count) {
  Job j;
  j.tag = tag;
  j.mode = mode;
  j.shell_count = count;
  return j;
}

TEST(Timing, HandWorkedStream) {
  static_assert(kPipelineSlots == 6 && kFirstSlotLatency == 7, "the hand-worked numbers below assume these");
  DeviceConfig cfg;
  cfg.LANES = 4;
  const std::vector<Job> jobs = {job(0, Mode::All, 0), job(1, Mode::All, 0), job(2, Mode::All, 8),
                                 job(3, Mode::All, 4), job(4, Mode::Count, 9), job(5, Mode::All, 12)};
  const std::vector<Record> recs = {
      Record::done(0, 0),                                    // first slot at cycle 7
      Record::done(1, 0),                                    // the next slot, 1 cycle later
      Record::done(2, 0),                                    // 2 slots, no hits
      Record::hit(3, 0, 0, 0, 0, 1), Record::hit(3, 1, 0, 0, 0, 1), Record::hit(3, 3, 0, 0, 0, 1),
      Record::done(3, 3),                                    // 1 slot of 3 hits and the completion: 4 cycles
      Record::done(4, 5),                                    // COUNT: 3 slots, no hit records
      Record::hit(5, 4, 0, 0, 0, 1), Record::hit(5, 5, 0, 0, 0, 1), Record::done(5, 2),  // 1 + 2 + 1
  };
  const std::vector<JobTiming> t = job_timing(cfg, jobs, recs);
  const uint64_t cycles[] = {7, 1, 2, 4, 3, 4};
  const uint64_t slots[] = {1, 1, 2, 1, 3, 3};
  for (size_t j = 0; j < jobs.size(); ++j) {
    EXPECT_EQ(t[j].cycles, cycles[j]) << "job " << j;
    EXPECT_EQ(t[j].slots, slots[j]) << "job " << j;
    EXPECT_EQ(t[j].points, jobs[j].shell_count) << "job " << j;
  }
  EXPECT_EQ(stream_cycles(t), 7u + 1 + 2 + 4 + 3 + 4 + 1);
}

// Brick lanes (TX 1): a dense-shell slot holds one point, so a dense job of c points takes c slots (an empty one,
// one); the lanes that multiply take ceil(c / LANES).
TEST(Timing, BrickLanesTakeOneDenseShellPointASlot) {
  DeviceConfig cfg;
  cfg.LANES = 4;
  cfg.BL = 3;
  DeviceConfig brick = cfg;
  brick.TX = 1;
  for (uint32_t c : {0u, 1u, 4u, 9u}) {
    EXPECT_EQ(job_slots(cfg, job(0, Mode::All, c)).groups, c == 0 ? 1u : (c + 3) / 4) << c;
    const JobSlots s = job_slots(brick, job(0, Mode::All, c));
    EXPECT_EQ(s.groups, c == 0 ? 1u : c) << c;
    for (uint64_t g = 0; g < c; ++g) EXPECT_EQ(s.end(g) - s.begin(g), 1u) << c << " slot " << g;
  }
  // Nine points, no hits: nine slots a cycle each behind the first slot's latency.
  const std::vector<Job> jobs = {job(0, Mode::Count, 9)};
  const std::vector<JobTiming> t = job_timing(brick, jobs, {Record::done(0, 0)});
  EXPECT_EQ(t[0].slots, 9u);
  EXPECT_EQ(t[0].cycles, uint64_t(kFirstSlotLatency + pipeline_slots(brick) - kPipelineSlots) + 9 - 1);
}

TEST(Timing, FirstStopsEarlyAndSquashesWhatIsInFlight) {
  DeviceConfig cfg;
  cfg.LANES = 1;
  // 20 points, first hit at point 2: slots 0 and 1 (1 cycle each), slot 2 with the hit and the completion (2),
  // then slots 3..7 squashed and one empty slot before the next job's first slot.
  const std::vector<Job> jobs = {job(0, Mode::First, 20), job(1, Mode::All, 0)};
  const std::vector<Record> recs = {Record::hit(0, 2, 0, 0, 0, 2), Record::done(0, 1), Record::done(1, 0)};
  const std::vector<JobTiming> t = job_timing(cfg, jobs, recs);
  EXPECT_EQ(t[0].cycles, 7u + 2 + 1);
  EXPECT_EQ(t[0].slots, 3u + 5 + 1);
  EXPECT_EQ(t[0].points, 3u);
  EXPECT_EQ(t[1].cycles, 1u + 5 + 1);
  // A hit in the last slots: nothing is left to squash beyond the job, and no empty slot.
  const std::vector<Job> near_end = {job(0, Mode::First, 4), job(1, Mode::All, 0)};
  const std::vector<Record> r2 = {Record::hit(0, 1, 0, 0, 0, 2), Record::done(0, 1), Record::done(1, 0)};
  const std::vector<JobTiming> t2 = job_timing(cfg, near_end, r2);
  EXPECT_EQ(t2[0].cycles, 7u + 1 + 1);
  EXPECT_EQ(t2[0].slots, 4u);
  EXPECT_EQ(t2[1].cycles, 1u + 2);
}

TEST(Timing, StreamThatDoesNotBelongToTheJobsIsAnError) {
  DeviceConfig cfg;
  const std::vector<Job> jobs = {job(7, Mode::All, 4)};
  EXPECT_THROW(job_timing(cfg, jobs, {Record::done(8, 0)}), std::invalid_argument);
  EXPECT_THROW(job_timing(cfg, jobs, {Record::hit(7, 4, 0, 0, 0, 1), Record::done(7, 1)}), std::invalid_argument);
  EXPECT_THROW(job_timing(cfg, jobs, {Record::done(7, 0), Record::done(7, 0)}), std::invalid_argument);
  EXPECT_THROW(job_timing(cfg, jobs, {}), std::invalid_argument);
}

}  // namespace
}  // namespace voxcd
