// Shared voxmap banks on the RTL (docs/contract.md, "Shared voxmap banks"): every banked model the build has
// (rtl_banked_configs()) against ref/, bit-exact and cycle-exact with the conflict cycles the model counts from the
// addresses, and under random back-pressure with the scoreboard. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "tests/rtl/scoreboard.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd {
namespace {

uint64_t test_seed() {
  const char* s = std::getenv("VOXCD_SEED");
  const uint64_t seed = s ? std::strtoull(s, nullptr, 0) : 20261125;
  std::printf("seed %llu (replay with VOXCD_SEED=%llu)\n", (unsigned long long)seed, (unsigned long long)seed);
  return seed;
}

TEST(RtlBanks, BuildHasBankedModelsAtEveryLaneCount) {
  std::vector<int> lanes;
  for (const DeviceConfig& c : rtl_banked_configs()) {
    EXPECT_TRUE(c.banked()) << c.to_string();
    if (c.BANKS == c.LANES) lanes.push_back(c.LANES);
  }
  EXPECT_EQ(lanes, (std::vector<int>{1, 2, 4, 8}));
}

TEST(RtlBanks, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  for (const DeviceConfig& cfg : rtl_banked_configs()) {
    GenerateOptions g;
    g.seed = seed * 64 + uint64_t(cfg.LANES * 8 + cfg.BANKS);
    g.jobs = 3000;
    g.config = cfg;
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    const std::vector<uint64_t> conflicts = bank_conflicts(v.config, v.memory.shell, v.jobs, want);
    annotate_cycles(v.config, v.jobs, want, conflicts);
    auto dev = make_device("rtl", v.config);
    dev->load(v.memory);
    const std::vector<Record> got = dev->run(v.jobs);
    const std::string what = cfg.to_string() + " generator seed " + std::to_string(g.seed);
    size_t job = 0;
    for (size_t i = 0; i < want.size() && i < got.size(); ++i) {
      ASSERT_TRUE(got[i].same_as(want[i], true))
          << what << ": job " << job << " (tag " << want[i].tag << ", " << conflicts[job]
          << " conflict cycles) record " << i << ": expected '" << want[i].to_string() << "', got '"
          << got[i].to_string() << "'";
      if (want[i].kind == Record::Done) {
        ASSERT_EQ(*got[i].points, *want[i].points) << what << ": job " << job << " points";
        ASSERT_EQ(*got[i].stalls, 0u) << what << ": job " << job << " stalls with an always-ready consumer";
        ++job;
      }
    }
    ASSERT_EQ(got.size(), want.size()) << what << ": record count";
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
  for (const DeviceConfig& cfg : rtl_banked_configs()) {
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
