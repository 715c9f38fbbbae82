// The DPI-C reference's C interface (ref/dpi/voxcd_dpi.h) without a simulator: its stream and cycles against
// ref/ over whole random streams, the idle restart, and every error path with its message.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"
#include "voxcd_dpi.h"

namespace {

using namespace voxcd;

// Owns a device; fails the test when it cannot be made.
struct Handle {
  void* h;
  explicit Handle(const std::string& cfg) : h(voxcd_dpi_new(cfg.c_str())) {
    EXPECT_NE(h, nullptr) << voxcd_dpi_error(nullptr);
  }
  ~Handle() { voxcd_dpi_free(h); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
};

void write_memory(void* h, const DeviceMemory& mem) {
  for (size_t k = 0; k < mem.shell.size(); ++k)
    ASSERT_EQ(voxcd_dpi_write_shell(h, int(k), mem.shell[k].x, mem.shell[k].y, mem.shell[k].z), 0)
        << voxcd_dpi_error(h);
  for (size_t k = 0; k < mem.map.size(); ++k)
    ASSERT_EQ(voxcd_dpi_write_map(h, int(k), static_cast<long long>(mem.map[k])), 0) << voxcd_dpi_error(h);
}

int submit(void* h, const Job& j) {
  return voxcd_dpi_submit(h, int(j.tag), int(j.mode), j.hit_mask, int(j.shell_base), int(j.shell_count),
                          int(j.map_base), int(j.nx), int(j.ny), int(j.nz), j.M[0][0], j.M[0][1], j.M[0][2],
                          j.M[1][0], j.M[1][1], j.M[1][2], j.M[2][0], j.M[2][1], j.M[2][2], j.t[0], j.t[1],
                          j.t[2], j.threshold);
}

// Pops one record into a Record (cycles and points on completions, the distance on hits).
int pop(void* h, Record& r) {
  int tag = -1, point = -1, x = -1, y = -1, z = -1, state = -1, hits = -1;
  long long cycles = -1, points = -1, dist = -1;
  const int kind = voxcd_dpi_pop(h, &tag, &point, &x, &y, &z, &state, &hits, &cycles, &points, &dist);
  if (kind == VOXCD_DPI_HIT) r = Record::hit(uint32_t(tag), uint32_t(point), uint32_t(x), uint32_t(y),
                                             uint32_t(z), uint8_t(state), int64_t(dist));
  if (kind == VOXCD_DPI_DONE) {
    r = Record::done(uint32_t(tag), uint32_t(hits), uint64_t(cycles));
    r.points = uint64_t(points);
  }
  return kind;
}

std::vector<Record> pop_all(void* h) {
  std::vector<Record> out;
  Record r;
  for (int kind; (kind = pop(h, r)) != VOXCD_DPI_NONE;) {
    EXPECT_GT(kind, 0) << voxcd_dpi_error(h);
    if (kind < 0) break;
    out.push_back(r);
  }
  return out;
}

// The whole stream with ref/'s cycles: run_stream, then annotate_cycles over all of it.
std::vector<Record> reference_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs) {
  std::vector<Record> want = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, jobs, want);
  return want;
}

void expect_same_stream(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], true))
        << what << ": record " << i << ": expected '" << want[i].to_string() << "', got '" << got[i].to_string() << "'";
    if (want[i].kind == Record::Done) {
      ASSERT_EQ(got[i].points, want[i].points) << what << ": record " << i;
    }
  }
}

// A job's cycles depend on the job before it, never on later ones: submitting one job at a time and popping
// its records at once gives the stream ref/ computes for the whole stream, cycles and points included; on 2-bit
// and distance devices (thresholds in, distances out).
TEST(DpiApi, StreamAndCyclesEqualRefOverWholeStreams) {
  for (int sb : {2, 8, 4, 16}) {
    for (int lanes : {1, 2, 4, 8}) {
      GenerateOptions opt;
      opt.seed = 40 + uint64_t(lanes) + uint64_t(sb) * 10;
      opt.jobs = 600;
      opt.cloud_points = 1500;
      opt.config.LANES = lanes;
      opt.config.SB = sb;
      const GeneratedVectors g = generate_vectors(opt);
      Handle d(g.config.to_string());
      write_memory(d.h, g.memory);
      std::vector<Record> got;
      size_t firsts = 0;
      for (const Job& j : g.jobs) {
        const int n = submit(d.h, j);
        ASSERT_GE(n, 1) << voxcd_dpi_error(d.h);
        ASSERT_EQ(voxcd_dpi_pending(d.h), n) << "a job's records are all ready as soon as it is submitted";
        const std::vector<Record> recs = pop_all(d.h);
        ASSERT_EQ(recs.size(), size_t(n));
        got.insert(got.end(), recs.begin(), recs.end());
        firsts += j.mode == Mode::First && recs.back().hits == 1;
      }
      EXPECT_EQ(voxcd_dpi_jobs(d.h), int(g.jobs.size()));
      EXPECT_GT(firsts, 10u) << "the stream must have FIRST jobs that stop early";
      expect_same_stream(reference_stream(g.config, g.memory, g.jobs), got, g.config.to_string());
      if (sb > 2) {
        size_t nonzero = 0;
        for (const Record& r : got) nonzero += r.kind == Record::Hit && r.dist != 0;
        EXPECT_GT(nonzero, 100u) << "hit records carry their distances";
      }
    }
  }
}

// voxcd_dpi_generate draws exactly what ref/vector_gen draws for the device's configuration.
TEST(DpiApi, GenerateMatchesVectorGen) {
  Handle d("LANES 2 TAGW 8");
  ASSERT_EQ(voxcd_dpi_generate(d.h, 9, 300, 700), 0) << voxcd_dpi_error(d.h);
  GenerateOptions opt;
  opt.seed = 9;
  opt.jobs = 300;
  opt.cloud_points = 700;
  opt.config.LANES = 2;
  opt.config.TAGW = 8;
  const GeneratedVectors g = generate_vectors(opt);
  ASSERT_EQ(voxcd_dpi_gen_shell_words(d.h), int(g.memory.shell.size()));
  ASSERT_EQ(voxcd_dpi_gen_map_words(d.h), int(g.memory.map.size()));
  ASSERT_EQ(voxcd_dpi_gen_jobs(d.h), 300);
  for (size_t k = 0; k < g.memory.shell.size(); ++k) {
    long long x, y, z;
    ASSERT_EQ(voxcd_dpi_gen_shell(d.h, int(k), &x, &y, &z), 0);
    ASSERT_EQ(ShellWord({x, y, z}), g.memory.shell[k]) << "shell word " << k;
  }
  for (size_t k = 0; k < g.memory.map.size(); ++k) {
    long long w;
    ASSERT_EQ(voxcd_dpi_gen_map(d.h, int(k), &w), 0);
    ASSERT_EQ(uint64_t(w), g.memory.map[k]) << "map word " << k;
  }
  for (size_t k = 0; k < g.jobs.size(); ++k) {
    int f[9];
    long long m[9], t[3], threshold = -1;
    ASSERT_EQ(voxcd_dpi_gen_job(d.h, int(k), &f[0], &f[1], &f[2], &f[3], &f[4], &f[5], &f[6], &f[7], &f[8], &m[0],
                                &m[1], &m[2], &m[3], &m[4], &m[5], &m[6], &m[7], &m[8], &t[0], &t[1], &t[2],
                                &threshold),
              0);
    const Job& j = g.jobs[k];
    EXPECT_EQ(threshold, 0) << "a 2-bit device's jobs have threshold 0";
    EXPECT_EQ(job_line(j), "job " + std::to_string(f[0]) + " " + mode_name(Mode(f[1])) + " " + std::to_string(f[2]) +
                               " " + std::to_string(f[3]) + " " + std::to_string(f[4]) + " " + std::to_string(f[5]) +
                               " " + std::to_string(f[6]) + " " + std::to_string(f[7]) + " " + std::to_string(f[8]) +
                               [&] {
                                 std::string s;
                                 for (long long v : m) s += " " + std::to_string(v);
                                 for (long long v : t) s += " " + std::to_string(v);
                                 return s;
                               }())
        << "job " << k;
  }
  EXPECT_EQ(voxcd_dpi_gen_job(d.h, 300, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                              nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                              nullptr, nullptr, nullptr, nullptr, nullptr),
            -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_gen_job: job 300 is outside the generated 0..299");
}

// After voxcd_dpi_restart the next job is timed as a stream's first job; without it, as following the previous.
TEST(DpiApi, RestartTimesTheNextJobAsAFirstJob) {
  GenerateOptions opt;
  opt.seed = 5;
  opt.jobs = 200;
  const GeneratedVectors g = generate_vectors(opt);
  Handle d("");
  write_memory(d.h, g.memory);
  std::vector<Record> got;
  // Split after an ALL job: a FIRST job that stops early leaves the pipeline as empty as an idle device does.
  size_t split = 120;
  while (g.jobs[split - 1].mode != Mode::All) ++split;
  for (size_t k = 0; k < g.jobs.size(); ++k) {
    if (k == split) {
      ASSERT_EQ(voxcd_dpi_restart(d.h), 0);
    }
    ASSERT_GE(submit(d.h, g.jobs[k]), 1) << voxcd_dpi_error(d.h);
  }
  got = pop_all(d.h);
  const std::vector<Job> head(g.jobs.begin(), g.jobs.begin() + split), tail(g.jobs.begin() + split, g.jobs.end());
  std::vector<Record> want = reference_stream(g.config, g.memory, head);
  const std::vector<Record> second = reference_stream(g.config, g.memory, tail);
  want.insert(want.end(), second.begin(), second.end());
  expect_same_stream(want, got, "two streams");
  // The restart changed something: the back-to-back stream differs in the first job after the split, and only there.
  const std::vector<Record> whole = reference_stream(g.config, g.memory, g.jobs);
  ASSERT_EQ(whole.size(), got.size());
  std::vector<size_t> differ;  // jobs whose cycles differ
  for (size_t i = 0, job = 0; i < whole.size(); ++i) {
    if (whole[i].kind != Record::Done) continue;
    if (*whole[i].cycles != *got[i].cycles) differ.push_back(job);
    ++job;
  }
  EXPECT_EQ(differ, std::vector<size_t>{split});
}

TEST(DpiApi, BadConfigurationSaysWhichParameter) {
  EXPECT_EQ(voxcd_dpi_new("PW 99"), nullptr);
  EXPECT_STREQ(voxcd_dpi_error(nullptr), "voxcd_dpi_new(\"PW 99\"): invalid device configuration: PW = 99 is outside 2..32");
  EXPECT_EQ(voxcd_dpi_new("LANES 4 WIDTH 3"), nullptr);
  EXPECT_NE(std::string(voxcd_dpi_error(nullptr)).find("WIDTH"), std::string::npos) << voxcd_dpi_error(nullptr);
  EXPECT_EQ(voxcd_dpi_new("MEMW 48"), nullptr);
  EXPECT_NE(std::string(voxcd_dpi_error(nullptr)).find("MEMW = 48 is not a power of two"), std::string::npos)
      << voxcd_dpi_error(nullptr);
  EXPECT_EQ(voxcd_dpi_new("LANES"), nullptr);
  EXPECT_NE(std::string(voxcd_dpi_error(nullptr)).find("voxcd_dpi_new(\"LANES\")"), std::string::npos)
      << voxcd_dpi_error(nullptr);
}

TEST(DpiApi, ConfigurationAndParameters) {
  Handle d("TAGW 8 LANES 2");
  EXPECT_STREQ(voxcd_dpi_config(d.h), "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 2 SAW 16 MAW 18 TAGW 8");
  EXPECT_EQ(voxcd_dpi_param(d.h, "LANES"), 2);
  EXPECT_EQ(voxcd_dpi_param(d.h, "TAGW"), 8);
  EXPECT_EQ(voxcd_dpi_param(d.h, "PW"), 24);
  EXPECT_EQ(voxcd_dpi_param(d.h, "pw"), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h),
               "voxcd_dpi_param: no parameter named 'pw' (PW, PF, MW, MF, TW, DW, MEMW, LANES, SAW, MAW, TAGW, SB, WB, "
               "BANKS, DEPTH, BL, IW)");
  EXPECT_EQ(voxcd_dpi_param(d.h, "SB"), 2);
  EXPECT_EQ(voxcd_dpi_param(d.h, "DEPTH"), 0);
  Handle deep("LANES 4 DEPTH 3 BANKS 2");
  EXPECT_EQ(voxcd_dpi_param(deep.h, "DEPTH"), 3);
  EXPECT_EQ(voxcd_dpi_param(deep.h, "BANKS"), 2);
  EXPECT_STREQ(voxcd_dpi_config(deep.h),
               "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 16 MAW 18 TAGW 16 BANKS 2 DEPTH 3");
  EXPECT_EQ(voxcd_dpi_param(d.h, "WB"), 8);
  Handle dist("SB 8 WB 6 LANES 1");
  EXPECT_STREQ(voxcd_dpi_config(dist.h),
               "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 1 SAW 16 MAW 18 TAGW 16 SB 8 WB 6");
  EXPECT_EQ(voxcd_dpi_param(dist.h, "SB"), 8);
  EXPECT_EQ(voxcd_dpi_param(dist.h, "WB"), 6);
  EXPECT_EQ(voxcd_dpi_param(dist.h, "IW"), 26);
  Handle def("");
  EXPECT_STREQ(voxcd_dpi_config(def.h), DeviceConfig{}.to_string().c_str());
  EXPECT_STREQ(voxcd_dpi_error(def.h), "") << "no call on it failed";
}

TEST(DpiApi, NullHandleFailsWithAMessage) {
  EXPECT_EQ(voxcd_dpi_pop(nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                          nullptr),
            -1);
  EXPECT_STREQ(voxcd_dpi_error(nullptr),
               "voxcd_dpi_pop: the handle is null (voxcd_dpi_new failed or was not called)");
  EXPECT_EQ(voxcd_dpi_write_map(nullptr, 0, 0), -1);
  EXPECT_STREQ(voxcd_dpi_error(nullptr),
               "voxcd_dpi_write_map: the handle is null (voxcd_dpi_new failed or was not called)");
  EXPECT_STREQ(voxcd_dpi_config(nullptr), "");
  voxcd_dpi_free(nullptr);
}

TEST(DpiApi, WritesOutsideTheirFormatAreRefused) {
  Handle d("MEMW 32 SAW 4 PW 12 PF 4");
  EXPECT_EQ(voxcd_dpi_write_shell(d.h, 16, 0, 0, 0), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_write_shell: shell address 16 is outside 0..15 (2^SAW words)");
  EXPECT_EQ(voxcd_dpi_write_shell(d.h, -1, 0, 0, 0), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_write_shell: shell address -1 is outside 0..15 (2^SAW words)");
  EXPECT_EQ(voxcd_dpi_write_shell(d.h, 3, 0, 2048, 0), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_write_shell: shell word 3: y = 2048 does not fit PW = 12 bits (signed)");
  EXPECT_EQ(voxcd_dpi_write_shell(d.h, 3, -2048, 2047, 0), 0) << "the extremes of PW = 12 fit";
  EXPECT_EQ(voxcd_dpi_write_map(d.h, 0, 1LL << 32), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_write_map: voxmap word 0 = 4294967296 has bits above MEMW = 32");
  EXPECT_EQ(voxcd_dpi_write_map(d.h, 0, 0xffffffffLL), 0);
  EXPECT_EQ(voxcd_dpi_write_map(d.h, 1 << 18, 0), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_write_map: voxmap address 262144 is outside 0..262143 (2^MAW words)");
  Handle w("");  // MEMW 64: every bit pattern is a word
  EXPECT_EQ(voxcd_dpi_write_map(w.h, 0, -1), 0);
}

// A job may read only words written through the write functions; each refusal names the job and the word.
TEST(DpiApi, JobsReadingUnwrittenOrInvalidAreRefused) {
  Handle d("");
  for (int k = 9; k >= 0; --k) ASSERT_EQ(voxcd_dpi_write_shell(d.h, k, k << 8, 0, 0), 0);  // any order
  for (int k : {0, 1, 2, 4}) ASSERT_EQ(voxcd_dpi_write_map(d.h, k, -1), 0);  // word 3 is never written
  Job j;
  j.tag = 7;
  j.shell_base = 2;
  j.shell_count = 9;
  j.nx = 64;  // 64 voxels: words 0 and 1
  j.M[0][0] = j.M[1][1] = j.M[2][2] = 1 << 16;
  EXPECT_EQ(submit(d.h, j), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h),
               "voxcd_dpi_submit: job tag 7 reads shell words [2, 11), and word 10 was never written "
               "(voxcd_dpi_write_shell)");
  j.shell_count = 8;
  j.map_base = 1;
  j.nx = 96;  // words 1, 2, 3
  EXPECT_EQ(submit(d.h, j), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h),
               "voxcd_dpi_submit: job tag 7 reads voxmap words [1, 4), and word 3 was never written "
               "(voxcd_dpi_write_map)");
  EXPECT_EQ(voxcd_dpi_pending(d.h), 0) << "a refused job adds no records";
  ASSERT_EQ(voxcd_dpi_write_map(d.h, 3, 0), 0);  // words 0..4 are all written now
  j.nx = 128;  // words 1..4
  EXPECT_EQ(submit(d.h, j), 1) << voxcd_dpi_error(d.h);  // x = 2..9 fall in word 1, all reserved; mask 6: no hit
  EXPECT_EQ(pop_all(d.h).size(), 1u);
  j.nx = 64;  // words 1, 2
  j.hit_mask = 8;  // the map is all state 3 (reserved); points 2..9 land on x = 2..9: eight hits
  EXPECT_EQ(submit(d.h, j), 9) << voxcd_dpi_error(d.h);
  j.mode = Mode(3);
  EXPECT_EQ(submit(d.h, j), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_submit: job tag 7: mode 3 is not 0 (ALL), 1 (FIRST) or 2 (COUNT)");
  j.mode = Mode::All;
  j.M[0][1] = 1 << 17;  // MW = 18 signed: 2^17 does not fit
  EXPECT_EQ(submit(d.h, j), -1);
  const std::string e = voxcd_dpi_error(d.h);
  EXPECT_EQ(e.rfind("voxcd_dpi_submit: ", 0), 0u) << e;
  EXPECT_NE(e.find("7"), std::string::npos) << e;
  EXPECT_NE(e.find("M01"), std::string::npos) << e;
  EXPECT_EQ(voxcd_dpi_jobs(d.h), 2);
}

// A distance device: the job's threshold decides the hit, the record carries D; a 2-bit device refuses a threshold;
// the words a distance map reads (8 parity banks) must all be written.
TEST(DpiApi, DistanceJobsTakeAThresholdAndGiveTheirDistance) {
  Handle d("SB 8 WB 8 LANES 1");
  ASSERT_EQ(voxcd_dpi_write_shell(d.h, 0, 128, 128, 128), 0);  // (0.5, 0.5, 0.5): every weight 2^7
  // A 1x1x1 map: its 8 nodes are slot 0 of words 0..7 (one per bank); node c holds c - 3.
  for (int c = 0; c < 7; ++c) ASSERT_EQ(voxcd_dpi_write_map(d.h, c, (c - 3) & 0xff), 0);
  Job j;
  j.tag = 5;
  j.shell_count = 1;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = 1 << 16;
  const int64_t D = int64_t{4} << 21;  // the values sum to 4, each weighted 2^21
  j.threshold = D;
  EXPECT_EQ(submit(d.h, j), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h),
               "voxcd_dpi_submit: job tag 5 reads voxmap words [0, 8), and word 7 was never written "
               "(voxcd_dpi_write_map)");
  ASSERT_EQ(voxcd_dpi_write_map(d.h, 7, 4), 0);
  EXPECT_EQ(submit(d.h, j), 2) << voxcd_dpi_error(d.h);
  std::vector<Record> got = pop_all(d.h);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].to_string(true), "hit 5 0 0 0 0 0 " + std::to_string(D));
  j.threshold = D - 1;  // one unit below D: no hit
  EXPECT_EQ(submit(d.h, j), 1) << voxcd_dpi_error(d.h);
  got = pop_all(d.h);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].hits, 0u);
  j.threshold = int64_t{1} << 31;  // IW = 32 bits signed
  EXPECT_EQ(submit(d.h, j), -1);
  EXPECT_NE(std::string(voxcd_dpi_error(d.h)).find("threshold 2147483648 does not fit IW"), std::string::npos)
      << voxcd_dpi_error(d.h);

  Handle two("");
  ASSERT_EQ(voxcd_dpi_write_shell(two.h, 0, 0, 0, 0), 0);
  ASSERT_EQ(voxcd_dpi_write_map(two.h, 0, 0), 0);
  j.threshold = 5;
  EXPECT_EQ(submit(two.h, j), -1);
  EXPECT_NE(std::string(voxcd_dpi_error(two.h)).find("threshold 5 on a 2-bit voxmap"), std::string::npos)
      << voxcd_dpi_error(two.h);
}

int submit_sparse(void* h, const Job& j) {
  return voxcd_dpi_submit_sparse(h, int(j.tag), int(j.mode), j.hit_mask, int(j.shell_base), int(j.shell_count),
                                 int(j.map_base), int(j.nx), int(j.ny), int(j.nz), j.M[0][0], j.M[0][1], j.M[0][2],
                                 j.M[1][0], j.M[1][1], j.M[1][2], j.M[2][0], j.M[2][1], j.M[2][2], j.t[0], j.t[1],
                                 j.t[2], j.threshold, j.sparse, int(j.brick_base), int(j.brick_units));
}

// A sparse device (BL 3): generated version-3 jobs (sparse maps and shells among dense ones), their sparse fields read
// back with voxcd_dpi_gen_job_sparse and submitted with voxcd_dpi_submit_sparse, give ref/'s stream with the cycles
// of annotate_cycles over the memory (a sparse shell's slots follow its words; shared banks count conflicts).
TEST(DpiApi, SparseJobsStreamAndCyclesEqualRef) {
  for (const char* cfg_text : {"BL 3", "BL 3 SB 8 WB 8 BANKS 2", "BL 3 LANES 2 DEPTH 3"}) {
    Handle d(cfg_text);
    ASSERT_EQ(voxcd_dpi_param(d.h, "BL"), 3);
    ASSERT_EQ(voxcd_dpi_generate(d.h, 31, 200, 400), 0) << voxcd_dpi_error(d.h);
    GenerateOptions g;
    g.seed = 31, g.jobs = 200, g.cloud_points = 400;
    g.config = parse_config_pairs(cfg_text, "test");
    const GeneratedVectors v = generate_vectors(g);
    write_memory(d.h, v.memory);
    size_t sparse = 0;
    for (size_t k = 0; k < v.jobs.size(); ++k) {
      int s = -1, base = -1, units = -1;
      ASSERT_EQ(voxcd_dpi_gen_job_sparse(d.h, int(k), &s, &base, &units), 0) << voxcd_dpi_error(d.h);
      ASSERT_EQ(s, v.jobs[k].sparse) << k;
      ASSERT_EQ(uint32_t(base), v.jobs[k].brick_base) << k;
      ASSERT_EQ(uint32_t(units), v.jobs[k].brick_units) << k;
      sparse += s != 0;
      ASSERT_GT(submit_sparse(d.h, v.jobs[k]), 0) << voxcd_dpi_error(d.h);
    }
    EXPECT_GT(sparse, 40u) << cfg_text;
    std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    annotate_cycles(v.config, v.memory, v.jobs, want);
    expect_same_stream(want, pop_all(d.h), cfg_text);
  }
}

// A sparse job reads its brick words too; a sparse job on a dense device, and sparse bits outside 0..3, are refused.
TEST(DpiApi, SparseJobsReadingUnwrittenBricksOrOnADenseDeviceAreRefused) {
  Handle d("BL 3");
  ASSERT_EQ(voxcd_dpi_write_shell(d.h, 0, 256, 256, 256), 0);
  // A 16 x 8 x 8 map: two cells, the first uniform surface, the second a brick (unit 0: words 2..17 of 16).
  ASSERT_EQ(voxcd_dpi_write_map(d.h, 0, (1ll << 32) | 1 | 3 << 2), 0);  // rank 1: the brick is unit 1, words 17..32
  Job j;
  j.tag = 4;
  j.sparse = kSparseMap;
  j.shell_count = 1;
  j.nx = 16, j.ny = 8, j.nz = 8;
  j.brick_base = 1;
  j.brick_units = 2;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = 1 << 16;
  EXPECT_EQ(submit_sparse(d.h, j), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h),
               "voxcd_dpi_submit_sparse: job tag 4 reads brick words [1, 33), and word 1 was never written "
               "(voxcd_dpi_write_map)");
  for (int k = 1; k < 33; ++k) ASSERT_EQ(voxcd_dpi_write_map(d.h, k, 0), 0);
  EXPECT_EQ(submit_sparse(d.h, j), 2) << voxcd_dpi_error(d.h);  // (1, 1, 1) in the uniform surface cell: a hit
  const std::vector<Record> got = pop_all(d.h);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].to_string(), "hit 4 0 1 1 1 1");
  j.sparse = 4;
  EXPECT_EQ(submit_sparse(d.h, j), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_submit_sparse: job tag 4: sparse 4 is outside 0..3 (1: the map, 2: the shell)");
  Handle dense("");
  ASSERT_EQ(voxcd_dpi_write_shell(dense.h, 0, 0, 0, 0), 0);
  ASSERT_EQ(voxcd_dpi_write_map(dense.h, 0, 0), 0);
  j.sparse = kSparseShell;
  j.brick_base = j.brick_units = 0;
  EXPECT_EQ(submit_sparse(dense.h, j), -1);
  EXPECT_NE(std::string(voxcd_dpi_error(dense.h)).find("a sparse shell on a device without sparse maps and shells"),
            std::string::npos)
      << voxcd_dpi_error(dense.h);
  EXPECT_EQ(voxcd_dpi_param(dense.h, "BL"), 0);
}

TEST(DpiApi, PopOnAnEmptyQueueReturnsNone) {
  Handle d("");
  Record r;
  EXPECT_EQ(pop(d.h, r), VOXCD_DPI_NONE);
  EXPECT_EQ(voxcd_dpi_pending(d.h), 0);
  EXPECT_EQ(voxcd_dpi_gen_jobs(d.h), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_gen_jobs: nothing generated yet (call voxcd_dpi_generate first)");
  EXPECT_EQ(voxcd_dpi_generate(d.h, 1, -3, 10), -1);
  EXPECT_STREQ(voxcd_dpi_error(d.h), "voxcd_dpi_generate: jobs = -3 is negative");
}

}  // namespace
