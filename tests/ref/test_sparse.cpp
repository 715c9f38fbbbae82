// Sparse maps and shells in ref/ (docs/contract.md, "Sparse voxmaps and shells"): a sparse map looks up exactly as
// the dense map it stores (2-bit, and distance bricks of level 0), a level-l brick as a dense map 2^l times finer,
// uniform cells and references past the bricks as the contract says; a sparse shell generates the points of its
// chain; validation, the slots and cycles of sparse jobs, version 3 vector files. Seed: printed at start;
// VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>

#include "tests/ref/sparse_images.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261127); }

DeviceConfig sparse_config(int sb = 2) {
  DeviceConfig c;
  c.BL = 3;
  c.SB = sb;
  return c;
}

// A random pose that keeps most of a cloud of the map's size inside it.
void random_pose(const DeviceConfig& cfg, std::mt19937_64& rng, uint32_t n, Job& j) {
  std::uniform_real_distribution<double> u(-1, 1);
  FloatPose pose;
  const double a = u(rng) * M_PI, c = std::cos(a), s = std::sin(a);
  const double R[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) pose.M[i][k] = R[i][k];
  for (int i = 0; i < 3; ++i) pose.t[i] = n / 2.0 - (R[i][0] + R[i][1] + R[i][2]) * n / 2.0 + u(rng) * 2;
  quantize_pose(cfg, pose, j);
}

// A cloud of shell words over [-2, n + 2) voxels, with points on faces too.
std::vector<ShellWord> cloud(const DeviceConfig& cfg, std::mt19937_64& rng, uint32_t n, size_t count) {
  std::uniform_real_distribution<double> u(-2, n + 2);
  std::vector<ShellWord> out;
  for (size_t k = 0; k < count; ++k) {
    ShellWord w{int64_t(std::ldexp(u(rng), cfg.PF)), int64_t(std::ldexp(u(rng), cfg.PF)),
                int64_t(std::ldexp(u(rng), cfg.PF))};
    if (k % 7 == 0) w.x = int64_t(std::lround(u(rng))) * (int64_t{1} << cfg.PF);  // on a voxel face
    out.push_back(w);
  }
  return out;
}

TEST(SparseMaps, TwoBitMapsLookUpAsTheirDenseForm) {
  const uint64_t seed = test_seed();
  std::printf("seed %llu\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  const DeviceConfig cfg = sparse_config();
  const uint32_t nx = 37, ny = 21, nz = 13;
  std::vector<uint8_t> states(uint64_t(nx) * ny * nz);
  // Uniform blocks of every state and noisy ones, so that both kinds of cell occur.
  for (uint64_t i = 0; i < states.size(); ++i) {
    const uint64_t x = i % nx, z = i / (uint64_t(nx) * ny);
    states[i] = x < 16 ? uint8_t(z < 8 ? 2 : 0) : x < 24 ? 1 : uint8_t(rng() % 4);
  }
  DeviceMemory mem;
  mem.map.assign(5, 0x5555);  // the dense map does not start at word 0
  Job dense;
  dense.map_base = 5, dense.nx = nx, dense.ny = ny, dense.nz = nz;
  dense.hit_mask = 0b1110;
  mem.map.resize(5 + map_words(cfg, dense), 0);
  for (uint64_t i = 0; i < states.size(); ++i) mem.map[5 + i / 32] |= uint64_t(states[i]) << (2 * (i % 32));
  const test::SparsePlacement p = test::append_sparse_states(cfg, nx, ny, nz, states, mem);
  EXPECT_GT(p.brick_units, 0u);
  EXPECT_LT(p.brick_units, p.codes.size()) << "some cells must be uniform";
  mem.shell = cloud(cfg, rng, nx, 3000);
  std::vector<Job> dense_jobs, sparse_jobs;
  for (int k = 0; k < 20; ++k) {
    Job d = dense;
    d.tag = uint32_t(k);
    d.shell_count = uint32_t(mem.shell.size());
    d.mode = k % 3 == 0 ? Mode::Count : Mode::All;
    random_pose(cfg, rng, nx, d);
    Job s = test::sparse_map_job(p, nx, ny, nz);
    s.tag = d.tag, s.mode = d.mode, s.hit_mask = d.hit_mask, s.shell_count = d.shell_count;
    std::copy(&d.M[0][0], &d.M[0][0] + 9, &s.M[0][0]);
    std::copy(d.t, d.t + 3, s.t);
    dense_jobs.push_back(d);
    sparse_jobs.push_back(s);
  }
  const std::vector<Record> want = run_stream(cfg, mem, dense_jobs), got = run_stream(cfg, mem, sparse_jobs);
  ASSERT_EQ(want.size(), got.size());
  size_t hits = 0;
  for (size_t r = 0; r < want.size(); ++r) {
    ASSERT_TRUE(want[r].same_as(got[r], false)) << "record " << r << ": " << want[r].to_string() << " vs "
                                                << got[r].to_string() << " (seed " << seed << ")";
    hits += want[r].kind == Record::Hit;
  }
  EXPECT_GT(hits, 1000u);
}

// A smooth field with values across the whole range, clamped: uniform far cells and bricks elsewhere.
int64_t field_value(const DeviceConfig& cfg, double x, double y, double z) {
  const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1;
  const double d = std::sqrt((x - 9.3) * (x - 9.3) + (y - 11.1) * (y - 11.1) + (z - 7.7) * (z - 7.7)) - 5.2;
  return std::clamp<int64_t>(int64_t(std::llround(d * qmax / 4.0 + 0.37 * std::sin(3 * x + y))), -qmax - 1, qmax);
}

// The same stream from two jobs that differ only in their map.
void expect_same_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const Job& a, const Job& b, int jobs,
                        std::mt19937_64& rng) {
  std::vector<Job> ja, jb;
  for (int k = 0; k < jobs; ++k) {
    Job x = a, y = b;
    x.tag = y.tag = uint32_t(k);
    x.shell_count = y.shell_count = uint32_t(mem.shell.size());
    random_pose(cfg, rng, a.nx, x);
    std::copy(&x.M[0][0], &x.M[0][0] + 9, &y.M[0][0]);
    std::copy(x.t, x.t + 3, y.t);
    x.threshold = y.threshold = int64_t(rng() % 64) << (3 * cfg.WB);
    ja.push_back(x);
    jb.push_back(y);
  }
  const std::vector<Record> ra = run_stream(cfg, mem, ja), rb = run_stream(cfg, mem, jb);
  ASSERT_EQ(ra.size(), rb.size());
  for (size_t r = 0; r < ra.size(); ++r)
    ASSERT_TRUE(ra[r].same_as(rb[r], false)) << ra[r].to_string(true) << " vs " << rb[r].to_string(true);
  EXPECT_GT(ra.size(), size_t(jobs) * 20) << "the jobs must hit";
}

TEST(SparseMaps, DistanceBricksOfLevelZeroLookUpAsTheDenseField) {
  std::mt19937_64 rng(test_seed() + 1);
  const DeviceConfig cfg = sparse_config(8);
  const uint32_t n = 20;
  auto q = [&](double x, double y, double z) { return field_value(cfg, x, y, z); };
  DeviceMemory mem;
  mem.map.assign(3, 0);
  Job dense;
  dense.map_base = test::append_dense_field(cfg, n, n, n, q, mem);
  dense.nx = dense.ny = dense.nz = n;
  // Every cell a level-0 brick except those the field clamps entirely (uniform).
  const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1;
  auto level = [&](uint64_t cx, uint64_t cy, uint64_t cz) {
    bool far = true, deep = true;
    for (uint64_t i = 0; i <= 8; ++i)
      for (uint64_t j = 0; j <= 8; ++j)
        for (uint64_t k = 0; k <= 8; ++k) {
          const int64_t v = q(double(cx * 8 + i), double(cy * 8 + j), double(cz * 8 + k));
          far = far && v == qmax;
          deep = deep && v == -qmax - 1;
        }
    return far ? -1 : deep ? -2 : 0;
  };
  const test::SparsePlacement p = test::append_sparse_field(cfg, n, n, n, q, level, mem);
  size_t uniform = 0;
  for (uint8_t c : p.codes) uniform += c < kCodeLevel0;
  EXPECT_GT(uniform, 0u) << "the far cells are uniform";
  mem.shell = cloud(cfg, rng, n, 2000);
  expect_same_stream(cfg, mem, dense, test::sparse_map_job(p, n, n, n), 12, rng);
}

// A brick of level l is the field sampled 2^l times finer: the same D as a dense map of that finer grid under a pose
// scaled by 2^l (the sub-cell and the weights are the same bits of the accumulator).
TEST(SparseMaps, ABrickOfLevelLIsADenseMapTwoToTheLTimesFiner) {
  std::mt19937_64 rng(test_seed() + 2);
  DeviceConfig cfg = sparse_config(8);
  cfg.MW = 22;  // room for M * 2^3
  for (int l = 0; l <= kMaxLevel; ++l) {
    const double s = std::ldexp(1.0, l);
    auto coarse = [&](double x, double y, double z) { return field_value(cfg, x * 2.2, y * 1.9, z * 2.1); };
    auto fine = [&](double x, double y, double z) { return coarse(x / s, y / s, z / s); };
    DeviceMemory mem;
    const uint32_t n = 8, nf = uint32_t(8 << l);
    Job dense;
    dense.map_base = test::append_dense_field(cfg, nf, nf, nf, fine, mem);
    dense.nx = dense.ny = dense.nz = nf;
    const test::SparsePlacement p =
        test::append_sparse_field(cfg, n, n, n, coarse, [l](uint64_t, uint64_t, uint64_t) { return l; }, mem);
    ASSERT_EQ(p.brick_units, level_units(cfg, l));
    mem.shell = cloud(cfg, rng, n, 600);
    Job sparse = test::sparse_map_job(p, n, n, n);
    for (int k = 0; k < 6; ++k) {
      random_pose(cfg, rng, n, sparse);
      sparse.shell_count = uint32_t(mem.shell.size());
      sparse.threshold = int64_t{1} << 60 >> (64 - cfg.IW());  // every inside point a hit
      Job d = dense;
      d.shell_count = sparse.shell_count, d.threshold = sparse.threshold;
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) d.M[i][j] = sparse.M[i][j] * int64_t(s);
        d.t[i] = sparse.t[i] * int64_t(s);
      }
      const std::vector<ShellWord> pts = job_points(cfg, mem.shell, sparse);
      size_t inside = 0;
      for (const ShellWord& pt : pts) {
        const Lookup a = look_up(cfg, mem.map, sparse, pt), b = look_up(cfg, mem.map, d, pt);
        ASSERT_EQ(a.loc.inside, b.loc.inside);
        if (!a.loc.inside) continue;
        ++inside;
        ASSERT_EQ(a.dist, b.dist) << "level " << l;
        for (int i = 0; i < 3; ++i) ASSERT_EQ(a.loc.index[i], b.loc.index[i] >> l) << "the voxel is the level-0 one";
      }
      EXPECT_GT(inside, 100u);
    }
  }
}

TEST(SparseMaps, UniformCellsInvalidCodesAndReferencesPastTheBricks) {
  const DeviceConfig cfg = sparse_config(8);
  const int64_t unit = int64_t{1} << (3 * cfg.WB), qmax = 127;
  DeviceMemory mem;
  // 3 x 1 x 1 cells: far, deep, a level-0 brick of value 5.
  const test::SparsePlacement p = test::append_sparse_field(
      cfg, 24, 8, 8, [](double, double, double) { return 5; },
      [](uint64_t cx, uint64_t, uint64_t) { return cx == 0 ? -1 : cx == 1 ? -2 : 0; }, mem);
  Job j = test::sparse_map_job(p, 24, 8, 8);
  j.M[0][0] = j.M[1][1] = j.M[2][2] = int64_t{1} << cfg.MF;
  auto dist_at = [&](const Job& job, double x) {
    return look_up(cfg, mem.map, job, ShellWord{int64_t(std::ldexp(x, cfg.PF)), 3 << cfg.PF, 3 << cfg.PF}).dist;
  };
  EXPECT_EQ(dist_at(j, 3.3), qmax * unit);
  EXPECT_EQ(dist_at(j, 11.7), (-qmax - 1) * unit);
  EXPECT_EQ(dist_at(j, 19.1), 5 * unit);
  Job short_of = j;
  short_of.brick_units = 0;  // the brick is past the job's units: code 0
  EXPECT_EQ(dist_at(short_of, 19.1), qmax * unit);
  // Codes 6..15 read as code 0; the units of the cells before a cell count in its word only up to it.
  for (uint64_t code = kCodeLevel0 + kMaxLevel + 1; code < 16; ++code) {
    DeviceMemory m2 = mem;
    m2.map[p.map_base] = (m2.map[p.map_base] & ~uint64_t{0xf0}) | code << 4;  // cell 1
    EXPECT_EQ(read_cell(cfg, m2.map, j, {p.map_base, 1}).code, kCodeFar) << code;
    EXPECT_EQ(read_cell(cfg, m2.map, j, {p.map_base, 2}).first, p.brick_base) << code;
  }
  // 2-bit: a uniform surface cell, and a brick past the units reads as empty.
  const DeviceConfig c2 = sparse_config();
  DeviceMemory m2;
  std::vector<uint8_t> states(16 * 8 * 8, kSurface);
  for (size_t i = 8; i < states.size(); i += 16) states[i] = kInterior;  // the second cell mixed
  const test::SparsePlacement p2 = test::append_sparse_states(c2, 16, 8, 8, states, m2);
  ASSERT_EQ(p2.codes, (std::vector<uint8_t>{kSurface, kCodeBrick}));
  Job j2 = test::sparse_map_job(p2, 16, 8, 8);
  j2.M[0][0] = j2.M[1][1] = j2.M[2][2] = int64_t{1} << c2.MF;
  auto state_at = [&](const Job& job, int x) {
    return look_up(c2, m2.map, job, ShellWord{(x << c2.PF) + 1, 1 << c2.PF, 1 << c2.PF}).state;
  };
  EXPECT_EQ(state_at(j2, 3), kSurface);
  EXPECT_EQ(state_at(j2, 8), kInterior);
  EXPECT_EQ(state_at(j2, 9), kSurface);
  j2.brick_units = 0;
  EXPECT_EQ(state_at(j2, 8), kEmpty);
}

TEST(SparseShells, WordsGenerateTheirChainsPoints) {
  const DeviceConfig cfg = sparse_config();
  const int64_t u = int64_t{1} << cfg.PF, h = u / 2;
  const int up[3] = {1, 0, 0}, back[3] = {-2, 1, -1}, none[3] = {0, 0, 0};
  std::vector<ShellWord> shell = {origin_word(cfg, 8 * u, -4 * u, 0), brick_word(cfg, 0b1 | uint64_t{1} << 63, none),
                                  brick_word(cfg, 0b110, up), brick_word(cfg, 0, back),
                                  brick_word(cfg, uint64_t{1} << 21, back)};
  Job j;
  j.sparse = kSparseShell;
  j.shell_count = uint32_t(shell.size());
  std::vector<uint32_t> pops;
  const std::vector<ShellWord> pts = shell_points(cfg, shell, j, &pops);
  EXPECT_EQ(pops, (std::vector<uint32_t>{0, 2, 2, 0, 1}));
  const std::vector<ShellWord> want = {
      {8 * u + h, -4 * u + h, h},                  // bit 0 of the first brick
      {8 * u + 3 * u + h, -4 * u + 3 * u + h, 3 * u + h},  // bit 63: (3, 3, 3)
      {12 * u + u + h, -4 * u + h, h},             // the next brick along x: bits 1 and 2
      {12 * u + 2 * u + h, -4 * u + h, h},
      // two steps of (-2, 1, -1) bricks: origin (12 - 16, -4 + 8, -8) voxels; bit 21 = (1, 1, 1)
      {-4 * u + u + h, 4 * u + u + h, -8 * u + u + h}};
  ASSERT_EQ(pts.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) EXPECT_EQ(pts[k], want[k]) << k;
  EXPECT_TRUE(is_origin_word(cfg, shell[0]));
  EXPECT_FALSE(is_origin_word(cfg, shell[1]));
  // Slots: each word max(1, ceil(pop / LANES)).
  DeviceConfig c4 = cfg;
  c4.LANES = 1;
  const JobSlots s1 = job_slots(c4, shell, j);
  EXPECT_EQ(s1.groups, 1u + 2 + 2 + 1 + 1);
  EXPECT_EQ(s1.slot_of(0), 1u);
  EXPECT_EQ(s1.slot_of(4), 6u);
  c4.LANES = 4;
  const JobSlots s4 = job_slots(c4, shell, j);
  EXPECT_EQ(s4.groups, 5u);
  EXPECT_EQ(s4.slot_of(3), 2u);
  EXPECT_EQ(s4.begin(2), 2u);
  EXPECT_EQ(s4.end(1), 2u);
  EXPECT_THROW(job_slots(c4, j), std::invalid_argument) << "a sparse shell's slots need its words";
}

TEST(SparseShells, OriginsWrapAtPWBitsAsTheRegistersDo) {
  const DeviceConfig cfg = sparse_config();
  const int64_t top = (int64_t{1} << (cfg.PW - 2)) - 1;  // the largest origin z
  const int up[3] = {1, 1, 1};
  const std::vector<ShellWord> shell = {origin_word(cfg, (int64_t{1} << (cfg.PW - 1)) - 1, 0, top),
                                        brick_word(cfg, 1, up)};
  Job j;
  j.sparse = kSparseShell;
  j.shell_count = 2;
  const std::vector<ShellWord> pts = shell_points(cfg, shell, j);
  ASSERT_EQ(pts.size(), 1u);
  const int64_t m = int64_t{1} << cfg.PW, step = 4 << cfg.PF, h = 1 << (cfg.PF - 1);
  auto wrap = [m](int64_t v) { v = ((v % m) + m) % m; return v >= m / 2 ? v - m : v; };
  EXPECT_EQ(pts[0].x, wrap(m / 2 - 1 + step + h));
  EXPECT_EQ(pts[0].z, wrap(top + step + h));
  EXPECT_THROW(origin_word(cfg, 0, 0, top + 1), std::invalid_argument) << "z has PW - 1 bits";
}

// A sparse shell's hits are those of the dense shell of its points; only the slots (so the cycles) differ.
TEST(SparseShells, HitsAreThoseOfTheDenseShellOfTheirPoints) {
  std::mt19937_64 rng(test_seed() + 3);
  const DeviceConfig cfg = sparse_config();
  DeviceMemory mem;
  mem.map.assign(64, 0);
  for (uint64_t& w : mem.map) w = rng();
  Job sparse;
  sparse.sparse = kSparseShell;
  sparse.nx = sparse.ny = sparse.nz = 12;
  const int64_t u = int64_t{1} << cfg.PF;
  mem.shell.push_back(origin_word(cfg, -u, 0, 0));
  for (int k = 0; k < 40; ++k) {
    const int step[3] = {int(rng() % 4) - 2, int(rng() % 2), 0};
    mem.shell.push_back(brick_word(cfg, rng() & rng(), step));
  }
  sparse.shell_count = uint32_t(mem.shell.size());
  random_pose(cfg, rng, 12, sparse);
  Job dense = sparse;
  dense.sparse = 0;
  const std::vector<ShellWord> pts = job_points(cfg, mem.shell, sparse);
  dense.shell_base = uint32_t(mem.shell.size());
  dense.shell_count = uint32_t(pts.size());
  mem.shell.insert(mem.shell.end(), pts.begin(), pts.end());
  for (Mode mode : {Mode::All, Mode::First, Mode::Count}) {
    sparse.mode = dense.mode = mode;
    std::vector<Record> a = run_stream(cfg, mem, {dense}), b = run_stream(cfg, mem, {sparse});
    ASSERT_EQ(a.size(), b.size());
    for (size_t r = 0; r < a.size(); ++r) EXPECT_TRUE(a[r].same_as(b[r], false)) << r;
    annotate_cycles(cfg, mem, {dense}, a);
    annotate_cycles(cfg, mem, {sparse}, b);
    if (mode == Mode::Count) {
      EXPECT_NE(*a.back().cycles, *b.back().cycles) << "slots follow the words";
    }
  }
}

TEST(SparseJobs, ValidationAndFaults) {
  const DeviceConfig sparse = sparse_config(), dense_dev;
  DeviceMemory mem;
  std::vector<uint8_t> states(16 * 8 * 8, kSurface);
  states[3] = kInterior;
  const test::SparsePlacement p = test::append_sparse_states(sparse, 16, 8, 8, states, mem);
  mem.shell.assign(4, ShellWord{});
  Job j = test::sparse_map_job(p, 16, 8, 8);
  const uint64_t words = mem.map.size();
  EXPECT_EQ(job_faults(sparse, j, 4, words), 0u);
  EXPECT_NO_THROW(validate_job(sparse, j, 4, words));
  EXPECT_EQ(job_faults(dense_dev, j, 4, words), uint32_t(kFaultMap)) << "a sparse map on a dense device";
  EXPECT_THROW(validate_job(dense_dev, j, 4, words), JobError);
  EXPECT_EQ(job_faults(sparse, j, 4, words - 1), uint32_t(kFaultMap)) << "the last brick word not loaded";
  Job shell = Job{};
  shell.sparse = kSparseShell;
  shell.shell_count = 4;
  EXPECT_EQ(job_faults(dense_dev, shell, 4, words), uint32_t(kFaultShell));
  Job stray = Job{};
  stray.brick_units = 1;
  EXPECT_EQ(job_faults(sparse, stray, 4, words), uint32_t(kFaultMap)) << "a dense map's brick fields are 0";
  stray = Job{};
  stray.sparse = 4;
  EXPECT_EQ(job_faults(sparse, stray, 4, words), uint32_t(kFaultMode));
  try {
    validate_job(sparse, [&] { Job k = j; k.brick_units = 9; return k; }(), 4, words);
    FAIL() << "bricks past the loaded words";
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("brick words"), std::string::npos) << e.what();
  }
  const DeviceConfig dist = sparse_config(8);
  Job off = j;
  off.map_base = 8, off.brick_base = 12;  // not on a bank boundary
  EXPECT_TRUE(job_faults(dist, off, 4, 1 << 12) & kFaultMap);
}

TEST(SparseTiming, PipelineSlotsAndPlaces) {
  DeviceConfig c = sparse_config();
  EXPECT_EQ(pipeline_slots(c), 9);
  EXPECT_EQ(pipeline_places(c).table_read, 5);
  EXPECT_EQ(pipeline_places(c).brick_read, 7);
  EXPECT_EQ(pipeline_places(c).hit_known, 8);
  c.SB = 8;
  EXPECT_EQ(pipeline_slots(c), 13);
  EXPECT_EQ(pipeline_places(c).brick_read, 8);
  c.depth = 5;
  EXPECT_EQ(pipeline_slots(c), 18);
  EXPECT_EQ(pipeline_places(c).table_read, 9);
  EXPECT_EQ(pipeline_places(c).hit_known, 17);
  c.SB = 2;
  EXPECT_EQ(pipeline_places(c).hit_known, pipeline_slots(c) - 2) << "a 2-bit hit is seen before READ";
  const DeviceConfig dense;
  EXPECT_EQ(pipeline_places(dense).brick_read, -1);
  EXPECT_EQ(pipeline_places(dense).table_read, 4);
}

// A banked sparse device: 2 lanes, 1 bank. Slot 1 of a FIRST job that hits in slot 0 reads two table words: one
// round waits while the hit travels from R5 to the hit test (the window), the brick port reads nothing.
TEST(SparseBanks, FirstWindowCountsTheTablePortsWaitsBehindTheHit) {
  DeviceConfig cfg = sparse_config();
  cfg.LANES = 2;
  cfg.BANKS = 1;
  DeviceMemory mem;
  // 64 x 8 x 8 voxels: 8 cells, uniform surface; 16 cells a table word, so cells 0 and 4 share a word... use 4 words
  // apart: 512 x 8 x 8 voxels, 64 cells, cells 0 and 16 in table words 0 and 1.
  std::vector<uint8_t> states(512 * 8 * 8, kSurface);
  const test::SparsePlacement p = test::append_sparse_states(cfg, 512, 8, 8, states, mem);
  ASSERT_EQ(p.brick_units, 0u);
  Job j = test::sparse_map_job(p, 512, 8, 8);
  j.mode = Mode::First;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = int64_t{1} << cfg.MF;
  const int64_t u = int64_t{1} << cfg.PF;
  for (int k = 0; k < 12; ++k) mem.shell.push_back({(k % 2) * 128 * u + u, u, u});  // cells 0 and 16
  j.shell_count = 12;
  const std::vector<Record> recs = run_stream(cfg, mem, {j});
  ASSERT_EQ(recs.size(), 2u);
  const std::vector<BankCycles> b = bank_cycles(cfg, mem, {j}, recs);
  EXPECT_EQ(b[0].conflicts, 2u) << "slot 0's own wait and one of slot 1 in the window";
  EXPECT_EQ(b[0].window, 1u);
  j.mode = Mode::Count;
  const std::vector<Record> all = run_stream(cfg, mem, {j});
  EXPECT_EQ(bank_cycles(cfg, mem, {j}, all)[0].conflicts, 6u) << "six slots of two table rounds";
}

TEST(SparseVectors, Version3RoundTripsAndRunsAsGenerated) {
  for (int sb : {2, 8}) {
    GenerateOptions o;
    o.seed = test_seed() + uint64_t(sb);
    o.jobs = 150;
    o.cloud_points = 300;
    o.config = sparse_config(sb);
    o.config.BANKS = sb == 2 ? 2 : 0;
    const GeneratedVectors g = generate_vectors(o);
    size_t sparse_maps = 0, sparse_shells = 0;
    for (const Job& j : g.jobs) sparse_maps += j.sparse_map(), sparse_shells += j.sparse_shell();
    EXPECT_GT(sparse_maps, 20u);
    EXPECT_GT(sparse_shells, 10u);
    std::vector<Record> recs = run_stream(g.config, g.memory, g.jobs);
    annotate_cycles(g.config, g.memory, g.jobs, recs);
    std::ostringstream os;
    write_vectors(os, g.config, true, g.memory, g.jobs, recs);
    const std::string text = os.str();
    ASSERT_EQ(text.rfind("voxcd-vectors 3\n", 0), 0u);
    const VectorFile f = parse_vectors(text, "gen.vec");
    EXPECT_EQ(f.config, g.config);
    ASSERT_EQ(f.jobs.size(), g.jobs.size());
    for (size_t k = 0; k < f.jobs.size(); ++k) {
      EXPECT_EQ(f.jobs[k].sparse, g.jobs[k].sparse);
      EXPECT_EQ(f.jobs[k].brick_base, g.jobs[k].brick_base);
      EXPECT_EQ(f.jobs[k].brick_units, g.jobs[k].brick_units);
    }
    EXPECT_EQ(compare_streams(f, recs, true), "");
  }
  // BL belongs to version 3; a version 3 job line has 25 fields.
  EXPECT_THROW(parse_vectors("voxcd-vectors 2\nconfig BL 3\n", "x.vec"), VectorError);
  EXPECT_THROW(parse_vectors("voxcd-vectors 3\njob 0 ALL 6 0 0 0 1 1 1 0 0 0 0 0 0 0 0 0 0 0 0 0\n", "x.vec"),
               VectorError);
}

}  // namespace
}  // namespace voxcd
