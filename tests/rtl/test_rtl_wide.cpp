// Wide devices on the RTL (docs/hardware.md, "Wide devices"): every wide model of the build (rtl_wide_configs(): 16
// lanes with reduced memories in every build, 32 and 64 lanes at full size with VOXCD_RTL_WIDE) against ref/,
// bit-exact and cycle-exact (a banked model's conflicts and a sparse shell's slots counted from the addresses), a
// FIRST job stopping at every lane of a wide slot, and under random back-pressure with the scoreboard. Seed: printed;
// VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/rtl/sparse_cases.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261128); }

TEST(RtlWide, BuildHasASixteenLaneDeviceWithCopiesAndOneWithSparseBanks) {
  bool copies = false, sparse_banks = false;
  for (const DeviceConfig& c : rtl_wide_configs()) {
    EXPECT_GE(c.LANES, 16) << c.to_string();
    copies = copies || (c.LANES == 16 && !c.banked() && !c.sparse());
    sparse_banks = sparse_banks || (c.LANES == 16 && c.banked() && c.sparse());
  }
  EXPECT_TRUE(copies) << "no 16-lane device with a voxmap copy per lane (VOXCD_RTL_WIDE_MODELS)";
  EXPECT_TRUE(sparse_banks) << "no 16-lane sparse device with shared banks (VOXCD_RTL_WIDE_MODELS)";
}

TEST(RtlWide, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  size_t models = 0;
  for (const DeviceConfig& cfg : rtl_wide_configs()) {
    const GeneratedVectors v = test::generated(cfg, seed, 2000);
    const std::string what = cfg.to_string() + " seed " + std::to_string(seed);
    const std::vector<Record> want = test::exact_stream(v.config, v.memory, v.jobs);
    auto dev = make_device("rtl", v.config);
    dev->load(v.memory);
    test::expect_exact(want, dev->run(v.jobs), what);
    if (HasFatalFailure()) return;
    uint64_t conflicts = 0, hits = 0;
    for (const BankCycles& b : bank_cycles(v.config, v.memory, v.jobs, want)) conflicts += b.conflicts;
    for (const Record& r : want) hits += r.kind == Record::Hit;
    std::printf("%s: %zu jobs, %llu hit records, %llu bank conflict cycles\n", cfg.to_string().c_str(),
                v.jobs.size(), (unsigned long long)hits, (unsigned long long)conflicts);
    EXPECT_GT(hits, v.jobs.size()) << what << ": the jobs must hit";
    // Brick lanes take a dense-shell slot's one point alone, which never conflicts: their conflicts are the sparse
    // shells'.
    if (cfg.banked()) {
      EXPECT_GT(conflicts, cfg.brick_lanes() ? v.jobs.size() / 4 : v.jobs.size())
          << what << ": the jobs must make the banks conflict";
    }
    ++models;
  }
  EXPECT_GE(models, 2u);
}

// A FIRST job whose only hit is point k, for k at every lane of the first wide slot and past it: the slots issued
// behind the hit are squashed and the job's cycles are the timing model's.
TEST(RtlWide, FirstStopsAtEveryLaneOfAWideSlot) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : rtl_wide_configs()) {
    DeviceMemory mem;
    Job job;
    job.mode = Mode::First;
    job.nx = job.ny = job.nz = 4;
    job.M[0][0] = job.M[1][1] = job.M[2][2] = int64_t(1) << cfg.MF;
    mem.map.assign(map_words(cfg, job), 0);
    mem.map[0] = kSurface;  // voxel (0, 0, 0); every other point lies in an empty voxel
    const uint32_t points = uint32_t(cfg.LANES) * 4;
    std::vector<Job> jobs;
    for (uint32_t k = 0; k < points; k += k < uint32_t(cfg.LANES) ? 1 : 7) {
      job.shell_base = uint32_t(mem.shell.size());
      job.shell_count = points;
      for (uint32_t i = 0; i < points; ++i)
        mem.shell.push_back({int64_t(i == k ? 0 : 2) << cfg.PF, int64_t(i == k ? 0 : 1) << cfg.PF, 0});
      job.tag = k;
      jobs.push_back(job);
    }
    const std::vector<Record> want = test::expect_rtl_exact(cfg, mem, jobs, "FIRST at every lane");
    if (HasFatalFailure()) return;
    size_t hits = 0;
    for (const Record& r : want) hits += r.kind == Record::Hit;
    EXPECT_EQ(hits, jobs.size()) << cfg.to_string() << ": one hit a job";
    ++ran;
  }
  EXPECT_GE(ran, 2u);
}

TEST(RtlWide, BackPressureLosesNothingAndCyclesAreAccountedFor) {
  const uint64_t seed = test_seed();
  for (const DeviceConfig& cfg : rtl_wide_configs()) {
    const GeneratedVectors v = test::generated(cfg, seed + 1, 300);
    const std::vector<Record> want = test::exact_stream(v.config, v.memory, v.jobs);
    for (double p : {0.2, 0.6}) {
      DeviceOptions opt;
      opt.hit_stall_prob = p;
      opt.done_stall_prob = 0.9 - p;
      opt.stall_seed = seed ^ uint64_t(cfg.LANES * 100 + cfg.BANKS * 10 + int(p * 10) + cfg.BL * 1000);
      const std::string what = cfg.to_string() + " stall " + std::to_string(p) + " seed " + std::to_string(seed);
      auto dev = make_device("rtl", v.config, opt);
      dev->load(v.memory);
      uint64_t stalls = 0;
      test::scoreboard(want, dev->run(v.jobs), what, stalls);
      if (HasFatalFailure()) return;
      EXPECT_GT(stalls, 0u) << what;
    }
  }
}

// A wide configuration with no model says how wide models are built.
TEST(RtlWide, AWideConfigurationWithoutAModelSaysHowToBuildOne) {
  DeviceConfig cfg;
  cfg.LANES = 64;
  cfg.depth = 3;
  try {
    make_device("rtl", cfg);
    ADD_FAILURE() << "an rtl device without a model";
  } catch (const std::exception& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("LANES 64"), std::string::npos) << m;
    EXPECT_NE(m.find("-DVOXCD_RTL_WIDE=ON"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace voxcd
