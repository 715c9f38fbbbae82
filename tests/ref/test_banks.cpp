// Shared voxmap banks (docs/contract.md, "Shared voxmap banks"): the rounds of a slot's reads, the conflict cycles of
// jobs, the configuration's rules, the timing model's refusal to time a banked device blind, the cpu backend's
// cycles (one thread and a pool) against the specification's, and BANKS in vector files. The RTL's banked models
// are checked against the same model in tests/rtl/test_rtl_banks.cpp.
#include <gtest/gtest.h>

#include <memory>
#include <sstream>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/fast/thread_pool.h"
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
  refused(dist, "shared voxmap banks are for 2-bit devices");
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
  EXPECT_THROW(job_timing(v.config, v.jobs, recs, std::vector<uint64_t>(3, 0)), std::invalid_argument);
  EXPECT_NO_THROW(annotate_cycles(v.config, v.memory, v.jobs, recs));
}

TEST(Banks, ConflictsAddToTheCyclesOfTheirJobOnly) {
  const GeneratedVectors v = banked_vectors(8, 2, 12, 400);
  const std::vector<Record> recs = run_stream(v.config, v.memory, v.jobs);
  const std::vector<uint64_t> c = bank_conflicts(v.config, v.memory.shell, v.jobs, recs);
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
  EXPECT_EQ(bank_conflicts(cfg, mem.shell, {job}, recs), (std::vector<uint64_t>{1}))
      << "the hit is in slot 0: its one conflict, none of the three slots behind it";
  job.mode = Mode::Count;
  recs = run_stream(cfg, mem, {job});
  EXPECT_EQ(bank_conflicts(cfg, mem.shell, {job}, recs), (std::vector<uint64_t>{4})) << "four slots of two rounds";
}

TEST(Banks, CpuBackendTimesBankedDevicesAsTheSpecification) {
  for (int threads : {1, 2}) {
    for (auto [lanes, banks] : {std::pair{1, 1}, {2, 2}, {4, 4}, {8, 8}, {8, 2}, {3, 4}}) {
      const GeneratedVectors v = banked_vectors(lanes, banks, 100 + uint64_t(lanes * 10 + banks), 600);
      std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
      annotate_cycles(v.config, v.memory, v.jobs, want);
      FastRunner fr(v.config, threads == 1 ? nullptr : std::make_shared<ThreadPool>(2));
      fr.load(v.memory);
      std::vector<Record> got;
      fr.run_into(v.jobs, got, true);
      const std::string what = "lanes " + std::to_string(lanes) + " banks " + std::to_string(banks) + " threads " +
                               std::to_string(threads);
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
  EXPECT_THROW(parse_config_pairs("SB 8 BANKS 2", "--config"), VectorError);
}

}  // namespace
}  // namespace voxcd
