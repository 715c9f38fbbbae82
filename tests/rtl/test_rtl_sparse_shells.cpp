// Sparse shells on the RTL (docs/contract.md, "Shell bricks"): the directed cases 3 to 5 of
// tests/rtl/test_rtl_sparse.cpp on every sparse model of the build, against what each case says by hand and against
// ref/'s stream with cycles.
#include <gtest/gtest.h>

#include "tests/rtl/sparse_cases.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {
namespace {

Job identity_job(const DeviceConfig& cfg) {
  Job j;
  for (int i = 0; i < 3; ++i) j.M[i][i] = int64_t{1} << cfg.MF;
  return j;
}

// A 2-bit map of n^3 voxels all of state `s` (a distance map: every node `s`) at the end of mem.map; its job's
// map fields.
void append_uniform_map(const DeviceConfig& cfg, uint32_t n, uint64_t s, DeviceMemory& mem, Job& job) {
  mem.map.resize((mem.map.size() + 7) / 8 * 8, 0);
  job.map_base = uint32_t(mem.map.size());
  job.nx = job.ny = job.nz = n;
  uint64_t word = 0;
  const int width = cfg.distance() ? cfg.SB : 2;
  for (int b = 0; b < cfg.MEMW; b += width) word |= (s & ((uint64_t{1} << width) - 1)) << b;  // every slot s
  mem.map.resize(mem.map.size() + map_words(cfg, job), word);
}

// The jobs of case 3 on a 16^3 map where every inside point hits: job 0 reads words 0..4 (an origin word, a full
// brick, an empty mask that only moves the origin, two sparse bricks), job 1 words 1..2 (its origin starts at 0
// again), job 2 words 5..6 (an origin near the top of x, then a step that wraps x to the bottom, where the translation
// brings it back into the map: only a wrapped sum hits), job 3 an empty sparse shell, job 4 words 1..4 on a sparse
// map of the same states.
std::vector<Job> case3_jobs(const DeviceConfig& cfg, DeviceMemory& mem) {
  const int step0[3] = {0, 0, 0}, step_x[3] = {1, 0, 0}, step_xy[3] = {1, 1, 0}, step_back[3] = {-2, 0, 1};
  const int64_t v = int64_t{1} << cfg.PF;
  mem.shell = {origin_word(cfg, 4 * v, 4 * v, 4 * v), brick_word(cfg, ~uint64_t{0}, step0),
               brick_word(cfg, 0, step_x), brick_word(cfg, uint64_t{1} << 63 | 1, step_xy),
               brick_word(cfg, 0xf0f0, step_back),
               origin_word(cfg, (int64_t{1} << (cfg.PW - 1)) - 4 * v, 2 * v, 2 * v),
               brick_word(cfg, 0x8421, step_x)};
  Job base = identity_job(cfg);
  base.sparse = kSparseShell, base.hit_mask = 0b0110, base.threshold = cfg.distance() ? int64_t{3} << (3 * cfg.WB) : 0;
  append_uniform_map(cfg, 16, cfg.distance() ? 3 : 1, mem, base);
  std::vector<Job> jobs(5, base);
  jobs[0].shell_count = 5;
  jobs[1].tag = 1, jobs[1].shell_base = 1, jobs[1].shell_count = 2;
  jobs[2].tag = 2, jobs[2].shell_base = 5, jobs[2].shell_count = 2;
  jobs[2].t[0] = int64_t{1} << (cfg.PW - 1 - cfg.PF + cfg.TF());  // +2^(PW-1-PF) voxels
  jobs[3].tag = 3, jobs[3].shell_count = 0;
  jobs[4].tag = 4, jobs[4].shell_base = 1, jobs[4].shell_count = 4, jobs[4].mode = Mode::Count;
  if (!cfg.distance()) {  // the same states as a sparse map: every cell uniform surface
    jobs[4].sparse |= kSparseMap;
    jobs[4].map_base = uint32_t(mem.map.size()), jobs[4].brick_base = 0, jobs[4].brick_units = 0;
    for (uint64_t w : table_image(cfg, std::vector<uint8_t>(coarse_dims(cfg, jobs[4]).cells(), kSurface)))
      mem.map.push_back(w);
  }
  return jobs;
}

TEST(RtlSparse, Case3ShellWords) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : rtl_sparse_configs()) {
    DeviceMemory mem;
    const std::vector<Job> jobs = case3_jobs(cfg, mem);
    const std::vector<Record> want = test::expect_rtl_exact(cfg, mem, jobs, "case 3");
    if (HasFatalFailure()) return;
    uint32_t hits[5] = {}, done[5] = {};
    bool wrapped_low = true, job1_at_origin = true;
    for (const Record& r : want) {
      if (r.kind == Record::Done) {
        done[r.tag] = r.hits;
        continue;
      }
      ++hits[r.tag];
      if (r.tag == 2) wrapped_low = wrapped_low && r.x < 4;
      if (r.tag == 1) job1_at_origin = job1_at_origin && r.x < 4 && r.y < 4 && r.z < 4;
    }
    // Job 0: 64 + 0 + 2 + 8 points, all inside; job 1: the full brick at the origin 0; job 2: 4 wrapped points.
    EXPECT_EQ(hits[0], 74u) << cfg.to_string();
    EXPECT_EQ(hits[1], 64u) << cfg.to_string();
    EXPECT_EQ(hits[2], 4u) << cfg.to_string();
    EXPECT_TRUE(wrapped_low && job1_at_origin) << cfg.to_string();
    EXPECT_EQ(done[3], 0u);
    EXPECT_EQ(done[4], 74u) << "COUNT of words 1..4: 64 + 0 + 2 + 8 points from the origin 0, all inside";
    ++ran;
  }
  EXPECT_GT(ran, 0u);
}

// Case 4: a FIRST job whose only hit is point j * LANES + j % LANES of a full brick word (so at slot j of the word,
// at every lane over the cases), or of the full word after it; each followed by a dense COUNT job, whose cycles show
// where the FIRST job left the pipeline.
TEST(RtlSparse, Case4FirstAtEverySlotOfABrickWord) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : rtl_sparse_configs()) {
    DeviceMemory mem;
    const int step0[3] = {0, 0, 0}, step_z[3] = {0, 0, 1};
    mem.shell = {brick_word(cfg, ~uint64_t{0}, step0), brick_word(cfg, ~uint64_t{0}, step_z)};
    for (int k = 0; k < 4; ++k) mem.shell.push_back({0, 0, 0});  // the dense job's points (outside: x < 0 below)
    std::vector<Job> jobs;
    std::vector<uint32_t> planted;
    const uint32_t lanes = uint32_t(cfg.LANES);
    for (uint32_t point = 0; point < 128; point += lanes) {
      const uint32_t k = point + (point / lanes) % lanes;
      Job first = identity_job(cfg);
      first.tag = uint32_t(jobs.size()), first.mode = Mode::First, first.sparse = kSparseShell;
      first.shell_count = 2, first.hit_mask = 0b0100;
      append_uniform_map(cfg, 8, cfg.distance() ? 5 : 0, mem, first);
      // Point k: bit k % 64 of word k / 64 (whose brick is 4 further in z), its voxel's state interior (a distance
      // map: the nodes of its voxel below the threshold 0).
      const uint64_t b = k % 64, x = b & 3, y = (b >> 2) & 3, z = (b >> 4) + 4 * (k / 64);
      if (cfg.distance()) {
        first.threshold = 0;
        for (uint64_t c = 0; c < 8; ++c) {
          const NodeAddress a = node_address(cfg, first, x + (c & 1), y + (c >> 1 & 1), z + (c >> 2));
          mem.map[a.word] &= ~(((uint64_t{1} << cfg.SB) - 1) << (cfg.SB * a.slot));  // node value 0
        }
      } else {
        const uint64_t i = x + 8 * (y + 8 * z), spw = uint64_t(cfg.states_per_word());
        mem.map[first.map_base + i / spw] |= uint64_t{2} << (2 * (i % spw));
      }
      Job dense = first;
      dense.tag = first.tag + 1, dense.mode = Mode::Count, dense.sparse = 0, dense.shell_base = 2;
      dense.shell_count = 4, dense.t[0] = -(int64_t{1} << cfg.TF());
      jobs.push_back(first);
      jobs.push_back(dense);
      planted.push_back(k);
    }
    const std::vector<Record> hits = test::hits_of(test::expect_rtl_exact(cfg, mem, jobs, "case 4"));
    if (HasFatalFailure()) return;
    ASSERT_EQ(hits.size(), planted.size()) << cfg.to_string();
    for (size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i].point, planted[i]) << cfg.to_string();
    ++ran;
  }
  EXPECT_GT(ran, 0u);
}

// Case 5: a one-point job that hits, first in a stream, on a sparse model and on the dense model of the same lanes,
// banks and depth where the build has one: the sparse device's completion comes kSparseSlots cycles later
// (kSparseDistanceSlots on a distance device), as ref/timing.h says.
TEST(RtlSparse, Case5SparseRegistersAddLatencyOnly) {
  size_t ran = 0;
  for (const DeviceConfig& cfg : rtl_sparse_configs()) {
    DeviceConfig dense = cfg;
    dense.BL = 0;
    dense.TX = 0;  // brick lanes are a sparse device's; a one-point job's latency is the same with them
    DeviceMemory mem;
    Job job = identity_job(cfg);
    append_uniform_map(cfg, 4, cfg.distance() ? 0 : 1, mem, job);
    job.threshold = cfg.distance() ? 1 : 0;
    job.shell_count = 1;
    mem.shell = {{1 << cfg.PF, 1 << cfg.PF, 1 << cfg.PF}};
    auto cycles = [&](const DeviceConfig& c) {
      auto dev = make_device("rtl", c);
      dev->load(mem);
      const std::vector<Record> got = dev->run({job});
      EXPECT_EQ(got.size(), 2u);
      return got.empty() ? uint64_t{0} : got.back().cycles.value_or(0);
    };
    const uint64_t sparse_cycles = cycles(cfg);
    EXPECT_EQ(sparse_cycles, 2 + uint64_t(pipeline_slots(cfg))) << cfg.to_string();
    try {
      const uint64_t dense_cycles = cycles(dense);
      EXPECT_EQ(sparse_cycles - dense_cycles, uint64_t(cfg.distance() ? kSparseDistanceSlots : kSparseSlots))
          << cfg.to_string();
      ++ran;
    } catch (const DeviceError&) {
      // No dense model of this configuration in the build.
    }
  }
  EXPECT_GT(ran, 0u) << "the build has a dense model beside some sparse one (LANES 4, the default device)";
}

}  // namespace
}  // namespace voxcd
