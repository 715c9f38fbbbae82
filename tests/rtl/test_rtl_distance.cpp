// The distance devices (SB > 2, docs/contract.md "Distance voxmaps") of the RTL against ref/: every distance model
// the build has (rtl_distance_configs()), numbered directed cases with hand-derived distances, random jobs
// bit-exact and cycle-exact, and random back-pressure on both output streams with the scoreboard. Seed: printed;
// VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "tests/rtl/scoreboard.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261124); }

std::vector<DeviceConfig> distance_models() { return rtl_distance_configs(); }

std::vector<Record> expected_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  std::vector<Record> r = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, jobs, r);
  return r;
}

// Fails on the first record that differs (distances included), then on the count.
void expect_stream(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what,
                   bool cycles) {
  size_t job = 0;
  for (size_t i = 0; i < want.size() && i < got.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], cycles))
        << what << ": job " << job << " (tag " << want[i].tag << ") record " << i << ": expected '"
        << want[i].to_string(true) << "', got '" << got[i].to_string(true) << "'";
    if (cycles && want[i].kind == Record::Done) {
      ASSERT_EQ(*got[i].points, *want[i].points) << what << ": job " << job << " points";
      ASSERT_EQ(*got[i].stalls, 0u) << what << ": job " << job << " stalls with an always-ready consumer";
    }
    if (want[i].kind == Record::Done) ++job;
  }
  ASSERT_EQ(got.size(), want.size()) << what << ": record count";
}

TEST(RtlDistance, BuildHasDistanceModels) {
  std::vector<int> sb8_lanes;
  bool sb4 = false, sb16 = false;
  for (const DeviceConfig& c : distance_models()) {
    if (c.SB == 8) sb8_lanes.push_back(c.LANES);
    sb4 = sb4 || c.SB == 4;
    sb16 = sb16 || c.SB == 16;
  }
  EXPECT_EQ(sb8_lanes, (std::vector<int>{1, 2, 4, 8})) << "SB 8 WB 8 on every lane count";
  EXPECT_TRUE(sb4 && sb16) << "SB 4 and SB 16 on one lane count each";
}

// ---- Directed cases ----

struct DistCase {
  std::string name;
  DeviceMemory memory;
  std::vector<Job> jobs;
  std::vector<Record> expected;  // derived by hand (cycles from the timing model)
};

// One map of a case: its job fields, and the node values written through ref/'s layout function.
struct NodeMap {
  const DeviceConfig& cfg;
  DeviceMemory& mem;
  Job map;  // map_base, nx, ny, nz
  NodeMap(const DeviceConfig& c, DeviceMemory& m, uint32_t base, uint32_t nx, uint32_t ny, uint32_t nz)
      : cfg(c), mem(m) {
    map.map_base = base;
    map.nx = nx;
    map.ny = ny;
    map.nz = nz;
    const uint64_t end = base + map_words(cfg, map);
    if (mem.map.size() < end) mem.map.resize(end, 0);
  }
  void set(uint64_t X, uint64_t Y, uint64_t Z, int64_t q) {
    const NodeAddress a = node_address(cfg, map, X, Y, Z);
    const uint64_t mask = (uint64_t{1} << cfg.SB) - 1, shift = uint64_t(cfg.SB) * a.slot;
    mem.map[a.word] = (mem.map[a.word] & ~(mask << shift)) | ((uint64_t(q) & mask) << shift);
  }
  void fill(const std::function<int64_t(uint64_t, uint64_t, uint64_t)>& q) {
    for (uint64_t Z = 0; Z <= map.nz; ++Z)
      for (uint64_t Y = 0; Y <= map.ny; ++Y)
        for (uint64_t X = 0; X <= map.nx; ++X) set(X, Y, Z, q(X, Y, Z));
  }
  // A job over shell words [base, base + count) with the identity pose plus translation t (raw, TF bits).
  Job job(uint32_t tag, Mode mode, uint32_t base, uint32_t count, int64_t threshold, int64_t t = 0) const {
    Job j = map;
    j.tag = tag;
    j.mode = mode;
    j.shell_base = base;
    j.shell_count = count;
    j.threshold = threshold;
    for (int i = 0; i < 3; ++i) {
      j.M[i][i] = int64_t{1} << cfg.MF;
      j.t[i] = t;
    }
    return j;
  }
};

int64_t iw_max(const DeviceConfig& c) { return c.IW() >= 64 ? INT64_MAX : (int64_t{1} << (c.IW() - 1)) - 1; }
int64_t iw_min(const DeviceConfig& c) { return -iw_max(c) - 1; }
int64_t qmax(const DeviceConfig& c) { return (int64_t{1} << (c.SB - 1)) - 1; }
int64_t qmin(const DeviceConfig& c) { return -qmax(c) - 1; }
ShellWord point(int64_t x, int64_t y, int64_t z) { return ShellWord{x, y, z}; }  // raw: PF fraction bits

std::vector<DistCase> directed(const DeviceConfig& cfg) {
  std::vector<DistCase> out;
  const int64_t one = int64_t{1} << cfg.PF;          // a voxel in shell units
  const int64_t U = int64_t{1} << (3 * cfg.WB);      // a node unit at full weight
  const int64_t W = int64_t{1} << cfg.WB;            // the weights' sum per axis
  const auto q_of = [](uint64_t X, uint64_t Y, uint64_t Z) { return int64_t((X + 2 * Y + 3 * Z) % 15) - 7; };

  {  // 01: every point exactly on a cell's corner node (all fractions 0): D = that node's value * 2^(3 WB); the
     // points on the map's far faces (x = nx, ...) are outside.
    DistCase c{"01_points_on_nodes", {}, {}, {}};
    NodeMap m(cfg, c.memory, 8, 5, 3, 2);
    m.fill(q_of);
    uint32_t k = 0, hits = 0;
    for (int64_t Z = 0; Z <= 2; ++Z)
      for (int64_t Y = 0; Y <= 3; ++Y)
        for (int64_t X = 0; X <= 5; ++X, ++k) {
          c.memory.shell.push_back(point(X * one, Y * one, Z * one));
          if (X < 5 && Y < 3 && Z < 2) {
            c.expected.push_back(Record::hit(1, k, uint32_t(X), uint32_t(Y), uint32_t(Z), 0,
                                             q_of(uint64_t(X), uint64_t(Y), uint64_t(Z)) * U));
            ++hits;
          }
        }
    c.jobs.push_back(m.job(1, Mode::All, 0, k, iw_max(cfg)));
    c.expected.push_back(Record::done(1, hits));
    out.push_back(c);
  }
  {  // 02: the largest fraction, 2^WB - 1: a point one shell unit below the next node (PF >= WB here: the top WB
     // bits are all ones), and a translation one TF ulp below an integer (the bits below the top WB are dropped).
    DistCase c{"02_fraction_all_ones", {}, {}, {}};
    NodeMap m(cfg, c.memory, 0, 4, 1, 1);
    m.fill([&](uint64_t X, uint64_t, uint64_t) { return X % 2 ? qmax(cfg) : qmin(cfg); });
    const int64_t f = W - 1;
    for (int64_t X = 0; X < 4; ++X) c.memory.shell.push_back(point(X * one + one - 1, 0, 0));
    // Along x only: D = (q0 * (W - f) + q1 * f) * W^2.
    for (uint32_t X = 0; X < 4; ++X) {
      const int64_t q0 = X % 2 ? qmax(cfg) : qmin(cfg), q1 = X % 2 ? qmin(cfg) : qmax(cfg);
      c.expected.push_back(Record::hit(2, X, X, 0, 0, 0, (q0 * (W - f) + q1 * f) * W * W));
    }
    c.jobs.push_back(m.job(2, Mode::All, 0, 4, iw_max(cfg)));
    c.expected.push_back(Record::done(2, 4));
    // The same points shifted by one ulp below a voxel on every axis, from voxel -1: cells (X, 0, 0) still, every
    // fraction 2^WB - 1; the x term as above, and y and z weights f on the far nodes (the same values here).
    c.memory.shell.push_back(point(0, 0, 0));
    const int64_t t = (int64_t{1} << cfg.TF()) - 1;
    const int64_t q0 = qmin(cfg), q1 = qmax(cfg);
    c.jobs.push_back(m.job(3, Mode::All, 4, 1, iw_max(cfg), t));
    c.expected.push_back(Record::hit(3, 0, 0, 0, 0, 0, (q0 * (W - f) + q1 * f) * W * W));
    c.expected.push_back(Record::done(3, 1));
    out.push_back(c);
  }
  {  // 03: clamped extremes and thresholds at IW's extremes. All nodes at the smallest value: D = -2^(IW-1), the
     // smallest threshold, so a point hits at threshold -2^(IW-1); all at the largest: a hit at the largest threshold
     // and none one unit below D; alternating extremes at the cell's centre: D = 4*(qmax + qmin) * 2^(3WB-3).
    DistCase c{"03_extremes_and_iw_thresholds", {}, {}, {}};
    NodeMap lo(cfg, c.memory, 0, 1, 1, 1), hi(cfg, c.memory, 8, 1, 1, 1), alt(cfg, c.memory, 16, 1, 1, 1);
    lo.fill([&](uint64_t, uint64_t, uint64_t) { return qmin(cfg); });
    hi.fill([&](uint64_t, uint64_t, uint64_t) { return qmax(cfg); });
    alt.fill([&](uint64_t X, uint64_t Y, uint64_t Z) { return (X + Y + Z) % 2 ? qmax(cfg) : qmin(cfg); });
    c.memory.shell.push_back(point(one / 2, one / 2, one / 2));
    c.memory.shell.push_back(point(one - 1, 0, one / 4));
    const int64_t dlo = qmin(cfg) * U, dhi = qmax(cfg) * U;
    EXPECT_EQ(dlo, iw_min(cfg));
    c.jobs.push_back(lo.job(10, Mode::All, 0, 2, iw_min(cfg)));
    c.expected.push_back(Record::hit(10, 0, 0, 0, 0, 0, dlo));
    c.expected.push_back(Record::hit(10, 1, 0, 0, 0, 0, dlo));
    c.expected.push_back(Record::done(10, 2));
    c.jobs.push_back(hi.job(11, Mode::Count, 0, 2, iw_max(cfg)));
    c.expected.push_back(Record::done(11, 2));
    c.jobs.push_back(hi.job(12, Mode::All, 0, 2, dhi - 1));
    c.expected.push_back(Record::done(12, 0));
    c.jobs.push_back(hi.job(13, Mode::First, 0, 2, dhi));
    c.expected.push_back(Record::hit(13, 0, 0, 0, 0, 0, dhi));
    c.expected.push_back(Record::done(13, 1));
    const int64_t dalt = 4 * (qmax(cfg) + qmin(cfg)) * (U >> 3);
    c.jobs.push_back(alt.job(14, Mode::All, 0, 1, dalt));
    c.expected.push_back(Record::hit(14, 0, 0, 0, 0, 0, dalt));
    c.expected.push_back(Record::done(14, 1));
    c.jobs.push_back(alt.job(15, Mode::All, 0, 1, dalt - 1));
    c.expected.push_back(Record::done(15, 0));
    out.push_back(c);
  }
  {  // 04: FIRST stops early on a distance map: 200 points, the first `k` at x = 6.5 (D = 2.5 * 2^(3WB) > 0) and the
     // rest at x = 0.5 (D = -3.5 * 2^(3WB)); threshold 0, so the first hit is point k. k = 0, a lane boundary, one
     // past it, mid-shell, and near the end (fewer slots left than the pipeline holds); then ALL and COUNT.
    DistCase c{"04_first_early_stop", {}, {}, {}};
    NodeMap m(cfg, c.memory, 0, 8, 1, 1);
    m.fill([](uint64_t X, uint64_t, uint64_t) { return int64_t(X) - 4; });
    const uint32_t n = 200;
    const uint32_t ks[] = {0, uint32_t(cfg.LANES), uint32_t(cfg.LANES) + 1, 37, n - 3};
    uint32_t tag = 20, base37 = 0;
    for (uint32_t k : ks) {
      const uint32_t base = uint32_t(c.memory.shell.size());
      if (k == 37) base37 = base;
      for (uint32_t i = 0; i < n; ++i) c.memory.shell.push_back(point(i < k ? 6 * one + one / 2 : one / 2, 0, 0));
      c.jobs.push_back(m.job(tag, Mode::First, base, n, 0));
      c.expected.push_back(Record::hit(tag, k, 0, 0, 0, 0, -(U / 2) * 7));
      c.expected.push_back(Record::done(tag, 1));
      ++tag;
    }
    c.jobs.push_back(m.job(tag, Mode::Count, 0, n, 0));  // the first shell: every point hits
    c.expected.push_back(Record::done(tag, n));
    ++tag;
    c.jobs.push_back(m.job(tag, Mode::All, base37, n, 0));  // the k = 37 shell: points 37.. hit
    for (uint32_t i = 37; i < n; ++i) c.expected.push_back(Record::hit(tag, i, 0, 0, 0, 0, -(U / 2) * 7));
    c.expected.push_back(Record::done(tag, n - 37));
    out.push_back(c);
  }
  return out;
}

TEST(RtlDistance, DirectedCasesOnEveryDistanceModel) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : distance_models()) {
    ASSERT_GE(cfg.PF, cfg.WB) << "case 02 takes the top WB bits of PF shell fraction bits";
    for (DistCase& c : directed(cfg)) {
      const std::string what = c.name + " on " + cfg.to_string();
      // The hand-derived stream against ref/ first (results only), then the RTL against both, cycles included.
      const std::vector<Record> want = expected_stream(cfg, c.memory, c.jobs);
      expect_stream(c.expected, want, what + " (ref/)", false);
      auto dev = make_device("rtl", cfg);
      dev->load(c.memory);
      const std::vector<Record> got = dev->run(c.jobs);
      expect_stream(c.expected, got, what, false);
      expect_stream(want, got, what, true);
      ++ran;
    }
  }
  EXPECT_GE(ran, 6 * 4u);
}

TEST(RtlDistance, RandomJobsBitExactAndCycleExact) {
  const uint64_t seed = test_seed();
  size_t jobs = 0, lookups = 0, hits = 0, firsts = 0;
  for (const DeviceConfig& cfg : distance_models()) {
    for (int part = 0; part < 2; ++part) {
      GenerateOptions g;
      g.seed = seed * 16 + uint64_t(cfg.SB) * 7 + uint64_t(cfg.LANES) * 3 + uint64_t(part);
      g.jobs = 2500;
      g.config = cfg;
      const GeneratedVectors v = generate_vectors(g);
      const std::vector<Record> want = expected_stream(v.config, v.memory, v.jobs);
      auto dev = make_device("rtl", v.config);
      dev->load(v.memory);
      expect_stream(want, dev->run(v.jobs), cfg.to_string() + " generator seed " + std::to_string(g.seed), true);
      if (HasFatalFailure()) return;
      jobs += v.jobs.size();
      for (const Job& j : v.jobs) lookups += j.shell_count;
      size_t job = 0;
      for (const Record& r : want) {
        if (r.kind == Record::Hit) {
          ++hits;
          continue;
        }
        firsts += v.jobs[job++].mode == Mode::First && r.hits == 1;  // stopped early, or at its last slot
      }
    }
  }
  std::printf("%zu jobs, %zu lookups, %zu hit records\n", jobs, lookups, hits);
  EXPECT_GE(jobs, 6 * 5000u);
  EXPECT_GT(hits, jobs) << "the random jobs must exercise hits";
  EXPECT_GT(firsts, 100u);
}

TEST(RtlDistance, BackPressureLosesNothingAndCyclesAreAccountedFor) {
  const uint64_t seed = test_seed();
  const std::pair<double, double> probs[] = {{0.3, 0.3}, {0.9, 0.0}, {0.0, 0.9}, {0.6, 0.2}};
  for (const DeviceConfig& cfg : distance_models()) {
    GenerateOptions g;
    g.seed = seed + uint64_t(cfg.SB) * 100 + uint64_t(cfg.LANES);
    g.jobs = 300;
    g.config = cfg;
    const GeneratedVectors v = generate_vectors(g);
    const std::vector<Record> want = expected_stream(v.config, v.memory, v.jobs);
    for (const auto& [ph, pd] : probs) {
      DeviceOptions opt;
      opt.hit_stall_prob = ph;
      opt.done_stall_prob = pd;
      opt.stall_seed = seed ^ uint64_t(cfg.SB * 10000 + cfg.LANES * 1000 + int(ph * 10) * 10 + int(pd * 10));
      const std::string what = cfg.to_string() + " hit stall " + std::to_string(ph) + " done stall " +
                               std::to_string(pd) + " seed " + std::to_string(seed);
      auto dev = make_device("rtl", v.config, opt);
      dev->load(v.memory);
      const std::vector<Record> got = dev->run(v.jobs);
      uint64_t stalls = 0;
      test::scoreboard(want, got, what, stalls);
      if (HasFatalFailure()) return;
      EXPECT_GT(stalls, 0u) << what << ": back-pressure must have stalled the device";
    }
  }
}

TEST(RtlDistance, ConfigurationsWithoutAModelAreRefusedNamingTheBuiltOnes) {
  DeviceConfig c;
  c.SB = 8;
  c.LANES = 16;
  try {
    make_device("rtl", c);
    ADD_FAILURE() << "a model for SB 8 LANES 16 does not exist";
  } catch (const DeviceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("not for " + c.to_string()), std::string::npos) << m;
    EXPECT_NE(m.find("LANES 8 SAW 16 MAW 18 TAGW 16 SB 8 WB 8"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace voxcd
