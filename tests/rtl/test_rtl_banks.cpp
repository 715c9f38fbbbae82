// Shared voxmap banks on the RTL (docs/contract.md, "Shared voxmap banks"): every banked model the build has
// (rtl_banked_configs()) against ref/, bit-exact and cycle-exact with the conflict cycles the model counts from the
// addresses, and under random back-pressure with the scoreboard. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/rtl/scoreboard.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261125); }

TEST(RtlBanks, BuildHasBankedModelsAtEveryLaneCount) {
  std::vector<int> lanes;
  bool distance = false;
  for (const DeviceConfig& c : rtl_banked_configs()) {
    EXPECT_TRUE(c.banked()) << c.to_string();
    if (c.BANKS == c.LANES && !c.distance()) lanes.push_back(c.LANES);
    distance = distance || c.distance();
  }
  EXPECT_EQ(lanes, (std::vector<int>{1, 2, 4, 8}));
  EXPECT_TRUE(distance) << "no distance device with shared banks";
}

// Every banked model of the build, 2-bit and distance, of every depth.
std::vector<DeviceConfig> banked_models() {
  std::vector<DeviceConfig> out = rtl_banked_configs();
  for (const DeviceConfig& c : rtl_depth_configs())
    if (c.banked()) out.push_back(c);
  return out;
}

// A FIRST job on a distance device with shared banks: the slots behind its hit keep reading (each two rounds: the
// lanes' cells are 4 apart in z, so they ask every parity bank for two words) until the hit reaches the hit test,
// and the empty slots they leave take squashed slots' places (ref/banks.h, first_window). Cycles against the
// timing model, with the job long enough to fill the pipeline behind its hit and too short to.
TEST(RtlBanks, DistanceFirstKeepsReadingBehindItsHit) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : banked_models()) {
    if (!cfg.distance()) continue;
    DeviceMemory mem;
    Job job;
    job.mode = Mode::First;
    job.nx = job.ny = job.nz = 8;
    job.M[0][0] = job.M[1][1] = job.M[2][2] = int64_t(1) << cfg.MF;
    for (int k = 0; k < 64 * cfg.LANES; ++k) mem.shell.push_back({0, 0, int64_t(k % 2) * (4 << cfg.PF)});
    mem.map.assign(map_words(cfg, job), 0);
    for (uint32_t groups : {40u, 5u, 3u, 2u}) {
      job.shell_count = uint32_t(cfg.LANES) * groups;
      const std::vector<Job> jobs = {job, Job{}, job};
      std::vector<Record> want = run_stream(cfg, mem, jobs);
      const std::vector<BankCycles> b = bank_cycles(cfg, mem, jobs, want);
      annotate_cycles(cfg, jobs, want, b);
      if (groups >= 3) {
        EXPECT_GT(b[0].window, 0u) << cfg.to_string() << ": the case must read behind its hit";
      }
      auto dev = make_device("rtl", cfg);
      dev->load(mem);
      const std::vector<Record> got = dev->run(jobs);
      ASSERT_EQ(got.size(), want.size()) << cfg.to_string();
      for (size_t i = 0; i < want.size(); ++i)
        ASSERT_TRUE(got[i].same_as(want[i], true)) << cfg.to_string() << " " << groups << " groups, record " << i
                                                   << ": expected '" << want[i].to_string() << "', got '"
                                                   << got[i].to_string() << "'";
      ++ran;
    }
  }
  EXPECT_GE(ran, 8u);
}

TEST(RtlBanks, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  for (const DeviceConfig& cfg : banked_models()) {
    GenerateOptions g;
    g.seed = seed * 64 + uint64_t(cfg.LANES * 8 + cfg.BANKS + cfg.SB * 100 + cfg.depth * 1000);
    g.jobs = 3000;
    g.config = cfg;
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    const std::vector<uint64_t> conflicts = bank_conflicts(v.config, v.memory, v.jobs, want);
    annotate_cycles(v.config, v.jobs, want, bank_cycles(v.config, v.memory, v.jobs, want));
    auto dev = make_device("rtl", v.config);
    dev->load(v.memory);
    const std::vector<Record> got = dev->run(v.jobs);
    const std::string what = cfg.to_string() + " generator seed " + std::to_string(g.seed);
    test::expect_exact(want, got, what);
    if (HasFatalFailure()) return;
    uint64_t total = 0;
    for (uint64_t c : conflicts) total += c;
    std::printf("%s: %zu jobs, %llu bank conflict cycles\n", cfg.to_string().c_str(), v.jobs.size(),
                (unsigned long long)total);
    if (cfg.LANES > 1) EXPECT_GT(total, v.jobs.size()) << what << ": the jobs must make the banks conflict";
    else EXPECT_EQ(total, 0u) << what << ": one lane never waits for a bank";
  }
}

TEST(RtlBanks, BackPressureLosesNothingAndCyclesAreAccountedFor) {
  const uint64_t seed = test_seed();
  for (const DeviceConfig& cfg : banked_models()) {
    GenerateOptions g;
    g.seed = seed + uint64_t(cfg.LANES * 8 + cfg.BANKS);
    g.jobs = 300;
    g.config = cfg;
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    annotate_cycles(v.config, v.memory, v.jobs, want);
    for (double p : {0.3, 0.7}) {
      DeviceOptions opt;
      opt.hit_stall_prob = p;
      opt.done_stall_prob = 0.9 - p;
      opt.stall_seed = seed ^ uint64_t(cfg.LANES * 100 + cfg.BANKS * 10 + int(p * 10));
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

TEST(RtlBanks, AConfigurationWithoutAModelIsRefusedByName) {
  DeviceConfig cfg;
  cfg.LANES = 4;
  cfg.BANKS = 16;
  try {
    make_device("rtl", cfg);
    ADD_FAILURE() << "an rtl device without a model";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("BANKS 16"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxcd
