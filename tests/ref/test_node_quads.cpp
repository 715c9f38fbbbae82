// FastRunner's node-quad copy of distance voxmaps (ref/fast/detail/node_quads.h): the kernels that read it give the
// same stream as the parity-bank kernels (the copy limited to 0 bytes) and as ref/'s run_stream, on random maps with
// extreme node values, random poses, points on the map's faces and edges, just inside and outside it, weights 0 and
// 2^WB - 1, at SB 8 and SB 4 (and with 32-bit words); a map written again loses its copy, the limit holds. Runs
// through every kernel (ref.kernels_avx2, ref.kernels_baseline). Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261207); }

struct Scene {
  DeviceConfig cfg;
  DeviceMemory mem;
  std::vector<Job> jobs;
  Job maps[2];  // the two maps' geometry
};

// Random node values of map j (a quarter at the extremes) into mem.map.
void fill_map(const DeviceConfig& cfg, const Job& j, std::mt19937_64& rng, std::vector<uint64_t>& map) {
  const int64_t lo = -(int64_t{1} << (cfg.SB - 1)), hi = (int64_t{1} << (cfg.SB - 1)) - 1;
  const uint64_t vmask = (uint64_t{1} << cfg.SB) - 1;
  for (uint64_t Z = 0; Z <= j.nz; ++Z)
    for (uint64_t Y = 0; Y <= j.ny; ++Y)
      for (uint64_t X = 0; X <= j.nx; ++X) {
        const int r = int(rng() % 8);
        const int64_t v = r == 0 ? lo : r == 1 ? hi : std::uniform_int_distribution<int64_t>(lo, hi)(rng);
        const NodeAddress a = node_address(cfg, j, X, Y, Z);
        map[a.word] &= ~(vmask << (uint64_t(cfg.SB) * a.slot));
        map[a.word] |= (uint64_t(v) & vmask) << (uint64_t(cfg.SB) * a.slot);
      }
}

// One coordinate of an identity-pose point against a map of n cells along the axis: the faces, a step of the
// shell's grid either side, the middle, or anywhere from a cell outside to a cell past the end.
double edge_coordinate(uint32_t n, double step, std::mt19937_64& rng) {
  const double picks[] = {-step, 0, step, 0.5, double(n) - 1, double(n) - step, double(n), double(n) + 0.5};
  if (rng() % 2) return picks[rng() % 8];
  return std::uniform_real_distribution<double>(-1.0, double(n) + 1.0)(rng);
}

Scene make_scene(const DeviceConfig& cfg, uint64_t seed) {
  std::mt19937_64 rng(seed);
  Scene s;
  s.cfg = cfg;
  s.maps[0].nx = 13, s.maps[0].ny = 6, s.maps[0].nz = 9;
  s.maps[0].map_base = 8;
  s.maps[1].nx = 4, s.maps[1].ny = 11, s.maps[1].nz = 1;
  s.maps[1].map_base = (8 + map_words(cfg, s.maps[0]) + 7) / 8 * 8 + 16;
  s.mem.map.assign(s.maps[1].map_base + map_words(cfg, s.maps[1]), 0);
  for (const Job& m : s.maps) fill_map(cfg, m, rng, s.mem.map);
  // Shell: 1,500 points at the faces and edges of each map under the identity pose, then 2,000 random ones.
  const double step = std::ldexp(1.0, -cfg.PF);
  for (const Job& m : s.maps)
    for (int k = 0; k < 1500; ++k) {
      const double p[3] = {edge_coordinate(m.nx, step, rng), edge_coordinate(m.ny, step, rng),
                           edge_coordinate(m.nz, step, rng)};
      s.mem.shell.push_back(quantize_point(cfg, p, "edge point"));
    }
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 2000; ++k) {
    const double p[3] = {8 * u(rng), 8 * u(rng), 8 * u(rng)};
    s.mem.shell.push_back(quantize_point(cfg, p, "random point"));
  }
  const int64_t tmax = (int64_t{1} << (cfg.IW() - 1)) - 1;
  for (uint32_t tag = 0; tag < 60; ++tag) {
    Job j = s.maps[tag % 2];
    j.tag = tag;
    j.mode = tag % 7 == 3 ? Mode::First : tag % 7 == 5 ? Mode::Count : Mode::All;
    FloatPose pose;  // identity on the map's own edge points, else a random rotation and scale about the map
    if (tag % 3 == 0) {
      j.shell_base = 1500 * (tag % 2), j.shell_count = 1500;
    } else {
      double q[4] = {u(rng), u(rng), u(rng), u(rng)}, n2 = 0;
      for (double v : q) n2 += v * v;
      for (double& v : q) v /= std::sqrt(n2);
      const double a = q[0], b = q[1], c = q[2], d = q[3], sc = 0.6 + 0.6 * (u(rng) + 1) / 2;
      const double R[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                              {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
                              {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
      const double n[3] = {double(j.nx), double(j.ny), double(j.nz)};
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) pose.M[i][k] = sc * R[i][k];
        pose.t[i] = n[i] / 2 + n[i] * 0.4 * u(rng);
      }
      j.shell_base = 3000 + uint32_t(rng() % 500), j.shell_count = 1500;
    }
    quantize_pose(cfg, pose, j);
    const int r = int(rng() % 6);
    j.threshold = r == 0 ? tmax : r == 1 ? -tmax - 1 : std::uniform_int_distribution<int64_t>(-tmax / 4, tmax / 4)(rng);
    s.jobs.push_back(j);
  }
  return s;
}

uint64_t quad_bytes(const Job& m) { return 4 * (uint64_t{m.nx} + 1) * m.ny * m.nz; }

void expect_same(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(got[i].same_as(want[i], true)) << what << " record " << i << ": expected '" << want[i].to_string(true)
                                               << "', got '" << got[i].to_string(true) << "'";
}

std::vector<Record> expected(const Scene& s) {
  std::vector<Record> want = run_stream(s.cfg, s.mem, s.jobs);
  annotate_cycles(s.cfg, s.jobs, want);
  return want;
}

DeviceConfig config(int sb, int wb, int memw = 64) {
  DeviceConfig c;
  c.SB = sb, c.WB = wb, c.MEMW = memw;
  return c;
}

TEST(DistanceFast, NodeQuadsGiveTheParityBanksAndTheSpecificationsStream) {
  const uint64_t seed = test_seed();
  std::printf("node quads kernel %s\n", FastRunner::distance_kernel());
  const std::pair<const char*, DeviceConfig> cfgs[] = {{"SB8 WB8", config(8, 8)},
                                                        {"SB4 WB2", config(4, 2)},
                                                        {"SB4 WB8", config(4, 8)},
                                                        {"SB8 WB5 MEMW32", config(8, 5, 32)}};
  for (const auto& [name, cfg] : cfgs) {
    const Scene s = make_scene(cfg, seed);
    const std::vector<Record> want = expected(s);
    size_t hits = 0, done_hits = 0;
    for (const Record& r : want) hits += r.kind == Record::Hit, done_hits += r.kind == Record::Done ? r.hits : 0;
    EXPECT_GT(hits, 2000u) << name;
    EXPECT_LT(done_hits, 60u * 1500u / 2) << name;  // thresholds that miss too
    FastRunner banks(cfg, 1);
    banks.set_node_copy_limit(0);
    banks.load(s.mem);
    expect_same(want, banks.run(s.jobs), std::string(name) + " parity banks");
    EXPECT_EQ(banks.node_copy_bytes(), 0u) << name;
    for (unsigned threads : {1u, 3u}) {
      FastRunner quads(cfg, threads);
      quads.load(s.mem);
      expect_same(want, quads.run(s.jobs), std::string(name) + " node quads, threads " + std::to_string(threads));
      EXPECT_EQ(quads.node_copy_bytes(), quad_bytes(s.maps[0]) + quad_bytes(s.maps[1])) << name;
    }
  }
}

TEST(DistanceFast, NodeQuadsFollowWritesAndTheLimit) {
  const uint64_t seed = test_seed() + 1;
  const DeviceConfig cfg = config(8, 8);
  Scene s = make_scene(cfg, seed);
  FastRunner fr(cfg, 1);
  fr.load(s.mem);
  expect_same(expected(s), fr.run(s.jobs), "before the write");
  // New node values in map 0 through the write port: its copy goes, map 1's stays, and the stream follows the new
  // values.
  std::mt19937_64 rng(seed);
  std::vector<uint64_t> map = s.mem.map;
  fill_map(cfg, s.maps[0], rng, map);
  const uint64_t first = s.maps[0].map_base, n = map_words(cfg, s.maps[0]);
  fr.write_map(first, map.data() + first, n);
  EXPECT_EQ(fr.node_copy_bytes(), quad_bytes(s.maps[1]));
  s.mem.map = map;
  const std::vector<Record> want = expected(s);
  expect_same(want, fr.run(s.jobs), "after the write");
  // A limit that holds map 0's copy only (its jobs come first): map 1 from its banks, the same stream.
  fr.set_node_copy_limit(quad_bytes(s.maps[0]));
  EXPECT_EQ(fr.node_copy_bytes(), 0u);
  expect_same(want, fr.run(s.jobs), "limited");
  EXPECT_EQ(fr.node_copy_bytes(), quad_bytes(s.maps[0]));
  // SB 16 keeps the parity banks: no copy.
  const DeviceConfig wide = config(16, 8);
  const Scene w = make_scene(wide, seed);
  FastRunner fw(wide, 1);
  fw.load(w.mem);
  expect_same(expected(w), fw.run(w.jobs), "SB16");
  EXPECT_EQ(fw.node_copy_bytes(), 0u);
}

}  // namespace
}  // namespace voxcd
