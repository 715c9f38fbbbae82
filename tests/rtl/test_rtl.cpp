// The RTL against ref/: every directed case, 25000 random jobs on each lane count of the build (1, 2, 4 and 8 by
// default) with bit-exact streams and exact cycles (ref/timing.h), and random back-pressure on both output streams
// with a scoreboard. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "tests/ref/directed_cases.h"
#include "tests/rtl/built_lanes.h"
#include "tests/rtl/scoreboard.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261123); }

std::vector<Record> expected_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  std::vector<Record> r = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, jobs, r);
  return r;
}

// Fails on the first record that differs: the job (tag and index), the record, both values and the seed.
void expect_stream(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what,
                   bool cycles) {
  size_t job = 0;
  for (size_t i = 0; i < want.size() && i < got.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], cycles))
        << what << ": job " << job << " (tag " << want[i].tag << ") record " << i << ": expected '"
        << want[i].to_string() << "', got '" << got[i].to_string() << "'";
    if (cycles && want[i].kind == Record::Done) {
      ASSERT_TRUE(got[i].cycles.has_value()) << what;
      ASSERT_EQ(*got[i].points, *want[i].points) << what << ": job " << job << " points";
      ASSERT_EQ(*got[i].stalls, 0u) << what << ": job " << job << " stalls with an always-ready consumer";
    }
    if (want[i].kind == Record::Done) ++job;
  }
  ASSERT_EQ(got.size(), want.size()) << what << ": record count";
}

// Every lane count of VOXCD_RTL_LANES (1, 2, 4 and 8 by default), through the module the library loads.
TEST(Rtl, BuildHasEveryLaneCount) {
  EXPECT_EQ(rtl_unavailable(), "");
  std::vector<int> built = {VOXCD_BUILT_LANES};
  std::sort(built.begin(), built.end());
  EXPECT_EQ(rtl_lanes(), built);
}

TEST(Rtl, DirectedCasesOnEveryLaneCount) {
  size_t ran = 0;
  for (int lanes : rtl_lanes()) {
    for (const auto& c : testing::directed_cases()) {
      DeviceConfig cfg = c.config;
      cfg.LANES = lanes;
      DeviceConfig built;
      built.LANES = lanes;
      if (!cfg.same_widths(built)) continue;  // the models are built for the default widths
      auto dev = make_device("rtl", cfg);
      dev->load(c.memory);
      const std::vector<Record> got = dev->run(c.jobs);
      // Results against the hand-derived expectations, cycles against the timing model.
      expect_stream(c.expected, got, c.name + " lanes " + std::to_string(lanes), false);
      expect_stream(expected_stream(cfg, c.memory, c.jobs), got, c.name + " lanes " + std::to_string(lanes), true);
      ++ran;
    }
  }
  EXPECT_GE(ran, rtl_lanes().size() * 15u) << "most directed cases use the default widths";
}

TEST(Rtl, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  size_t jobs = 0, lookups = 0, hits = 0;
  for (int lanes : rtl_lanes()) {
    for (int part = 0; part < 5; ++part) {
      GenerateOptions g;
      g.seed = seed * 16 + uint64_t(lanes) * 5 + uint64_t(part);
      g.jobs = 5000;
      g.config.LANES = lanes;
      const GeneratedVectors v = generate_vectors(g);
      const std::vector<Record> want = expected_stream(v.config, v.memory, v.jobs);
      auto dev = make_device("rtl", v.config);
      dev->load(v.memory);
      expect_stream(want, dev->run(v.jobs),
                    "lanes " + std::to_string(lanes) + " generator seed " + std::to_string(g.seed), true);
      jobs += v.jobs.size();
      for (const Job& j : v.jobs) lookups += j.shell_count;
      for (const Record& r : want) hits += r.kind == Record::Hit;
    }
  }
  std::printf("%zu jobs, %zu lookups, %zu hit records\n", jobs, lookups, hits);
  EXPECT_GE(jobs, rtl_lanes().size() * 25000u);
  EXPECT_GT(hits, jobs) << "the random jobs must exercise hits";
}

TEST(Rtl, BackPressureLosesNothingAndCyclesAreAccountedFor) {
  const uint64_t seed = test_seed();
  const double probs[] = {0.0, 0.1, 0.3, 0.5, 0.7, 0.9};
  for (int lanes : rtl_lanes()) {
    GenerateOptions g;
    g.seed = seed + uint64_t(lanes);
    g.jobs = 400;
    g.config.LANES = lanes;
    const GeneratedVectors v = generate_vectors(g);
    const std::vector<Record> want = expected_stream(v.config, v.memory, v.jobs);
    for (double ph : probs) {
      for (double pd : {0.0, ph, 0.9 - ph}) {
        DeviceOptions opt;
        opt.hit_stall_prob = ph;
        opt.done_stall_prob = pd;
        opt.stall_seed = seed ^ uint64_t(lanes * 1000 + int(ph * 10) * 10 + int(pd * 10));
        const std::string what = "lanes " + std::to_string(lanes) + " hit stall " + std::to_string(ph) +
                                 " done stall " + std::to_string(pd) + " seed " + std::to_string(seed);
        auto dev = make_device("rtl", v.config, opt);
        dev->load(v.memory);
        const std::vector<Record> got = dev->run(v.jobs);
        // Scoreboard: the same records in the same order (none lost, duplicated or reordered), cycles accounted.
        uint64_t stalls = 0;
        test::scoreboard(want, got, what, stalls);
        if (HasFatalFailure()) return;
        if (ph > 0 || pd > 0) EXPECT_GT(stalls, 0u) << what << ": back-pressure must have stalled the device";
        else EXPECT_EQ(stalls, 0u) << what;
      }
    }
  }
}

TEST(Rtl, TraceWritesAWaveform) {
  const auto& c = testing::directed_cases().front();
  const std::string path = ::testing::TempDir() + "voxcd_rtl_trace.fst";
  std::remove(path.c_str());
  {
    DeviceOptions opt;
    opt.trace_path = path;
    DeviceConfig cfg = c.config;
    cfg.LANES = built_rtl_lanes(2);
    auto dev = make_device("rtl", cfg, opt);
    dev->load(c.memory);
    dev->run(c.jobs);
  }
  FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr) << path;
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fclose(f);
  EXPECT_GT(size, 1000) << "an FST file with the design's signals";
}

TEST(Rtl, OtherWidthsAndLaneCountsAreRefusedByName) {
  DeviceConfig c;
  c.PW = 20;
  try {
    make_device("rtl", c);
    ADD_FAILURE() << "a model for PW 20 does not exist";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("PW 20"), std::string::npos) << e.what();
  }
  c = DeviceConfig{};
  c.LANES = 3;
  try {
    make_device("rtl", c);
    ADD_FAILURE() << "a model for LANES 3 does not exist";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("LANES 3"), std::string::npos) << e.what();
  }
}

TEST(Rtl, InvalidJobIsRejectedBeforeAnyRuns) {
  auto dev = make_device("rtl", DeviceConfig{});
  DeviceMemory m;
  m.shell.resize(4);
  m.map.resize(1);
  dev->load(m);
  Job ok;
  ok.shell_count = 4;
  Job bad = ok;
  bad.tag = 3;
  bad.nx = 0;
  try {
    dev->run({ok, bad});
    ADD_FAILURE() << "the rtl backend accepted a 0-voxel map";
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("job tag 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxcd
