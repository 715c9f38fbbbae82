// Sparse devices on the RTL with random jobs: on every sparse model of the build (rtl_sparse_configs()), generated
// version-3 vectors (sparse maps and shells, dense ones, mixed in one stream: ref/vector_gen.h) bit-exact and
// cycle-exact against ref/'s timing model (a banked model's conflicts, and the windows of FIRST jobs, counted from the
// addresses), and under random back-pressure with the scoreboard. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/rtl/sparse_cases.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261128); }

// What a stream exercises: jobs with a sparse map, a sparse shell, both, neither; hit records; bank conflict cycles
// and FIRST windows.
struct Coverage {
  size_t map = 0, shell = 0, both = 0, dense = 0, hits = 0;
  uint64_t conflicts = 0, windows = 0;
};

Coverage coverage_of(const GeneratedVectors& v, const std::vector<Record>& want) {
  Coverage c;
  for (const Job& j : v.jobs) {
    c.map += j.sparse == kSparseMap;
    c.shell += j.sparse == kSparseShell;
    c.both += j.sparse == (kSparseMap | kSparseShell);
    c.dense += j.sparse == 0;
  }
  for (const Record& r : want) c.hits += r.kind == Record::Hit;
  for (const BankCycles& b : bank_cycles(v.config, v.memory, v.jobs, want)) {
    c.conflicts += b.conflicts;
    c.windows += b.window;
  }
  return c;
}

TEST(RtlSparse, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  size_t models = 0;
  for (const DeviceConfig& cfg : rtl_sparse_configs()) {
    const GeneratedVectors v = test::generated(cfg, seed, 3000);
    const std::string what = cfg.to_string() + " seed " + std::to_string(seed);
    const std::vector<Record> want = test::exact_stream(v.config, v.memory, v.jobs);
    auto dev = make_device("rtl", v.config);
    dev->load(v.memory);
    test::expect_exact(want, dev->run(v.jobs), what);
    if (HasFatalFailure()) return;
    const Coverage c = coverage_of(v, want);
    std::printf("%s: %zu jobs (%zu sparse map, %zu sparse shell, %zu both, %zu dense), %zu hit records, "
                "%llu bank conflict cycles (%llu in FIRST windows)\n",
                cfg.to_string().c_str(), v.jobs.size(), c.map, c.shell, c.both, c.dense, c.hits,
                (unsigned long long)c.conflicts, (unsigned long long)c.windows);
    EXPECT_GT(c.map, 100u) << what;
    EXPECT_GT(c.shell, 100u) << what;
    EXPECT_GT(c.both, 100u) << what;
    EXPECT_GT(c.dense, 100u) << what;
    EXPECT_GT(c.hits, v.jobs.size()) << what << ": the jobs must hit";
    if (cfg.banked() && cfg.LANES > 1) {
      EXPECT_GT(c.conflicts, v.jobs.size()) << what << ": the jobs must make the banks conflict";
      EXPECT_GT(c.windows, 0u) << what << ": FIRST jobs must read behind their hits";
    }
    ++models;
  }
  EXPECT_GE(models, 1u);
}

TEST(RtlSparse, BackPressureLosesNothingAndCyclesAreAccountedFor) {
  const uint64_t seed = test_seed();
  for (const DeviceConfig& cfg : rtl_sparse_configs()) {
    const GeneratedVectors v = test::generated(cfg, seed + 1, 300);
    const std::vector<Record> want = test::exact_stream(v.config, v.memory, v.jobs);
    for (double p : {0.2, 0.5, 0.8}) {
      DeviceOptions opt;
      opt.hit_stall_prob = p;
      opt.done_stall_prob = 0.9 - p;
      opt.stall_seed = seed ^ uint64_t(cfg.LANES * 100 + cfg.BANKS * 10 + int(p * 10) + cfg.SB * 1000);
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

}  // namespace
}  // namespace voxcd
