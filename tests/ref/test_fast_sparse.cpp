// FastRunner (ref/fast/fast.h) on sparse maps and shells (docs/contract.md, "Sparse voxmaps and shells") against the
// specification: the same stream as run_stream with annotate_cycles(cfg, mem, ...)'s cycles on generated version-3
// vectors (2-bit and distance, banked and not, at several depths, every arithmetic path, 1 and 2 threads), on directed
// cases (chunks that begin inside a brick word, FIRST across pieces, codes past the units, a map rewritten under its
// copy, the copy's limit), and through run_hits and run_piece. Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "tests/ref/sparse_images.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261128); }

std::vector<Record> reference(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  std::vector<Record> want = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, mem, jobs, want);
  return want;
}

void expect_same(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], true)) << what << " record " << i << ": expected '"
                                               << want[i].to_string(true) << "' cycles "
                                               << want[i].cycles.value_or(0) << ", got '" << got[i].to_string(true)
                                               << "' cycles " << got[i].cycles.value_or(0);
    ASSERT_EQ(got[i].points, want[i].points) << what << " record " << i;
  }
}

DeviceConfig sparse_config(int sb, int banks = 0, int depth = 0, int lanes = 4) {
  DeviceConfig c;
  c.BL = 3;
  c.SB = sb;
  c.BANKS = banks;
  c.depth = depth;
  c.LANES = lanes;
  return c;
}

struct Counts {
  size_t sparse_maps = 0, sparse_shells = 0, hits = 0;
};
Counts counts(const GeneratedVectors& v, const std::vector<Record>& recs) {
  Counts c;
  for (const Job& j : v.jobs) c.sparse_maps += j.sparse_map(), c.sparse_shells += j.sparse_shell();
  for (const Record& r : recs) c.hits += r.kind == Record::Hit;
  return c;
}

// Generated vectors of cfg, run on 1 and 2 threads against the reference; the runner takes `path`.
void check_generated(const DeviceConfig& cfg, uint64_t seed, size_t jobs, FastRunner::Path path,
                     const std::string& name) {
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.cloud_points = 1500;
  g.config = cfg;
  const GeneratedVectors v = generate_vectors(g);
  const std::vector<Record> want = reference(v.config, v.memory, v.jobs);
  const Counts c = counts(v, want);
  EXPECT_GT(c.sparse_maps, jobs / 10) << name;
  EXPECT_GT(c.sparse_shells, jobs / 20) << name;
  EXPECT_GT(c.hits, 100u) << name << ": the vectors must hit";
  for (unsigned threads : {1u, 2u}) {
    FastRunner fr(v.config, threads);
    ASSERT_EQ(fr.path(), path) << name;
    fr.load(v.memory);
    const std::string what = name + " (" + v.config.to_string() + ") threads " + std::to_string(threads) + " seed " +
                             std::to_string(seed);
    expect_same(want, fr.run(v.jobs), what);
    const std::vector<Record> untimed = fr.run(v.jobs, false);
    ASSERT_EQ(untimed.size(), want.size()) << what;
    for (size_t i = 0; i < want.size(); ++i) ASSERT_TRUE(untimed[i].same_as(want[i], false)) << what << " " << i;
  }
}

TEST(FastSparse, GeneratedVectorsOnEveryDeviceShape) {
  const uint64_t seed = test_seed();
  std::printf("kernels: sparse %s, sparse distance %s\n", FastRunner::sparse_kernel(), FastRunner::sparse_distance_kernel());
  for (int sb : {2, 8})
    for (int banks : {0, 2})
      for (int depth : {0, 3}) {
        const std::string name = "SB " + std::to_string(sb) + " BANKS " + std::to_string(banks) + " DEPTH " +
                                 std::to_string(depth);
        check_generated(sparse_config(sb, banks, depth), seed + uint64_t(sb + 10 * banks + 100 * depth), 250,
                        FastRunner::Path::Double, name);
      }
  // Other lane counts, and 32-bit words.
  check_generated(sparse_config(2, 0, 5, 1), seed + 7, 200, FastRunner::Path::Double, "one lane, DEPTH 5");
  check_generated(sparse_config(8, 4, 0, 8), seed + 8, 200, FastRunner::Path::Double, "eight lanes, BANKS 4");
  DeviceConfig narrow = sparse_config(4);
  narrow.MEMW = 32;
  check_generated(narrow, seed + 9, 200, FastRunner::Path::Double, "SB 4 MEMW 32");
}

TEST(FastSparse, GeneratedVectorsOnEveryArithmeticPath) {
  const uint64_t seed = test_seed() + 20;
  for (int sb : {2, 8, 16}) {
    DeviceConfig wide = sparse_config(sb);
    wide.PW = 28, wide.PF = 10, wide.MW = 24, wide.MF = 20, wide.TW = 56, wide.LANES = 8;
    check_generated(wide, seed + uint64_t(sb), 150, FastRunner::Path::Int64, "int64 SB " + std::to_string(sb));
    DeviceConfig widest = sparse_config(sb);
    widest.PW = 32, widest.PF = 16, widest.MW = 26, widest.MF = 24, widest.TW = 64, widest.MEMW = 32,
    widest.LANES = 2;
    check_generated(widest, seed + 100 + uint64_t(sb), 150, FastRunner::Path::Wide, "wide SB " + std::to_string(sb));
  }
  // The double path where the distance copy cannot serve: SB 16 (two bytes a node), and IW above 51.
  check_generated(sparse_config(16), seed + 200, 150, FastRunner::Path::Double, "double SB 16");
  DeviceConfig fine = sparse_config(8);
  fine.WB = 16;  // IW = 56
  check_generated(fine, seed + 201, 150, FastRunner::Path::Double, "double SB 8 WB 16");
}

// A 2-bit map of every state, dense and sparse, and a sparse shell of long chains: jobs of many chunks whose pieces
// begin inside brick words, every mode, 1 to 3 threads, equal to the reference and to the dense job's hits.
TEST(FastSparse, LargeSparseJobsSplitIntoPiecesInsideWords) {
  std::mt19937_64 rng(test_seed() + 30);
  const DeviceConfig cfg = sparse_config(2);
  const uint32_t nx = 45, ny = 38, nz = 29;
  std::vector<uint8_t> states(uint64_t(nx) * ny * nz);
  for (uint64_t i = 0; i < states.size(); ++i) {
    const uint64_t x = i % nx, z = i / (uint64_t(nx) * ny);
    states[i] = x < 16 ? uint8_t(z < 8 ? kInterior : kEmpty) : x < 24 ? uint8_t(kSurface) : uint8_t(rng() % 4);
  }
  DeviceMemory mem;
  const test::SparsePlacement p = test::append_sparse_states(cfg, nx, ny, nz, states, mem);
  // Rows of bricks along x through the map (an origin word a row, then steps of one brick), some masks empty.
  const int64_t u = int64_t{1} << cfg.PF;
  const int along[3] = {1, 0, 0};
  for (int rep = 0; rep < 3; ++rep)
    for (int64_t bz = 0; bz < 8; ++bz)
      for (int64_t by = 0; by < 10; ++by) {
        mem.shell.push_back(origin_word(cfg, -8 * u + rep * u / 3, 4 * by * u, 4 * bz * u));
        for (int k = 0; k < 13; ++k)
          mem.shell.push_back(brick_word(cfg, k % 11 == 5 ? 0 : (rng() | rng()) & ~uint64_t(k % 7), along));
      }
  Job j = test::sparse_map_job(p, nx, ny, nz);
  j.sparse |= kSparseShell;
  j.shell_count = uint32_t(mem.shell.size());
  j.hit_mask = 0b1110;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = int64_t{1} << cfg.MF;
  j.t[0] = int64_t{3} << (cfg.TF() - 2);
  std::vector<Job> jobs;
  for (Mode m : {Mode::All, Mode::First, Mode::Count, Mode::All}) {
    j.mode = m;
    ++j.tag;
    jobs.push_back(j);
  }
  jobs.back().hit_mask = 0b1000;  // hits of the reserved state only: few, spread over the job
  const std::vector<Record> want = reference(cfg, mem, jobs);
  EXPECT_GT(job_points(cfg, mem.shell, j).size(), 20u * 2048) << "many chunks";
  EXPECT_GT(want.size(), 10000u);
  for (unsigned threads : {1u, 2u, 3u}) {
    FastRunner fr(cfg, threads);
    fr.load(mem);
    expect_same(want, fr.run(jobs), "threads " + std::to_string(threads));
    EXPECT_EQ(fr.job_points(j), job_points(cfg, mem.shell, j).size());
    const JobSlots s = fr.job_slots(j), r = job_slots(cfg, mem.shell, j);
    EXPECT_EQ(s.groups, r.groups);
    EXPECT_EQ(s.starts, r.starts);
  }
}

// Origins at the top of PW - 1 bits and steps that carry the points past PW bits: the generated points wrap as the
// registers do (ref/sparse.h, shell_points), on every arithmetic path's coordinates; the wrapped points land in the
// map.
TEST(FastSparse, ShellPointsWrapAtPWBits) {
  struct Widths {
    int pw, pf, mw, mf, tw;
    FastRunner::Path path;
  };
  for (const Widths& w : {Widths{24, 8, 18, 16, 48, FastRunner::Path::Double},
                          Widths{28, 10, 24, 20, 56, FastRunner::Path::Int64},
                          Widths{32, 16, 26, 24, 64, FastRunner::Path::Wide}}) {
    DeviceConfig cfg = sparse_config(2);
    const int pw = w.pw;
    cfg.PW = w.pw, cfg.PF = w.pf, cfg.MW = w.mw, cfg.MF = w.mf, cfg.TW = w.tw;
    const int64_t top = (int64_t{1} << (pw - 2)) - 1, u = int64_t{1} << cfg.PF;
    const int up[3] = {1, 1, 1}, down[3] = {-2, -2, -2};
    DeviceMemory mem;
    const int none[3] = {0, 0, 0};
    mem.shell = {origin_word(cfg, (int64_t{1} << (pw - 1)) - 2 * u, -(int64_t{1} << (pw - 1)), top - u),
                 brick_word(cfg, ~uint64_t{0}, none), brick_word(cfg, ~uint64_t{0}, up),
                 brick_word(cfg, 0x8000000000000001ull, down), brick_word(cfg, 0x00ff00ff00ff00ffull, down)};
    mem.map.assign(1 << 13, 0x6666666666666666ull);  // states 2 and 1
    Job j;
    j.sparse = kSparseShell;
    j.shell_count = uint32_t(mem.shell.size());
    j.nx = j.ny = j.nz = 64;
    j.hit_mask = 0b0110;
    j.M[0][0] = j.M[1][1] = j.M[2][2] = int64_t{1} << cfg.MF;
    // The first brick's points of x offset 2 and 3 are carried past PW bits (the sum wraps), and the second brick's
    // origin too (the step wraps): a translation that brings the first wrapped point 8 voxels into the map takes
    // those with it.
    const std::vector<ShellWord> pts = job_points(cfg, mem.shell, j);
    ASSERT_EQ(pts.size(), 64u + 64 + 2 + 32);
    ASSERT_GT(pts[1].x, 0);
    ASSERT_LT(pts[2].x, 0) << "x wrapped";
    for (int i = 0; i < 3; ++i) j.t[i] = -pts[2][i] * (int64_t{1} << cfg.MF) + (int64_t{8} << cfg.TF());
    const std::vector<Record> want = reference(cfg, mem, {j});
    EXPECT_GE(want.size(), 64u) << "PW " << pw << ": the wrapped points must land in the map";
    for (unsigned threads : {1u, 2u}) {
      FastRunner fr(cfg, threads);
      ASSERT_EQ(fr.path(), w.path) << "PW " << pw;
      fr.load(mem);
      expect_same(want, fr.run({j}), "PW " + std::to_string(pw) + " " + FastRunner::path_name(fr.path()));
    }
  }
}

// run_hits and run_piece: the hits of the stream, and a piece anywhere in a sparse shell gives the stream's hits of
// its points.
TEST(FastSparse, RunHitsAndPiecesOfSparseShells) {
  GenerateOptions g;
  g.seed = test_seed() + 40;
  g.jobs = 200;
  g.config = sparse_config(8);
  const GeneratedVectors v = generate_vectors(g);
  FastRunner fr(v.config, 1);
  fr.load(v.memory);
  const std::vector<Record> want = reference(v.config, v.memory, v.jobs);
  HitColumns cols;
  std::vector<JobOutcome> out;
  fr.run_hits(v.jobs.data(), v.jobs.size(), cols, out);
  size_t r = 0, pieces = 0;
  std::mt19937_64 rng(g.seed);
  for (size_t j = 0; j < v.jobs.size(); ++j) {
    for (size_t k = 0; k < out[j].records; ++k, ++r)
      ASSERT_TRUE(cols.record(out[j].first + k, v.jobs[j].tag).same_as(want[r], false)) << "job " << j;
    ASSERT_EQ(out[j].hits, want[r].hits) << "job " << j;
    ASSERT_EQ(out[j].cycles, *want[r].cycles) << "job " << j;
    ++r;
    if (!v.jobs[j].sparse_shell() || v.jobs[j].mode != Mode::All) continue;
    // A piece [a, b) of the job: the hits of the stream whose points lie in it.
    const uint64_t n = fr.job_points(v.jobs[j]);
    if (n < 2) continue;
    const uint32_t a = uint32_t(rng() % n), b = uint32_t(a + 1 + rng() % (n - a));
    HitColumns piece;
    uint32_t count = 0;
    fr.run_piece(v.jobs[j], a, b, true, piece, count);
    size_t expect = 0;
    for (size_t k = 0; k < out[j].records; ++k) {
      const uint32_t pt = cols.point[out[j].first + k];
      if (pt < a || pt >= b) continue;
      ASSERT_LT(expect, piece.size());
      EXPECT_EQ(piece.point[expect], pt);
      EXPECT_EQ(piece.x[expect], cols.x[out[j].first + k]);
      EXPECT_EQ(piece.dist[expect], cols.dist[out[j].first + k]);
      ++expect;
    }
    EXPECT_EQ(piece.size(), expect);
    EXPECT_EQ(count, expect);
    ++pieces;
  }
  EXPECT_GT(pieces, 5u);
}

// A distance map of uniform cells, bricks of every level, a brick past the job's units and codes 6..15: the copy's
// kernel, the point-at-a-time path (copy limit 0) and the reference agree; a map rewritten under its copy is read
// anew; the copy counts against the limit.
TEST(FastSparse, DistanceCopyCodesRewritesAndLimit) {
  std::mt19937_64 rng(test_seed() + 50);
  DeviceConfig cfg = sparse_config(8);
  cfg.MAW = 22;  // room for bricks of level 3 (281 units of 128 words)
  const uint32_t n = 32;
  auto q = [](double x, double y, double z) {
    const double d = std::sqrt((x - 15.3) * (x - 15.3) + (y - 16.6) * (y - 16.6) + (z - 14.2) * (z - 14.2)) - 9.1;
    return std::clamp<int64_t>(int64_t(std::llround(d * 32 + 3 * std::sin(2 * x))), -128, 127);
  };
  auto level = [](uint64_t cx, uint64_t cy, uint64_t cz) { return int((cx + 2 * cy + 3 * cz) % 6) - 2; };
  DeviceMemory mem;
  const test::SparsePlacement p = test::append_sparse_field(cfg, n, n, n, q, level, mem);
  // Two table codes made invalid (cell 5 of word 0, 12..15 read as code 0).
  mem.map[p.map_base] = (mem.map[p.map_base] & ~(uint64_t{0xf} << 20)) | uint64_t{0xd} << 20;
  std::uniform_real_distribution<double> coord(-1, n + 1);
  for (int k = 0; k < 6000; ++k)
    mem.shell.push_back({int64_t(std::ldexp(coord(rng), cfg.PF)), int64_t(std::ldexp(coord(rng), cfg.PF)),
                         int64_t(std::ldexp(coord(rng), cfg.PF))});
  std::vector<Job> jobs;
  Job j = test::sparse_map_job(p, n, n, n);
  j.shell_count = uint32_t(mem.shell.size());
  for (int k = 0; k < 8; ++k) {
    FloatPose pose;
    const double a = 0.3 * k, c = std::cos(a), s = std::sin(a);
    pose.M[0][0] = c, pose.M[0][1] = -s, pose.M[1][0] = s, pose.M[1][1] = c, pose.M[2][2] = 1;
    pose.t[0] = 16 - 16 * (c - s), pose.t[1] = 16 - 16 * (s + c), pose.t[2] = 0.1 * k;
    quantize_pose(cfg, pose, j);
    j.tag = uint32_t(k);
    j.threshold = (int64_t(k) * 20 - 60) * (int64_t{1} << (3 * cfg.WB));
    j.brick_units = k == 7 ? p.brick_units / 2 : p.brick_units;  // the later bricks past the units: code 0
    j.mode = k % 3 == 1 ? Mode::First : k % 3 == 2 ? Mode::Count : Mode::All;
    jobs.push_back(j);
  }
  const std::vector<Record> want = reference(cfg, mem, jobs);
  EXPECT_GT(want.size(), 3000u);
  FastRunner fr(cfg, 2);
  fr.load(mem);
  expect_same(want, fr.run(jobs), "on the copy");
  EXPECT_GT(fr.node_copy_bytes(), 0u) << "the copy was built";
  FastRunner scalar(cfg, 2);
  scalar.set_node_copy_limit(0);
  scalar.load(mem);
  expect_same(want, scalar.run(jobs), "one point at a time");
  EXPECT_EQ(scalar.node_copy_bytes(), 0u);
  // Every brick word negated: the copy must go.
  DeviceMemory m2 = mem;
  for (uint64_t w = p.brick_base; w < m2.map.size(); ++w) m2.map[w] = ~m2.map[w];
  fr.write_map(p.brick_base, m2.map.data() + p.brick_base, m2.map.size() - p.brick_base);
  const std::vector<Record> want2 = reference(cfg, m2, jobs);
  ASSERT_NE(want2.size(), want.size()) << "the rewrite must change the stream";
  expect_same(want2, fr.run(jobs), "after rewriting the bricks");
}

// 2-bit maps' references past the units read as empty; tables of narrower words (MEMW 32: 8 codes and a 16-bit rank;
// MEMW 16: 4 codes and an 8-bit rank).
TEST(FastSparse, TwoBitCodesPastTheUnitsAndNarrowWords) {
  std::mt19937_64 rng(test_seed() + 60);
  for (int memw : {64, 32, 16}) {
    DeviceConfig cfg = sparse_config(2);
    cfg.MEMW = memw;
    const uint32_t nx = 40, ny = 17, nz = 20;
    std::vector<uint8_t> states(uint64_t(nx) * ny * nz);
    for (uint64_t i = 0; i < states.size(); ++i) states[i] = uint8_t(i % nx < 20 ? (rng() % 9 ? 2 : rng() % 4) : 0);
    DeviceMemory mem;
    const test::SparsePlacement p = test::append_sparse_states(cfg, nx, ny, nz, states, mem);
    std::uniform_real_distribution<double> coord(-1, 41);
    for (int k = 0; k < 3000; ++k)
      mem.shell.push_back({int64_t(std::ldexp(coord(rng), cfg.PF)), int64_t(std::ldexp(coord(rng) / 2, cfg.PF)),
                           int64_t(std::ldexp(coord(rng) / 2, cfg.PF))});
    std::vector<Job> jobs;
    for (uint32_t units : {p.brick_units, p.brick_units / 3, 0u}) {
      Job j = test::sparse_map_job(p, nx, ny, nz);
      j.brick_units = units;
      j.shell_count = uint32_t(mem.shell.size());
      j.hit_mask = 0b1111;
      j.M[0][0] = j.M[1][1] = j.M[2][2] = int64_t{1} << cfg.MF;
      j.tag = units;
      jobs.push_back(j);
    }
    const std::vector<Record> want = reference(cfg, mem, jobs);
    EXPECT_NE(want.size(), 4u);
    // On the map's copy (its table resolved) and, with no room for copies, on the table itself.
    for (uint64_t limit : {FastRunner::kNodeCopyLimit, uint64_t{0}}) {
      FastRunner fr(cfg, 1);
      fr.set_node_copy_limit(limit);
      fr.load(mem);
      const std::string what = "MEMW " + std::to_string(memw) + " copy limit " + std::to_string(limit);
      expect_same(want, fr.run(jobs), what);
      EXPECT_EQ(fr.node_copy_bytes() > 0, limit > 0) << what;
      // The table rewritten (every brick cell made uniform surface): the copy must follow.
      DeviceMemory m2 = mem;
      for (uint64_t w = p.map_base; w < p.brick_base; ++w)
        for (uint64_t c = 0; c < table_cells_per_word(cfg); ++c)
          if (((m2.map[w] >> (2 * c)) & 3) == kCodeBrick) m2.map[w] ^= uint64_t{2} << (2 * c);
      const std::vector<Record> want2 = reference(cfg, m2, jobs);
      ASSERT_FALSE(std::equal(want.begin(), want.end(), want2.begin(), want2.end(),
                              [](const Record& a, const Record& b) { return a.same_as(b, true); }))
          << what << ": the rewrite must change the stream";
      fr.write_map(p.map_base, m2.map.data() + p.map_base, p.brick_base - p.map_base);
      expect_same(want2, fr.run(jobs), what + " after rewriting the table");
    }
  }
}

}  // namespace
}  // namespace voxcd
