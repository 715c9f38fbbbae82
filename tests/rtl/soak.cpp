// Soak: at least 10^6 generated jobs (every mode, random shells, poses and maps) through the Verilated device in
// batches, each batch on a random lane count with random back-pressure on both output streams (0 to 0.9 stall
// probability per cycle on each), against ref/ with a scoreboard: every record present, none duplicated, none
// reordered, and each job's cycles equal to the always-ready prediction plus the stalls the device counted. Prints
// the totals. Seed: printed; VOXCD_SEED replays; VOXCD_SOAK_JOBS sets the number of jobs.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "tests/rtl/scoreboard.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

TEST(RtlSoak, MillionJobsUnderRandomBackPressure) {
  const uint64_t seed = test::seed(20261123);
  const char* n = std::getenv("VOXCD_SOAK_JOBS");
  const size_t target = n ? size_t(std::strtoull(n, nullptr, 0)) : 1000000;
  std::printf("%zu jobs\n", target);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<int> lanes = rtl_lanes();
  size_t jobs = 0, records = 0, hits = 0, batches = 0;
  uint64_t stalls = 0, lookups = 0;
  while (jobs < target) {
    GenerateOptions g;
    g.seed = rng();
    g.jobs = std::min<size_t>(10000, target - jobs);
    g.cloud_points = 500 + size_t(u(rng) * 3000);
    g.config.LANES = lanes[rng() % lanes.size()];
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    annotate_cycles(v.config, v.jobs, want);
    DeviceOptions opt;
    opt.hit_stall_prob = 0.9 * u(rng);
    opt.done_stall_prob = 0.9 * u(rng);
    opt.stall_seed = rng();
    const std::string what = "batch " + std::to_string(batches) + " (generator seed " + std::to_string(g.seed) +
                             ", lanes " + std::to_string(g.config.LANES) + ", stall " +
                             std::to_string(opt.hit_stall_prob) + "/" + std::to_string(opt.done_stall_prob) + ")";
    auto dev = make_device("rtl", v.config, opt);
    dev->load(v.memory);
    const std::vector<Record> got = dev->run(v.jobs);
    test::scoreboard(want, got, what, stalls);
    if (HasFatalFailure()) return;
    jobs += v.jobs.size();
    records += got.size();
    for (const Record& r : got) hits += r.kind == Record::Hit;
    for (const Job& j : v.jobs) lookups += j.shell_count;
    ++batches;
  }
  std::printf("soak: %zu jobs in %zu batches, %llu lookups, %zu records (%zu hits), %llu stall cycles; lost 0, "
              "duplicated 0, reordered 0\n",
              jobs, batches, (unsigned long long)lookups, records, hits, (unsigned long long)stalls);
  EXPECT_GE(jobs, target);
  EXPECT_GT(stalls, 0u);
  EXPECT_GT(hits, 0u);
}

}  // namespace
}  // namespace voxcd
