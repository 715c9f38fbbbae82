// FastRunner (ref/fast/fast.h) against the specification: the same record stream as run_stream, with annotate_cycles'
// cycles, on generated vectors for every arithmetic path (double, int64, 128-bit), for 1 to 3 threads; memories
// written piecewise and rewritten between runs; invalid input refused before anything runs or is written.
// Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "tests/ref/directed_cases.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(777001); }

std::vector<Record> reference(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  std::vector<Record> want = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, jobs, want);
  return want;
}

void expect_same(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], true))
        << what << " record " << i << ": expected '" << want[i].to_string() << "', got '" << got[i].to_string()
        << "'";
    ASSERT_EQ(got[i].points, want[i].points) << what << " record " << i;
    ASSERT_EQ(got[i].stalls, want[i].stalls) << what << " record " << i;
  }
}

struct PathConfig {
  const char* name;
  DeviceConfig cfg;
  FastRunner::Path path;
};

std::vector<PathConfig> path_configs() {
  std::vector<PathConfig> v;
  v.push_back({"default", DeviceConfig{}, FastRunner::Path::Double});
  DeviceConfig c;
  c.PW = 14, c.PF = 3, c.MW = 10, c.MF = 8, c.TW = 24, c.DW = 7, c.MEMW = 16, c.LANES = 1;
  v.push_back({"coarse", c, FastRunner::Path::Double});
  c = DeviceConfig{};
  c.PW = 28, c.PF = 10, c.MW = 24, c.MF = 20, c.TW = 56, c.LANES = 8;
  v.push_back({"wide", c, FastRunner::Path::Int64});
  c = DeviceConfig{};
  c.PW = 32, c.PF = 16, c.MW = 26, c.MF = 24, c.TW = 64, c.MEMW = 32, c.LANES = 2;
  v.push_back({"widest", c, FastRunner::Path::Wide});
  return v;
}

TEST(FastRunner, MatchesRunStreamOnEveryPathAndThreadCount) {
  const uint64_t seed = test_seed();
  std::printf("double kernel %s\n", FastRunner::double_kernel());
  for (const PathConfig& pc : path_configs()) {
    GenerateOptions g;
    g.seed = seed;
    g.jobs = 400;
    g.config = pc.cfg;
    const GeneratedVectors v = generate_vectors(g);
    const std::vector<Record> want = reference(v.config, v.memory, v.jobs);
    size_t hits = 0;
    for (const Record& r : want) hits += r.kind == Record::Hit;
    EXPECT_GT(hits, 100u) << pc.name << ": the generated vectors must exercise hits";
    for (unsigned threads : {1u, 2u, 3u}) {
      FastRunner fr(v.config, threads);
      ASSERT_EQ(fr.path(), pc.path) << pc.name << " takes the " << FastRunner::path_name(pc.path) << " path";
      fr.load(v.memory);
      const std::string what = std::string(pc.name) + " (" + FastRunner::path_name(fr.path()) + " path) threads " +
                               std::to_string(threads) + " seed " + std::to_string(seed);
      expect_same(want, fr.run(v.jobs), what);
      // Without cycles: the same records, none of them timed.
      const std::vector<Record> untimed = fr.run(v.jobs, false);
      ASSERT_EQ(untimed.size(), want.size()) << what;
      for (size_t i = 0; i < want.size(); ++i) {
        ASSERT_TRUE(untimed[i].same_as(want[i], false)) << what << " record " << i;
        ASSERT_FALSE(untimed[i].cycles.has_value()) << what << " record " << i;
      }
    }
  }
}

TEST(FastRunner, MatchesDirectedCases) {
  for (const auto& c : testing::directed_cases()) {
    FastRunner fr(c.config, 2);
    fr.load(c.memory);
    expect_same(reference(c.config, c.memory, c.jobs), fr.run(c.jobs), c.name);
  }
}

TEST(FastRunner, LargeJobsSplitIntoChunksKeepOrder) {
  // One job of 50000 points per mode on a dense map: many chunks over the threads; FIRST still reports the lowest.
  GenerateOptions g;
  g.seed = test_seed() + 1;
  g.jobs = 0;
  g.cloud_points = 50000;
  GeneratedVectors v = generate_vectors(g);
  for (auto& w : v.memory.map) w = 0x5555555555555555ull;
  Job j;
  j.shell_count = 50000;
  j.nx = j.ny = j.nz = 16;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = 1 << 14;
  for (Mode m : {Mode::All, Mode::First, Mode::Count}) {
    j.mode = m;
    ++j.tag;
    v.jobs.push_back(j);
  }
  const std::vector<Record> want = reference(v.config, v.memory, v.jobs);
  EXPECT_GT(want.size(), 1000u);
  for (unsigned threads : {1u, 2u}) {
    FastRunner fr(v.config, threads);
    fr.load(v.memory);
    expect_same(want, fr.run(v.jobs), "threads " + std::to_string(threads));
  }
}

TEST(FastRunner, PiecewiseWritesAndRewritesBetweenRuns) {
  const uint64_t seed = test_seed() + 2;
  std::mt19937_64 rng(seed);
  for (const PathConfig& pc : path_configs()) {
    const std::string what = std::string(pc.name) + " seed " + std::to_string(seed);
    GenerateOptions g;
    g.seed = seed;
    g.jobs = 150;
    g.config = pc.cfg;
    const GeneratedVectors v = generate_vectors(g);
    // Words written in random-sized pieces, in random order, as an initiator would through the write port.
    FastRunner fr(v.config, 1);
    const auto write_all = [&](const DeviceMemory& mem) {
      std::vector<std::pair<size_t, size_t>> pieces;
      for (size_t k = 0; k < mem.shell.size();) {
        const size_t n = std::min<size_t>(mem.shell.size() - k, 1 + rng() % 300);
        pieces.push_back({k, n});
        k += n;
      }
      std::shuffle(pieces.begin(), pieces.end(), rng);
      for (auto [k, n] : pieces) fr.write_shell(k, mem.shell.data() + k, n);
      pieces.clear();
      for (size_t k = 0; k < mem.map.size();) {
        const size_t n = std::min<size_t>(mem.map.size() - k, 1 + rng() % 300);
        pieces.push_back({k, n});
        k += n;
      }
      std::shuffle(pieces.begin(), pieces.end(), rng);
      for (auto [k, n] : pieces) fr.write_map(k, mem.map.data() + k, n);
    };
    write_all(v.memory);
    ASSERT_EQ(fr.shell_words(), v.memory.shell.size()) << what;
    ASSERT_EQ(fr.map_words(), v.memory.map.size()) << what;
    std::vector<Record> out;
    fr.run_into(v.jobs, out);
    expect_same(reference(v.config, v.memory, v.jobs), out, what + " first load");
    // Rewrite both memories (points mirrored through the origin, map states rotated) and run into the same
    // vector: a runner that kept stale copies of either memory would give the first stream again.
    DeviceMemory m2 = v.memory;
    for (ShellWord& w : m2.shell) {
      const int64_t lim = (int64_t{1} << (v.config.PW - 1)) - 1;
      w = {std::min(-w.x, lim), std::min(-w.y, lim), std::min(-w.z, lim)};
    }
    const uint64_t word_mask = v.config.MEMW == 64 ? ~uint64_t{0} : (uint64_t{1} << v.config.MEMW) - 1;
    for (uint64_t& w : m2.map) w = ((w << 2) | (w >> (v.config.MEMW - 2))) & word_mask;
    const std::vector<Record> want2 = reference(v.config, m2, v.jobs);
    ASSERT_FALSE(std::equal(want2.begin(), want2.end(), out.begin(), out.end(),
                            [](const Record& a, const Record& b) { return a.same_as(b, true); }))
        << what << ": the rewrite must change the stream";
    write_all(m2);
    fr.run_into(v.jobs, out);
    expect_same(want2, out, what + " after rewriting");
    // load() replaces both memories, shrinking them too.
    fr.load(v.memory);
    expect_same(reference(v.config, v.memory, v.jobs), fr.run(v.jobs), what + " after load");
  }
}

TEST(FastRunner, RefusesInvalidInputBeforeActing) {
  DeviceConfig cfg;
  FastRunner fr(cfg, 2);
  DeviceMemory mem;
  mem.shell = {{256, 0, 0}, {0, 256, 0}};
  mem.map = {0x5555555555555555ull};
  fr.load(mem);
  Job ok;
  ok.tag = 1;
  ok.shell_count = 2;
  ok.nx = ok.ny = ok.nz = 2;
  ok.M[0][0] = ok.M[1][1] = ok.M[2][2] = 1 << 16;
  Job bad = ok;
  bad.tag = 2;
  bad.shell_count = 3;  // past the two loaded shell words
  std::vector<Record> out = {Record::done(99, 0)};
  EXPECT_THROW(fr.run_into({ok, bad}, out), JobError);
  ASSERT_EQ(out.size(), 1u) << "nothing may run (or be written) when one job is invalid";
  EXPECT_EQ(out[0].tag, 99u);
  // A coordinate beyond PW bits, a word beyond the shell depth, a map word beyond MEMW: refused, nothing written.
  const ShellWord far{int64_t{1} << 23, 0, 0};
  EXPECT_THROW(fr.write_shell(1, &far, 1), JobError);
  EXPECT_THROW(fr.write_shell(cfg.shell_depth(), mem.shell.data(), 1), JobError);
  DeviceConfig narrow = cfg;
  narrow.MEMW = 32;
  FastRunner fn(narrow);
  const uint64_t wide_word = uint64_t{1} << 32;
  EXPECT_THROW(fn.write_map(0, &wide_word, 1), JobError);
  EXPECT_EQ(fn.map_words(), 0u);
  DeviceMemory too_wide = mem;
  too_wide.shell[1].z = -(int64_t{1} << 23) - 1;
  EXPECT_THROW(fr.load(too_wide), JobError);
  EXPECT_EQ(fr.shell_words(), 2u);
  const std::vector<Record> got = fr.run({ok});
  expect_same(reference(cfg, mem, {ok}), got, "after refused writes");
  ASSERT_EQ(got.size(), 3u);  // both points hit (voxels (1,0,0) and (0,1,0), surface), then the completion
  DeviceConfig invalid;
  invalid.PW = 0;
  EXPECT_THROW(FastRunner{invalid}, ConfigError);
}

TEST(FastRunner, ParallelBatchesOfSmallJobsAndEmptyOnesKeepTheStream) {
  // A batch above kParallelMinPoints made of many small jobs of every mode, with jobs of no points between them and
  // first and last: the pieces run as tasks of several jobs, and the stream (and the cycles, joined from the pieces'
  // summaries) are run_stream's on every thread count.
  GenerateOptions g;
  g.seed = test_seed() + 3;
  g.jobs = 600;
  g.cloud_points = 20000;
  for (int lanes : {4, 3}) {
    g.config.LANES = lanes;
    GeneratedVectors v = generate_vectors(g);
    std::vector<Job> jobs;
    Job empty;
    empty.nx = empty.ny = empty.nz = 1;
    size_t points = 0;
    for (size_t k = 0; k < v.jobs.size(); ++k) {
      if (k % 50 == 0) jobs.push_back(empty);
      jobs.push_back(v.jobs[k]);
      points += v.jobs[k].shell_count;
    }
    jobs.push_back(empty);
    for (size_t k = 0; k < jobs.size(); ++k) jobs[k].tag = uint32_t(k & v.config.max_tag());
    ASSERT_GE(points, FastRunner::kParallelMinPoints);
    const std::vector<Record> want = reference(v.config, v.memory, jobs);
    for (unsigned threads : {1u, 2u, 3u}) {
      FastRunner fr(v.config, threads);
      fr.load(v.memory);
      std::vector<Record> out(5 * want.size());  // a longer vector from before: shrunk, every record rewritten
      fr.run_into(jobs, out);
      expect_same(want, out, "lanes " + std::to_string(lanes) + " threads " + std::to_string(threads));
      fr.run_into(jobs, out);
      expect_same(want, out, "again, lanes " + std::to_string(lanes) + " threads " + std::to_string(threads));
    }
  }
}

TEST(FastRunner, ParallelBatchesRefuseTheFirstInvalidJobBeforeWriting) {
  // The parallel path validates each job in the task that runs its first piece: the error is the first invalid
  // job's, as on one thread, and `out` is left as it was.
  GenerateOptions g;
  g.seed = test_seed() + 4;
  g.jobs = 600;
  g.cloud_points = 20000;
  GeneratedVectors v = generate_vectors(g);
  std::vector<Job> jobs = v.jobs;
  jobs[400].shell_count = uint32_t(v.memory.shell.size()) + 1;  // past the loaded shell
  jobs[500].nx = 0;
  std::string want;
  for (unsigned threads : {1u, 2u, 3u}) {
    FastRunner fr(v.config, threads);
    fr.load(v.memory);
    std::vector<Record> out = {Record::done(99, 0)};
    try {
      fr.run_into(jobs, out);
      FAIL() << "no error";
    } catch (const JobError& e) {
      if (want.empty()) want = e.what();
      EXPECT_EQ(want, e.what()) << threads << " threads";
    }
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].tag, 99u);
  }
}

}  // namespace
}  // namespace voxcd
