// Deeper pipelines on the RTL (DeviceConfig::depth, the RTL's Depth; docs/hardware.md "Pipeline depth"): every
// depth model the build has (rtl_depth_configs(): every depth at LANES 4, the deepest at LANES 1 and 8, with shared
// banks and on distance devices) against ref/, bit-exact and cycle-exact with the timing model at that depth, FIRST's
// early stop and squash included, and under random back-pressure with the scoreboard. The latency of each depth is
// also checked against numbers worked out by hand. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "tests/ref/directed_cases.h"
#include "tests/rtl/scoreboard.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261126); }

// ref/'s stream for the jobs with the timing model's cycles (bank conflicts counted from the memory when banked).
std::vector<Record> expected_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  std::vector<Record> r = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, mem, jobs, r);
  return r;
}

using test::expect_exact;

TEST(RtlDepth, BuildHasEveryDepthAtFourLanesAndTheDeepestElsewhere) {
  std::set<std::pair<int, int>> plain;  // (LANES, depth) of 2-bit devices with a copy per lane
  bool deepest_banked = false, deepest_distance = false;
  for (const DeviceConfig& c : rtl_depth_configs()) {
    EXPECT_GT(c.depth, 0) << c.to_string();
    EXPECT_NE(c.to_string().find(" DEPTH " + std::to_string(c.depth)), std::string::npos) << c.to_string();
    if (!c.distance() && !c.banked()) plain.insert({c.LANES, c.depth});
    deepest_banked = deepest_banked || (c.banked() && c.depth == kMaxDepth);
    deepest_distance = deepest_distance || (c.distance() && c.depth == kMaxDepth);
  }
  for (int d = 1; d <= kMaxDepth; ++d) EXPECT_TRUE(plain.count({4, d})) << "no LANES 4 model at depth " << d;
  EXPECT_TRUE(plain.count({1, kMaxDepth})) << "no LANES 1 model at the deepest depth";
  EXPECT_TRUE(plain.count({8, kMaxDepth})) << "no LANES 8 model at the deepest depth";
  EXPECT_TRUE(deepest_banked) << "no model with shared banks at the deepest depth";
  EXPECT_TRUE(deepest_distance) << "no distance model at the deepest depth";
}

// Hand-worked latency: a stream's first job, one point that hits (ALL), accepted in cycle 0: its slot reaches the
// hit test after the queue register and the 6 + depth slot registers (9 + depth on a distance device), and its
// completion follows its hit record, so the completion carries 1 + (6 + depth) + 1 cycles. A FIRST job that hits
// in its first slot squashes the 5 + depth slots behind it, then leaves one empty slot: the COUNT job after it
// (one slot, its completion only) completes (5 + depth) + 1 + 1 cycles after it.
TEST(RtlDepth, LatencyAndSquashGrowByOneCyclePerDepth) {
  std::vector<DeviceConfig> cfgs = rtl_depth_configs();
  for (int lanes : rtl_lanes()) {
    DeviceConfig c;
    c.LANES = lanes;
    cfgs.push_back(c);
  }
  size_t ran = 0;
  for (const DeviceConfig& cfg : cfgs) {
    if (cfg.distance()) continue;
    const uint64_t n = uint64_t(6 + cfg.depth);
    DeviceMemory mem;
    const uint32_t points = uint32_t(cfg.LANES) * uint32_t(n + 2);  // more slots than the squash window
    for (uint32_t k = 0; k < points; ++k) mem.shell.push_back({0, 0, 0});  // every point in voxel (0, 0, 0)
    mem.map = {uint64_t{kSurface}};                                        // which is surface
    Job one;
    one.tag = 1;
    one.shell_count = 1;
    Job first = one;
    first.tag = 2;
    first.mode = Mode::First;
    first.shell_count = points;
    Job count = one;
    count.tag = 3;
    count.mode = Mode::Count;
    auto dev = make_device("rtl", cfg);
    dev->load(mem);
    const std::vector<Record> got = dev->run({one, first, count});
    const std::string what = cfg.to_string();
    ASSERT_EQ(got.size(), 5u) << what;  // hit, done, hit, done, done
    EXPECT_EQ(*got[1].cycles, 1 + n + 1) << what << ": the first job's latency";
    EXPECT_EQ(*got[3].cycles, 2u) << what << ": FIRST's hit then its completion, right after the previous job";
    EXPECT_EQ(*got[4].cycles, (n - 1) + 1 + 1) << what << ": the COUNT job after FIRST's squashed slots";
    ++ran;
  }
  // Every depth at LANES 4, the deepest at LANES 1 and 8 and with banks, and depth 0 at every lane count built.
  EXPECT_GE(ran, size_t(kMaxDepth + 3) + rtl_lanes().size());
}

TEST(RtlDepth, DirectedCasesAtEveryDepth) {
  size_t ran = 0, two_bit = 0;
  for (const DeviceConfig& model : rtl_depth_configs()) {
    two_bit += !model.distance();
    for (const auto& c : testing::directed_cases()) {
      DeviceConfig cfg = c.config;
      cfg.LANES = model.LANES;
      cfg.BANKS = model.BANKS;
      cfg.depth = model.depth;
      if (!(cfg == model)) continue;  // the case's widths are not this model's
      auto dev = make_device("rtl", cfg);
      dev->load(c.memory);
      const std::vector<Record> got = dev->run(c.jobs);
      const std::string what = c.name + " on " + cfg.to_string();
      // Results against the hand-derived expectations, cycles against the timing model at this depth.
      ASSERT_EQ(got.size(), c.expected.size()) << what;
      for (size_t i = 0; i < got.size(); ++i)
        ASSERT_TRUE(got[i].same_as(c.expected[i], false)) << what << ": record " << i << " '" << got[i].to_string()
                                                          << "', expected '" << c.expected[i].to_string() << "'";
      expect_exact(expected_stream(cfg, c.memory, c.jobs), got, what);
      if (HasFatalFailure()) return;
      ++ran;
    }
  }
  EXPECT_GE(ran, 10u * two_bit) << "most directed cases use the default widths";
}

TEST(RtlDepth, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  size_t jobs = 0, firsts = 0;
  for (const DeviceConfig& cfg : rtl_depth_configs()) {
    GenerateOptions g;
    g.seed = seed * 64 + uint64_t(cfg.LANES * 8 + cfg.depth + cfg.SB * 100 + cfg.BANKS * 1000);
    g.jobs = 3000;
    g.config = cfg;
    const GeneratedVectors v = generate_vectors(g);
    const std::vector<Record> want = expected_stream(v.config, v.memory, v.jobs);
    auto dev = make_device("rtl", v.config);
    dev->load(v.memory);
    expect_exact(want, dev->run(v.jobs), cfg.to_string() + " generator seed " + std::to_string(g.seed));
    if (HasFatalFailure()) return;
    jobs += v.jobs.size();
    for (const Job& j : v.jobs) firsts += j.mode == Mode::First && j.shell_count > uint32_t(cfg.LANES * 12);
  }
  std::printf("%zu jobs, %zu FIRST jobs longer than the squash window\n", jobs, firsts);
  EXPECT_GE(jobs, 3000u * size_t(kMaxDepth + 5));  // the five depths at LANES 4 and five more models
  EXPECT_GT(firsts, jobs / 20) << "the random jobs must exercise FIRST's early stop at every depth";
}

TEST(RtlDepth, BackPressureLosesNothingAndCyclesAreAccountedFor) {
  const uint64_t seed = test_seed();
  for (const DeviceConfig& cfg : rtl_depth_configs()) {
    GenerateOptions g;
    g.seed = seed + uint64_t(cfg.LANES * 8 + cfg.depth + cfg.SB * 100 + cfg.BANKS * 1000);
    g.jobs = 250;
    g.config = cfg;
    const GeneratedVectors v = generate_vectors(g);
    const std::vector<Record> want = expected_stream(v.config, v.memory, v.jobs);
    for (double p : {0.2, 0.6, 0.9}) {
      DeviceOptions opt;
      opt.hit_stall_prob = p;
      opt.done_stall_prob = 0.9 - p / 2;
      opt.stall_seed = seed ^ uint64_t(cfg.LANES * 1000 + cfg.depth * 100 + int(p * 10));
      const std::string what = cfg.to_string() + " stall " + std::to_string(p) + " seed " + std::to_string(seed);
      auto dev = make_device("rtl", v.config, opt);
      dev->load(v.memory);
      uint64_t stalls = 0;
      test::scoreboard(want, dev->run(v.jobs), what, stalls);
      if (HasFatalFailure()) return;
      EXPECT_GT(stalls, 0u) << what << ": back-pressure must have stalled the device";
    }
  }
}

TEST(RtlDepth, ADepthWithoutAModelIsRefusedByName) {
  // A 2-bit device at a depth and lane count the build has no model for (whatever the build's model lists are).
  std::set<std::string> built;
  for (const DeviceConfig& c : rtl_depth_configs()) built.insert(c.to_string());
  ASSERT_FALSE(built.empty());
  DeviceConfig cfg;
  bool found = false;
  for (int lanes : {2, 1, 8, 4})
    for (int d = 1; d <= kMaxDepth && !found; ++d) {
      cfg.LANES = lanes;
      cfg.depth = d;
      found = !built.count(cfg.to_string());
    }
  ASSERT_TRUE(found) << "every 2-bit depth and lane count has a model";
  try {
    make_device("rtl", cfg);
    ADD_FAILURE() << "an rtl device without a model: " << cfg.to_string();
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find(cfg.to_string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(*built.begin()), std::string::npos)
        << "the message lists the depth models there are: " << e.what();
  }
}

}  // namespace
}  // namespace voxcd
