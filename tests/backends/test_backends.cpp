// Every backend this build has gives the same stream as ref/ on the directed cases and on random vectors of
// several configurations (which exercise each arithmetic path of the cpu backend), for any thread count.
// Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdlib>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "tests/ref/directed_cases.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(424242); }

void expect_same(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(got[i].same_as(want[i], false))
        << what << " record " << i << ": expected '" << want[i].to_string() << "', got '" << got[i].to_string()
        << "'";
}

// Backends that run anywhere (rtl and sysc-rtl have their own suites: they only take the widths they were built
// for).
std::vector<std::string> software_backends() {
  std::vector<std::string> out;
  for (const auto& b : device_backends())
    if (b != "rtl" && b != "sysc-rtl") out.push_back(b);
  return out;
}

TEST(Backends, DirectedCases) {
  for (const auto& b : software_backends()) {
    for (const auto& c : testing::directed_cases()) {
      auto dev = make_device(b, c.config);
      dev->load(c.memory);
      expect_same(c.expected, dev->run(c.jobs), b + " " + c.name);
    }
  }
}

struct NamedConfig {
  const char* name;
  DeviceConfig cfg;
};

std::vector<NamedConfig> configs() {
  std::vector<NamedConfig> v;
  v.push_back({"default(double path)", DeviceConfig{}});
  DeviceConfig c;
  c.PW = 14, c.PF = 3, c.MW = 10, c.MF = 8, c.TW = 24, c.DW = 7, c.MEMW = 16;
  v.push_back({"coarse(double path)", c});
  c = DeviceConfig{};
  c.PW = 28, c.PF = 10, c.MW = 24, c.MF = 20, c.TW = 56;
  v.push_back({"wide(int64 path)", c});
  c = DeviceConfig{};
  c.PW = 32, c.PF = 16, c.MW = 26, c.MF = 24, c.TW = 64, c.MEMW = 32;
  v.push_back({"widest(128-bit path)", c});
  return v;
}

TEST(Backends, RandomVectorsOnEveryConfigAndThreadCount) {
  const uint64_t seed = test_seed();
  for (const auto& nc : configs()) {
    GenerateOptions g;
    g.seed = seed;
    g.jobs = 400;
    g.config = nc.cfg;
    const GeneratedVectors v = generate_vectors(g);
    const std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    size_t hits = 0;
    for (const Record& r : want) hits += r.kind == Record::Hit;
    EXPECT_GT(hits, 100u) << nc.name << ": the generated vectors must exercise hits";
    for (const auto& b : software_backends()) {
      for (unsigned threads : {1u, 2u, 3u}) {
        DeviceOptions opt;
        opt.threads = threads;
        auto dev = make_device(b, v.config, opt);
        dev->load(v.memory);
        expect_same(want, dev->run(v.jobs),
                    b + " " + nc.name + " threads " + std::to_string(threads) + " seed " + std::to_string(seed));
      }
    }
  }
}

// Every pipeline depth (DeviceConfig::depth), with a copy per lane and with shared banks: the backends that model
// cycles give ref/'s timing model's exactly, for any thread count.
TEST(Backends, CyclesAtEveryDepth) {
  const uint64_t seed = test_seed();
  for (int banks : {0, 2}) {
    for (int d = 0; d <= kMaxDepth; ++d) {
      GenerateOptions g;
      g.seed = seed + uint64_t(d + 10 * banks);
      g.jobs = 200;
      g.config.LANES = 4;
      g.config.BANKS = banks;
      g.config.depth = d;
      const GeneratedVectors v = generate_vectors(g);
      std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
      annotate_cycles(v.config, v.memory, v.jobs, want);
      for (const auto& b : software_backends()) {
        for (unsigned threads : {1u, 3u}) {
          DeviceOptions opt;
          opt.threads = threads;
          auto dev = make_device(b, v.config, opt);
          if (!dev->models_cycles()) continue;
          dev->load(v.memory);
          const std::vector<Record> got = dev->run(v.jobs);
          const std::string what = b + " " + v.config.to_string() + " threads " + std::to_string(threads);
          ASSERT_EQ(got.size(), want.size()) << what;
          for (size_t i = 0; i < want.size(); ++i)
            ASSERT_TRUE(got[i].same_as(want[i], true)) << what << " record " << i << ": expected '"
                                                       << want[i].to_string() << "', got '" << got[i].to_string() << "'";
        }
      }
    }
  }
}

TEST(Backends, LargeJobsSplitAcrossThreadsKeepOrder) {
  // One job of 60000 points in each mode: it is split into many chunks; FIRST must still report the lowest.
  GenerateOptions g;
  g.seed = test_seed() + 1;
  g.jobs = 0;
  g.cloud_points = 60000;
  GeneratedVectors v = generate_vectors(g);
  Job j;
  j.tag = 1;
  j.shell_count = 60000;
  j.nx = j.ny = j.nz = 16;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = 1 << 14;  // a quarter scale: the cloud of ~46 voxels covers ~12
  j.map_base = 0;
  for (Mode m : {Mode::All, Mode::First, Mode::Count}) {
    j.mode = m;
    v.jobs.push_back(j);
  }
  // Make the map dense so hits abound: every state 1.
  for (auto& w : v.memory.map) w = 0x5555555555555555ull;
  const auto want = run_stream(v.config, v.memory, v.jobs);
  EXPECT_GT(want.size(), 1000u);
  for (const auto& b : software_backends()) {
    DeviceOptions opt;
    opt.threads = 2;
    auto dev = make_device(b, v.config, opt);
    dev->load(v.memory);
    expect_same(want, dev->run(v.jobs), b);
  }
}

TEST(Backends, InvalidJobIsRejectedBeforeAnyRuns) {
  for (const auto& b : software_backends()) {
    auto dev = make_device(b, DeviceConfig{});
    DeviceMemory m;
    m.shell.resize(4);
    m.map.resize(1);
    dev->load(m);
    Job ok;
    ok.shell_count = 4;
    Job bad = ok;
    bad.tag = 3;
    bad.shell_count = 5;
    try {
      dev->run({ok, bad});
      ADD_FAILURE() << b << " accepted a job past the loaded shell";
    } catch (const JobError& e) {
      EXPECT_NE(std::string(e.what()).find("job tag 3"), std::string::npos) << e.what();
    }
  }
}

TEST(Backends, UnknownBackendNamesTheOnesThatExist) {
  try {
    make_device("gpu", DeviceConfig{});
    ADD_FAILURE();
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown backend 'gpu'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("ref"), std::string::npos);
  }
}

}  // namespace
}  // namespace voxcd
