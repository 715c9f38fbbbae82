// Shared voxmap banks (docs/contract.md, "Shared voxmap banks"): the rounds of a slot's reads, the conflict cycles of
// jobs, the configuration's rules, the timing model's refusal to time a banked device blind, the cpu backend's
// cycles (one thread and a pool) against the specification's, and BANKS in vector files. The RTL's banked models
// are checked against the same model in tests/rtl/test_rtl_banks.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <tuple>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {
namespace {

TEST(Banks, RoundsAreTheMostDistinctWordsOfOneBank) {
  EXPECT_EQ(bank_rounds(4, {}), 1u);                 // no lane reads: the slot passes in one cycle
  EXPECT_EQ(bank_rounds(4, {7}), 1u);
  EXPECT_EQ(bank_rounds(4, {0, 1, 2, 3}), 1u);       // one word in each bank
  EXPECT_EQ(bank_rounds(4, {5, 5, 5, 5}), 1u);       // one word for every lane: one read serves them all
  EXPECT_EQ(bank_rounds(4, {0, 4, 8, 1}), 3u);       // bank 0 holds three of them
  EXPECT_EQ(bank_rounds(4, {0, 4, 0, 4}), 2u);
  EXPECT_EQ(bank_rounds(1, {3, 9, 3, 12}), 3u);      // one bank: every distinct word is a round
  EXPECT_EQ(bank_rounds(2, {0, 2, 4, 6, 1, 3, 5, 7}), 4u);
  EXPECT_EQ(bank_rounds(0, {0, 4, 8}), 1u);          // a copy per lane never waits
}

TEST(Banks, ConfigurationRules) {
  DeviceConfig c;
  c.BANKS = 4;
  EXPECT_NO_THROW(c.validate());
  EXPECT_EQ(c.voxmap_copies(), 1);
  EXPECT_NE(c.to_string().find(" BANKS 4"), std::string::npos);
  DeviceConfig copies;
  EXPECT_EQ(copies.voxmap_copies(), copies.LANES);
  EXPECT_EQ(copies.to_string().find("BANKS"), std::string::npos) << "a device with copies keeps its text";
  EXPECT_TRUE(c.same_widths(copies)) << "BANKS changes timing, never results";
  EXPECT_NE(c, copies);
  auto refused = [](DeviceConfig d, const std::string& words) {
    try {
      d.validate();
      ADD_FAILURE() << "accepted " << d.to_string();
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  c.BANKS = 3;
  refused(c, "BANKS = 3 is not a power of two");
  c.BANKS = 128;
  refused(c, "BANKS = 128 is outside 1..64");
  c.BANKS = -1;
  refused(c, "BANKS = -1");
  c.BANKS = 8;
  c.MAW = 2;
  refused(c, "more than the 2^MAW");
  DeviceConfig dist;
  dist.SB = 8;
  dist.BANKS = 2;
  EXPECT_NO_THROW(dist.validate()) << "a distance device shares its 8 parity banks too";
  EXPECT_EQ(memory_banks(dist), 16);
  dist.MAW = 6;
  dist.BANKS = 16;
  refused(dist, "8 * BANKS = 128 banks (each parity bank split BANKS = 16 ways) are more than the 2^MAW = 64");
}

GeneratedVectors banked_vectors(int lanes, int banks, uint64_t seed, size_t jobs) {
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.config.LANES = lanes;
  g.config.BANKS = banks;
  return generate_vectors(g);
}

TEST(Banks, TimingABankedDeviceNeedsItsReads) {
  const GeneratedVectors v = banked_vectors(4, 4, 11, 50);
  std::vector<Record> recs = run_stream(v.config, v.memory, v.jobs);
  EXPECT_THROW(annotate_cycles(v.config, v.jobs, recs), std::invalid_argument);
  EXPECT_THROW(job_timing(v.config, v.jobs, recs), std::invalid_argument);
  EXPECT_THROW(job_timing(v.config, v.jobs, recs, std::vector<BankCycles>(3)), std::invalid_argument);
  EXPECT_NO_THROW(annotate_cycles(v.config, v.memory, v.jobs, recs));
}

TEST(Banks, ConflictsAddToTheCyclesOfTheirJobOnly) {
  const GeneratedVectors v = banked_vectors(8, 2, 12, 400);
  const std::vector<Record> recs = run_stream(v.config, v.memory, v.jobs);
  const std::vector<uint64_t> c = bank_conflicts(v.config, v.memory, v.jobs, recs);
  DeviceConfig copies = v.config;
  copies.BANKS = 0;
  const std::vector<JobTiming> with = job_timing(v.config, v.memory, v.jobs, recs);
  const std::vector<JobTiming> without = job_timing(copies, v.jobs, recs);
  uint64_t total = 0, jobs_with = 0;
  for (size_t j = 0; j < v.jobs.size(); ++j) {
    // The job's first slot follows the previous job by the previous job's own cycles: its conflicts land in it.
    EXPECT_EQ(with[j].cycles, without[j].cycles + c[j]) << "job " << j;
    total += c[j];
    jobs_with += c[j] > 0;
  }
  EXPECT_GT(jobs_with, v.jobs.size() / 8) << "8 lanes over 2 banks must conflict often";
  EXPECT_GT(total, v.jobs.size());
  std::printf("%llu conflict cycles in %llu of %zu jobs\n", (unsigned long long)total, (unsigned long long)jobs_with,
              v.jobs.size());
}

TEST(Banks, FirstStopsCountingAtTheSlotOfItsHit) {
  // A FIRST job whose lanes all read different words of one bank: each slot up to the hit's waits LANES - 1
  // cycles, the slots behind the hit never read.
  DeviceConfig cfg;
  cfg.LANES = 4;
  cfg.BANKS = 1;
  DeviceMemory mem;
  Job job;
  job.mode = Mode::First;
  job.hit_mask = 0b0010;
  job.nx = 64, job.ny = 1, job.nz = 1;
  job.shell_count = 16;
  job.M[0][0] = job.M[1][1] = job.M[2][2] = int64_t(1) << cfg.MF;
  // Point k at voxel x = 32 k mod 64 ... in words of 32 states: points 0..3 read words 0, 1, 0, 1 (two rounds).
  for (int k = 0; k < 16; ++k) mem.shell.push_back({int64_t(k % 2) * 32 << cfg.PF, 0, 0});
  mem.map.assign(2, 0);
  mem.map[1] = uint64_t(1) << (2 * 0);  // voxel 32 (word 1, slot 0) holds state 1: every odd point hits
  std::vector<Record> recs = run_stream(cfg, mem, {job});
  ASSERT_EQ(recs.size(), 2u);
  EXPECT_EQ(recs[0].point, 1u);
  EXPECT_EQ(bank_conflicts(cfg, mem, {job}, recs), (std::vector<uint64_t>{1}))
      << "the hit is in slot 0: its one conflict, none of the three slots behind it";
  job.mode = Mode::Count;
  recs = run_stream(cfg, mem, {job});
  EXPECT_EQ(bank_conflicts(cfg, mem, {job}, recs), (std::vector<uint64_t>{4})) << "four slots of two rounds";
}

// A distance device's lane reads the 8 node words of its cell, one from each parity bank; with BANKS = 1 two lanes
// whose cells are 4 apart in z read different words of every parity bank: two rounds a slot. A FIRST job that hits in
// slot 0 still reads behind its hit for the kDistanceSlots rounds its hit takes to reach the hit test: slot 1 (two
// rounds, one empty slot) and the first round of slot 2 (another), worked out by hand against the timing model.
TEST(Banks, DistanceDevicesReadEightWordsAndKeepReadingBehindAFirstHit) {
  DeviceConfig cfg;
  cfg.SB = 8;
  cfg.LANES = 2;
  cfg.BANKS = 1;
  ASSERT_EQ(memory_banks(cfg), 8);
  ASSERT_EQ(pipeline_places(cfg).hit_known - pipeline_places(cfg).table_read - 1, kDistanceSlots);
  DeviceMemory mem;
  Job job;
  job.mode = Mode::First;
  job.nx = job.ny = job.nz = 8;  // H = 5: half-indices 0 and 50 (z = 4), in words 0 and 6 of every bank
  job.M[0][0] = job.M[1][1] = job.M[2][2] = int64_t(1) << cfg.MF;
  for (int k = 0; k < 40; ++k) mem.shell.push_back({0, 0, int64_t(k % 2) * (4 << cfg.PF)});
  mem.map.assign(map_words(cfg, job), 0);  // every node 0: D = 0 <= the threshold 0, every point hits
  for (uint32_t groups : {20u, 5u}) {
    job.shell_count = 2 * groups;
    const std::vector<Record> recs = run_stream(cfg, mem, {job, Job{}});
    ASSERT_EQ(recs.size(), 3u);
    EXPECT_EQ(recs[0].point, 0u);
    EXPECT_EQ(slot_rounds(cfg, mem.map, job, job_points(cfg, mem.shell, job), job_slots(cfg, job), 0).table, 2u);
    const std::vector<BankCycles> b = bank_cycles(cfg, mem, {job, Job{}}, recs);
    EXPECT_EQ(b[0].conflicts, 3u) << "slot 0's conflict and the window's two empty slots";
    EXPECT_EQ(b[0].window, 2u);
    const std::vector<JobTiming> t = job_timing(cfg, {job, Job{}}, recs, b);
    const uint64_t P = uint64_t(pipeline_slots(cfg));  // 9
    EXPECT_EQ(t[0].cycles, 1 + P + 1 + 1) << "the hit slot's conflict, then its hit record and its completion";
    // Behind the hit: P slot registers' worth when the job has groups enough (the empty slots take squashed slots'
    // places), else its groups left and the empty slots.
    EXPECT_EQ(t[1].cycles, groups == 20 ? 1 + P : 1 + (groups - 1) + 2) << groups << " groups";
  }
}

TEST(Banks, CpuBackendTimesBankedDevicesAsTheSpecification) {
  for (int threads : {1, 2}) {
    for (auto [lanes, banks, sb] : {std::tuple{1, 1, 2}, {2, 2, 2}, {4, 4, 2}, {8, 8, 2}, {8, 2, 2}, {3, 4, 2},
                                    {4, 1, 8}, {2, 2, 4}}) {
      GenerateOptions g;
      g.seed = 100 + uint64_t(lanes * 10 + banks);
      g.jobs = 600;
      g.config.LANES = lanes;
      g.config.BANKS = banks;
      g.config.SB = sb;
      const GeneratedVectors v = generate_vectors(g);
      std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
      annotate_cycles(v.config, v.memory, v.jobs, want);
      FastRunner fr(v.config, threads == 1 ? nullptr : std::make_shared<ThreadPool>(2));
      fr.load(v.memory);
      std::vector<Record> got;
      fr.run_into(v.jobs, got, true);
      const std::string what = v.config.to_string() + " threads " + std::to_string(threads);
      ASSERT_EQ(got.size(), want.size()) << what;
      for (size_t i = 0; i < want.size(); ++i)
        ASSERT_TRUE(got[i].same_as(want[i], true))
            << what << " record " << i << ": expected '" << want[i].to_string() << "', got '" << got[i].to_string()
            << "'";
    }
  }
}

TEST(Banks, VectorFilesCarryBanks) {
  const GeneratedVectors v = banked_vectors(4, 2, 7, 20);
  std::vector<Record> recs = run_stream(v.config, v.memory, v.jobs);
  annotate_cycles(v.config, v.memory, v.jobs, recs);
  std::ostringstream text;
  write_vectors(text, v.config, true, v.memory, v.jobs, recs);
  EXPECT_NE(text.str().find(" BANKS 2"), std::string::npos);
  const VectorFile f = parse_vectors(text.str(), "banked.vec");
  EXPECT_TRUE(f.has_banks);
  EXPECT_EQ(f.config, v.config);
  EXPECT_THROW(parse_vectors("voxcd-vectors 1\nconfig BANKS 3\n", "bad.vec"), VectorError);
  EXPECT_EQ(parse_config_pairs("SB 8 BANKS 2", "--config").BANKS, 2) << "distance devices share banks too";
  EXPECT_THROW(parse_config_pairs("SB 8 BANKS 64 MAW 8", "--config"), VectorError);
}

}  // namespace
}  // namespace voxcd
