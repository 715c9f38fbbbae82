// Sparse maps and shells on the RTL (docs/contract.md, "Sparse voxmaps and shells"), numbered directed cases on every
// sparse model of the build (rtl_sparse_configs()), each checked twice: against what the case says by hand, and
// against ref/'s stream with the timing model's cycles (tests/rtl/sparse_cases.h).
//   1  2-bit cells: uniform of every state, a brick, a brick reference past the job's units (reads as code 0)
//   2  distance cells: uniform far and deep, a brick of every level, codes 6 and 15 (read as 0), bricks past the units
//   3  shell words: origin words, steps, empty masks, a job's origin back at 0, a sum that wraps at PW bits, an empty
//      sparse shell, a sparse shell on a sparse map
//   4  FIRST at every slot of a brick word (and of the word after it), each followed by a dense job
//   5  latency: a sparse device's first slot reaches the hit test 3 cycles later (4 on a distance device) than the
//      dense device's of the same lanes, banks and depth
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/ref/sparse_images.h"
#include "tests/rtl/sparse_cases.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {
namespace {

Job identity_job(const DeviceConfig& cfg) {
  Job j;
  for (int i = 0; i < 3; ++i) j.M[i][i] = int64_t{1} << cfg.MF;
  return j;
}

// The centre of voxel (x, y, z) as a shell word (identity pose: shell units are the map's voxels).
ShellWord centre(const DeviceConfig& cfg, int64_t x, int64_t y, int64_t z) {
  const int64_t h = cfg.PF > 0 ? int64_t{1} << (cfg.PF - 1) : 0;
  return {(x << cfg.PF) + h, (y << cfg.PF) + h, (z << cfg.PF) + h};
}

TEST(RtlSparse, BuildHasSparseModelsOfEveryKind) {
  std::vector<int> lanes;
  bool distance = false, banked = false, deep = false;
  for (const DeviceConfig& c : rtl_sparse_configs()) {
    EXPECT_TRUE(c.sparse()) << c.to_string();
    if (!c.distance() && !c.banked() && c.depth == 0 && !c.brick_lanes()) lanes.push_back(c.LANES);
    distance = distance || c.distance();
    banked = banked || c.banked();
    deep = deep || c.depth == kMaxDepth;
  }
  std::sort(lanes.begin(), lanes.end());
  EXPECT_EQ(lanes, (std::vector<int>{1, 2, 4, 8}));
  EXPECT_TRUE(distance && banked && deep) << "a distance, a banked and a deepest sparse model";
  bool brick = false, brick_distance = false, brick_banked = false, brick_deep = false;
  for (const DeviceConfig& c : rtl_sparse_configs()) {
    if (!c.brick_lanes()) continue;
    brick = brick || (!c.distance() && !c.banked() && c.depth == 0);
    brick_distance = brick_distance || c.distance();
    brick_banked = brick_banked || c.banked();
    brick_deep = brick_deep || c.depth == kMaxDepth;
  }
  EXPECT_TRUE(brick && brick_distance && brick_banked && brick_deep)
      << "brick lanes (TX 1): a 2-bit, a distance, a banked and a deepest sparse model";
}

// Case 1: a 3B x B x B map (B = 2^BL) of three coarse cells: uniform surface, a brick of states (x + y + z) % 3, and
// a brick that the job's units do not cover (its voxels read as empty). Every inside point is a hit (mask 15), so
// each record shows its voxel's state.
TEST(RtlSparse, Case1TwoBitCells) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : test::sparse_models(false)) {
    const uint32_t B = uint32_t(brick_edge(cfg));
    DeviceMemory mem;
    mem.map.assign(3, ~uint64_t{0} >> (64 - cfg.MEMW));  // words before the map: never read
    Job job = identity_job(cfg);
    job.sparse = kSparseMap, job.nx = 3 * B, job.ny = job.nz = B, job.map_base = 3, job.hit_mask = 15;
    for (uint64_t w : table_image(cfg, {kSurface, kCodeBrick, kCodeBrick})) mem.map.push_back(w);
    job.brick_base = uint32_t(mem.map.size()), job.brick_units = 1;
    const uint64_t spw = uint64_t(cfg.states_per_word());
    mem.map.resize(mem.map.size() + 2 * unit_words(cfg), ~uint64_t{0} >> (64 - cfg.MEMW));  // the second: all 3s
    for (uint64_t i = 0; i < uint64_t(B) * B * B; ++i) {
      uint64_t& w = mem.map[job.brick_base + i / spw];
      if (i % spw == 0) w = 0;
      w |= uint64_t((i % B + i / B % B + i / (B * B)) % 3) << (2 * (i % spw));
    }
    for (int64_t x = 0; x < 3 * B; ++x)
      for (int64_t y = 0; y < B; ++y) mem.shell.push_back(centre(cfg, x, y, (x + y) % B));
    job.shell_count = uint32_t(mem.shell.size());
    Job count = job, first = job;
    count.tag = 1, count.mode = Mode::Count, count.hit_mask = 0b0110;
    first.tag = 2, first.mode = Mode::First, first.hit_mask = 0b0100;
    const std::vector<Record> want = test::expect_rtl_exact(cfg, mem, {job, count, first}, "case 1");
    if (HasFatalFailure()) return;
    const std::vector<Record> hits = test::hits_of(want);
    ASSERT_EQ(hits.size(), mem.shell.size() + 1u);
    for (size_t k = 0; k < mem.shell.size(); ++k) {
      const Record& r = hits[k];
      const uint32_t brick_state = (r.x % B + r.y + r.z) % 3;
      EXPECT_EQ(r.state, r.x < B ? 1u : r.x < 2 * B ? brick_state : 0u) << "point " << r.point;
    }
    EXPECT_GE(hits.back().x, B) << "FIRST's interior voxel is in the brick";
    ++ran;
  }
  EXPECT_GT(ran, 0u);
}

// The deepest level whose bricks of levels 0 .. it fit half the voxmap memory (every level at BL 3 and the default
// MAW; at BL 4 a level-3 brick alone is more than 2^18 words).
int deepest_fitting_level(const DeviceConfig& cfg) {
  uint64_t words = 0;
  int l = 0;
  for (; l <= kMaxLevel && (words += level_words(cfg, l)) <= cfg.map_depth() / 2; ++l) {
  }
  return l - 1;
}

// Sets the code of cell t of the table at word `base`.
void set_code(const DeviceConfig& cfg, DeviceMemory& mem, uint64_t base, uint64_t t, uint8_t code) {
  const uint64_t cpw = table_cells_per_word(cfg);
  uint64_t& w = mem.map[base + t / cpw];
  w = (w & ~(uint64_t{15} << (4 * (t % cpw)))) | uint64_t(code) << (4 * (t % cpw));
}

// Case 2: an 8B x B x B distance map of eight coarse cells with codes 0, 1, 2, 3, 4, 5, 6, 15: far, deep, a brick of
// each level (up to the deepest the memory holds: deepest_fitting_level), and two codes past the levels. Every inside
// point is a hit (the largest threshold), so each record carries D; uniform cells give q * 2^(3 WB). A second job's
// units end before the level-2 brick: cells 4 and 5 read as far.
TEST(RtlSparse, Case2DistanceCells) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : test::sparse_models(true)) {
    const uint32_t B = uint32_t(brick_edge(cfg));
    const int deepest = deepest_fitting_level(cfg);
    const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1, one = int64_t{1} << (3 * cfg.WB);
    auto q = [&](double x, double y, double z) {
      return std::clamp<int64_t>(std::llround(qmax * std::sin(0.37 * x + 0.21 * y) * std::cos(0.29 * z)), -qmax, qmax);
    };
    auto level = [deepest](uint64_t cx, uint64_t, uint64_t) {
      return cx == 0 ? -1 : cx == 1 ? -2 : cx < 6 ? std::min(int(cx) - 2, deepest) : -1;
    };
    DeviceMemory mem;
    const test::SparsePlacement p = test::append_sparse_field(cfg, 8 * B, B, B, q, level, mem);
    set_code(cfg, mem, p.map_base, 6, 6);  // cells 6 and 7: codes past the levels
    set_code(cfg, mem, p.map_base, 7, 15);
    // Ten points a voxel column along x, spread over the cell by the fractional parts of multiples of irrationals.
    auto spread = [](uint32_t k, double a) { return k * a - std::floor(k * a); };
    for (uint32_t k = 0; k < 80 * B; ++k)
      mem.shell.push_back({int64_t(std::ldexp(k / 10 + spread(k, 0.7548776662), cfg.PF)),
                           int64_t(std::ldexp(B * spread(k, 0.5698402910), cfg.PF)),
                           int64_t(std::ldexp(B * spread(k, 0.4142135624), cfg.PF))});
    Job job = identity_job(cfg);
    job.sparse = kSparseMap, job.map_base = p.map_base, job.brick_base = p.brick_base;
    job.brick_units = p.brick_units, job.nx = 8 * B, job.ny = job.nz = B, job.shell_count = uint32_t(mem.shell.size());
    job.threshold = (int64_t{1} << (cfg.IW() - 1)) - 1;
    Job short_units = job;
    short_units.tag = 1, short_units.brick_units = uint32_t(level_units(cfg, 0) + level_units(cfg, 1));
    const std::vector<Record> want = test::expect_rtl_exact(cfg, mem, {job, short_units}, "case 2");
    if (HasFatalFailure()) return;
    const std::vector<Record> hits = test::hits_of(want);
    ASSERT_EQ(hits.size(), 2 * mem.shell.size());
    for (const Record& r : hits) {
      const uint32_t cell = r.x / B;
      if (cell == 0 || cell >= 6 || (r.tag == 1 && cell >= 4)) {
        EXPECT_EQ(r.dist, qmax * one) << r.to_string(true);
      } else if (cell == 1) {
        EXPECT_EQ(r.dist, (-qmax - 1) * one) << r.to_string(true);
      }
    }
    ++ran;
  }
  EXPECT_GT(ran, 0u);
}

}  // namespace
}  // namespace voxcd
