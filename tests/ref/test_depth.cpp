// The pipeline depth (DeviceConfig::depth, docs/hardware.md "Pipeline depth") in the reference: the configuration's
// range, text and comparisons, the timing model worked by hand at several depths, DEPTH in vector files (a file
// without it keeps its meaning), and the rules a job breaks (job_faults) against validate_job on random jobs.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <stdexcept>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

Job job(uint32_t tag, Mode mode, uint32_t count) {
  Job j;
  j.tag = tag;
  j.mode = mode;
  j.shell_count = count;
  return j;
}

TEST(Depth, ConfigurationRangeTextAndComparisons) {
  DeviceConfig c;
  EXPECT_EQ(c.depth, 0);
  EXPECT_EQ(c.to_string().find("DEPTH"), std::string::npos) << "depth 0 keeps the paper device's text";
  for (int d = 0; d <= kMaxDepth; ++d) {
    c.depth = d;
    EXPECT_NO_THROW(c.validate()) << d;
  }
  c.depth = 3;
  EXPECT_NE(c.to_string().find(" DEPTH 3"), std::string::npos);
  DeviceConfig shallow;
  EXPECT_TRUE(c.same_widths(shallow)) << "depth changes timing, never results";
  EXPECT_FALSE(c == shallow) << "but it is part of the device";
  for (int bad : {-1, kMaxDepth + 1, 100}) {
    c.depth = bad;
    try {
      c.validate();
      ADD_FAILURE() << "depth " << bad << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("DEPTH = " + std::to_string(bad) + " is outside 0.." +
                                           std::to_string(kMaxDepth)),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Depth, EachUnitIsOneSlotRegister) {
  DeviceConfig c, dist;
  dist.SB = 8;
  for (int d = 0; d <= kMaxDepth; ++d) {
    c.depth = dist.depth = d;
    EXPECT_EQ(pipeline_slots(c), kPipelineSlots + d);
    EXPECT_EQ(pipeline_slots(dist), kPipelineSlots + kDistanceSlots + d);
  }
}

// The hand-worked stream of test_timing.cpp at every depth: only the first job's latency moves, by one cycle per
// unit of depth; and FIRST's squash window, worked out for depth 2 (8 slot registers).
TEST(Depth, TimingModelByHand) {
  const std::vector<Job> jobs = {job(0, Mode::All, 0), job(1, Mode::All, 0), job(2, Mode::All, 8),
                                 job(3, Mode::All, 4), job(4, Mode::Count, 9)};
  const std::vector<Record> recs = {Record::done(0, 0), Record::done(1, 0), Record::done(2, 0),
                                    Record::hit(3, 0, 0, 0, 0, 1), Record::hit(3, 1, 0, 0, 0, 1),
                                    Record::hit(3, 3, 0, 0, 0, 1), Record::done(3, 3), Record::done(4, 5)};
  DeviceConfig cfg;
  for (int d = 0; d <= kMaxDepth; ++d) {
    cfg.depth = d;
    const std::vector<JobTiming> t = job_timing(cfg, jobs, recs);
    const uint64_t cycles[] = {uint64_t(7 + d), 1, 2, 4, 3};
    for (size_t j = 0; j < jobs.size(); ++j) EXPECT_EQ(t[j].cycles, cycles[j]) << "depth " << d << " job " << j;
  }
  // LANES 1, depth 2: 20 points, first hit at point 2: slots 0, 1 (a cycle each), slot 2 with the hit and the
  // completion (2), then the 7 slots issued behind it (3..9) squashed and one empty slot before the next job.
  cfg = DeviceConfig{};
  cfg.LANES = 1;
  cfg.depth = 2;
  const std::vector<Job> first = {job(0, Mode::First, 20), job(1, Mode::All, 0)};
  const std::vector<Record> r = {Record::hit(0, 2, 0, 0, 0, 2), Record::done(0, 1), Record::done(1, 0)};
  const std::vector<JobTiming> t = job_timing(cfg, first, r);
  EXPECT_EQ(t[0].cycles, 9u + 2 + 1);
  EXPECT_EQ(t[0].slots, 3u + 7 + 1);
  EXPECT_EQ(t[1].cycles, 1u + 7 + 1);
  // A hit closer to the end than the window: the job's remaining slots only, no empty slot.
  const std::vector<Job> near_end = {job(0, Mode::First, 9), job(1, Mode::All, 0)};
  const std::vector<JobTiming> t2 = job_timing(cfg, near_end, r);
  EXPECT_EQ(t2[0].slots, 3u + 6);
  EXPECT_EQ(t2[1].cycles, 1u + 6);
}

TEST(Depth, VectorFilesCarryDepthAndFilesWithoutItKeepTheirMeaning) {
  const VectorFile plain = parse_vectors("voxcd-vectors 1\nconfig LANES 2\n", "plain.vec");
  EXPECT_EQ(plain.config.depth, 0);
  EXPECT_FALSE(plain.has_depth);
  const VectorFile deep = parse_vectors("voxcd-vectors 1\nconfig LANES 2 DEPTH 4\n", "deep.vec");
  EXPECT_EQ(deep.config.depth, 4);
  EXPECT_TRUE(deep.has_depth);
  EXPECT_EQ(parse_vectors("voxcd-vectors 2\nconfig SB 8 DEPTH 5\n", "d.vec").config.depth, 5);
  EXPECT_EQ(parse_config_pairs("LANES 4 DEPTH 2", "--config").depth, 2);
  try {
    parse_vectors("voxcd-vectors 1\nconfig DEPTH " + std::to_string(kMaxDepth + 1) + "\n", "bad.vec");
    ADD_FAILURE() << "a depth past the deepest was accepted";
  } catch (const VectorError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.vec:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("DEPTH = 6 is outside 0..5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_vectors("voxcd-vectors 1\nconfig DEPTH 1 DEPTH 2\n", "twice.vec"), VectorError);

  // Written only when not 0 (a depth-0 file is byte for byte what it was); read back with the cycles of its depth.
  GenerateOptions g;
  g.seed = 3;
  g.jobs = 40;
  g.config.LANES = 2;
  for (int d : {0, 3}) {
    g.config.depth = d;
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> recs = run_stream(v.config, v.memory, v.jobs);
    annotate_cycles(v.config, v.jobs, recs);
    std::ostringstream os;
    write_vectors(os, v.config, true, v.memory, v.jobs, recs);
    EXPECT_EQ(os.str().find("DEPTH") != std::string::npos, d != 0) << os.str().substr(0, 200);
    const VectorFile back = parse_vectors(os.str(), "back.vec");
    EXPECT_EQ(back.config, v.config);
    EXPECT_EQ(compare_streams(back, recs, true), "");
  }
}

// Every rule of validate_job, one at a time, gives its own fault bit; a valid job none.
TEST(Depth, JobFaultsNameTheRuleBroken) {
  DeviceConfig cfg;
  Job ok;
  ok.tag = 5;
  ok.shell_base = 2;
  ok.shell_count = 6;
  ok.nx = 8;
  ok.ny = 8;
  ok.nz = 2;  // 128 voxels: 4 words of 32 states
  ok.map_base = 10;
  const uint64_t shell_words = 8, map_words = 14;
  EXPECT_EQ(job_faults(cfg, ok, shell_words, map_words), 0u);
  struct Bad {
    const char* what;
    uint32_t fault;
    void (*make)(Job&);
  };
  const Bad bad[] = {
      {"mode 3", kFaultMode, [](Job& j) { j.mode = Mode(3); }},
      {"mask 16", kFaultMode, [](Job& j) { j.hit_mask = 16; }},
      {"tag 2^16", kFaultTag, [](Job& j) { j.tag = 1u << 16; }},
      {"shell past the loaded words", kFaultShell, [](Job& j) { j.shell_count = 7; }},
      {"shell base past SAW", kFaultShell, [](Job& j) { j.shell_base = 1u << 16, j.shell_count = 0; }},
      {"nx 0", kFaultDims, [](Job& j) { j.nx = 0; }},
      {"nz 2^DW + 1", kFaultDims, [](Job& j) { j.nz = 1025; }},
      {"map past the loaded words", kFaultMap, [](Job& j) { j.nz = 3; }},
      {"map base past MAW", kFaultMap, [](Job& j) { j.map_base = 1u << 18; }},
      {"M00 2^17", kFaultPose, [](Job& j) { j.M[0][0] = 1 << 17; }},
      {"t2 -2^47 - 1", kFaultPose, [](Job& j) { j.t[2] = -(int64_t{1} << 47) - 1; }},
      {"threshold on a 2-bit device", kFaultThreshold, [](Job& j) { j.threshold = 1; }},
  };
  for (const Bad& b : bad) {
    Job j = ok;
    b.make(j);
    EXPECT_EQ(job_faults(cfg, j, shell_words, map_words), b.fault) << b.what;
    EXPECT_THROW(validate_job(cfg, j, shell_words, map_words), JobError) << b.what;
  }
  // Invalid dimensions leave the map range unjudged; two rules broken give two bits.
  Job two = ok;
  two.nx = 0;
  two.tag = 1u << 20;
  EXPECT_EQ(job_faults(cfg, two, shell_words, map_words), uint32_t(kFaultDims | kFaultTag));
  // A distance map: its base on a bank boundary, its threshold within IW bits.
  DeviceConfig dist;
  dist.SB = 8;
  Job d = ok;
  d.map_base = 8;
  d.nx = d.ny = d.nz = 2;  // 2x2x2 half-grid, 8 nodes: one word per bank, 8 words
  EXPECT_EQ(job_faults(dist, d, shell_words, 16), 0u);
  d.map_base = 4;
  EXPECT_EQ(job_faults(dist, d, shell_words, 16), uint32_t(kFaultMap));
  d.map_base = 8;
  d.threshold = int64_t{1} << 40;
  EXPECT_EQ(job_faults(dist, d, shell_words, 16), uint32_t(kFaultThreshold));
}

// The voxmap words of a job's map when its dimensions are valid (0 otherwise).
uint64_t map_words_of(const DeviceConfig& cfg, const Job& j) {
  const bool ok = j.nx >= 1 && j.ny >= 1 && j.nz >= 1 && j.nx <= cfg.max_dim() && j.ny <= cfg.max_dim() &&
                  j.nz <= cfg.max_dim();
  return ok ? map_words(cfg, j) : 0;
}

// On random jobs near every boundary, job_faults is 0 exactly when validate_job accepts the job.
TEST(Depth, JobFaultsAgreeWithValidateJob) {
  std::mt19937_64 rng(test::seed(20261126));
  auto pick = [&](int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng); };
  size_t valid = 0, invalid = 0;
  for (int sb : {2, 8}) {
    DeviceConfig cfg;
    cfg.SB = sb;
    cfg.DW = 4;
    cfg.SAW = 6;
    cfg.MAW = 7;
    for (int k = 0; k < 20000; ++k) {
      // Each field past its edge one time in about ten, else on it or inside.
      auto edge = [&](int64_t inside_hi, int64_t past) { return pick(0, 9) ? pick(0, inside_hi) : past; };
      Job j;
      j.tag = uint32_t(edge(0xffff, 0x10000 + pick(0, 5)));
      j.mode = Mode(pick(0, 9) ? pick(0, 2) : 3);
      j.hit_mask = uint8_t(edge(15, 16 + pick(0, 200)));
      const uint64_t loaded_shell = uint64_t(pick(0, 64)), loaded_map = uint64_t(pick(0, 128));
      j.shell_base = uint32_t(edge(int64_t(loaded_shell), 64 + pick(0, 10)));
      j.shell_count = uint32_t(pick(0, 9) && j.shell_base <= loaded_shell
                                   ? pick(0, int64_t(loaded_shell) - j.shell_base + (pick(0, 3) == 0))
                                   : pick(0, 70));
      j.nx = uint32_t(edge(15, pick(0, 1) ? 0 : 17)) + (pick(0, 9) ? 1 : 0);
      j.ny = uint32_t(pick(1, 16));
      j.nz = uint32_t(pick(1, 16));
      const uint64_t words = map_words_of(cfg, j);
      j.map_base = uint32_t(pick(0, 9) && words <= loaded_map ? int64_t(loaded_map - words) - pick(-1, 2) : pick(0, 140));
      if (pick(0, 9) == 0) j.M[pick(0, 2)][pick(0, 2)] = pick(0, 1) ? (int64_t{1} << 17) : -(int64_t{1} << 17) - 1;
      if (pick(0, 9) == 0) j.t[pick(0, 2)] = pick(0, 1) ? (int64_t{1} << 47) : -(int64_t{1} << 47) - 1;
      j.threshold = pick(0, 3) ? 0 : pick(-(int64_t{1} << 40), int64_t{1} << 40);
      bool throws = false;
      try {
        validate_job(cfg, j, loaded_shell, loaded_map);
      } catch (const JobError&) {
        throws = true;
      }
      const uint32_t f = job_faults(cfg, j, loaded_shell, loaded_map);
      ASSERT_EQ(f != 0, throws) << "SB " << sb << " job " << job_line(j, 2) << " shell words " << loaded_shell
                                << " map words " << loaded_map << ": faults " << f;
      (throws ? invalid : valid)++;
    }
  }
  EXPECT_GT(valid, 1000u);
  EXPECT_GT(invalid, 1000u);
}

}  // namespace
}  // namespace voxcd
