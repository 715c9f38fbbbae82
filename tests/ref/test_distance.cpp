// Distance voxmaps in ref/ (docs/contract.md, "Distance voxmaps"): the parity-bank layout, the interpolation
// against the exact rational result on the quantised inputs and against the double model within the documented
// bound, validation of configurations, jobs and vector files, the timing model's deeper pipeline, and the cpu
// backend's integer path against the specification. Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <sstream>

#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261124); }

DeviceConfig distance_config(int sb, int wb) {
  DeviceConfig c;
  c.SB = sb;
  c.WB = wb;
  return c;
}

// floor(a / 2^s) by division, not by shifting.
Acc floor_div(Acc a, int s) {
  const Acc d = Acc(1) << s;
  Acc q = a / d;
  if (a % d != 0 && a < 0) q -= 1;
  return q;
}

TEST(DistanceLayout, EightNodesOfEveryCellFallInEightBanksInsideTheMap) {
  for (int sb : {4, 8, 16}) {
    const DeviceConfig cfg = distance_config(sb, 8);
    for (uint32_t nx : {1u, 2u, 5u, 8u}) {
      for (uint32_t ny : {1u, 3u, 4u}) {
        for (uint32_t nz : {1u, 2u, 7u}) {
          Job j;
          j.map_base = 24;
          j.nx = nx, j.ny = ny, j.nz = nz;
          const uint64_t words = map_words(cfg, j);
          EXPECT_EQ(words % 8, 0u);
          std::set<std::pair<uint64_t, uint32_t>> seen;  // every node has its own slot
          for (uint64_t Z = 0; Z <= nz; ++Z)
            for (uint64_t Y = 0; Y <= ny; ++Y)
              for (uint64_t X = 0; X <= nx; ++X) {
                const NodeAddress a = node_address(cfg, j, X, Y, Z);
                ASSERT_GE(a.word, j.map_base);
                ASSERT_LT(a.word, j.map_base + words) << nx << "x" << ny << "x" << nz << " node " << X << Y << Z;
                ASSERT_LT(a.slot, uint32_t(cfg.nodes_per_word()));
                ASSERT_EQ(a.word & 7, (X & 1) | (Y & 1) << 1 | (Z & 1) << 2);
                ASSERT_TRUE(seen.insert({a.word, a.slot}).second);
              }
          for (uint64_t z = 0; z < nz; ++z)
            for (uint64_t y = 0; y < ny; ++y)
              for (uint64_t x = 0; x < nx; ++x) {
                std::set<uint64_t> banks;
                for (int c = 0; c < 8; ++c) banks.insert(node_address(cfg, j, x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)).word & 7);
                ASSERT_EQ(banks.size(), 8u);
              }
        }
      }
    }
  }
}

struct Stats {
  uint64_t lookups = 0, inside = 0, exact_mismatch = 0, bound_violations = 0, truncation_differs = 0;
  double worst_ratio = 0;
};

// Random maps and poses; every inside lookup's D against (a) the exact sum recomputed from fractions obtained by
// division and nested interpolation in 128 bits, (b) the double model's trilinear interpolant at the exact
// position, within (sum over axes of the cell's largest node difference along the axis) x (2^-WB + the
// fixed-point path's bound).
void run_config(const DeviceConfig& cfg, uint64_t seed, uint64_t n, Stats& st) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Job job;
  job.nx = 9, job.ny = 6, job.nz = 7;
  job.map_base = 16;
  DeviceMemory mem;
  mem.map.assign(job.map_base + map_words(cfg, job), 0);
  const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1;
  const uint64_t vmask = (uint64_t{1} << cfg.SB) - 1;
  std::vector<int64_t> q((job.nx + 1) * (job.ny + 1) * (job.nz + 1));
  auto node = [&](uint64_t X, uint64_t Y, uint64_t Z) -> int64_t& {
    return q[X + (job.nx + 1) * (Y + (job.ny + 1) * Z)];
  };
  for (uint64_t Z = 0; Z <= job.nz; ++Z)
    for (uint64_t Y = 0; Y <= job.ny; ++Y)
      for (uint64_t X = 0; X <= job.nx; ++X) {
        const int64_t v = std::uniform_int_distribution<int64_t>(-qmax - 1, qmax)(rng);
        node(X, Y, Z) = v;
        const NodeAddress a = node_address(cfg, job, X, Y, Z);
        mem.map[a.word] |= (uint64_t(v) & vmask) << (uint64_t(cfg.SB) * a.slot);
      }
  FloatPose pose;
  const double one = std::ldexp(1.0, cfg.WB);
  for (uint64_t k = 0; k < n; ++k) {
    if (k % 64 == 0) {
      const double a = 3.14159 * u(rng), c = std::cos(a), s = std::sin(a);
      const double R[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.M[i][j] = R[i][j] * (0.9 + 0.1 * u(rng));
        pose.t[i] = 3.5 + 3 * u(rng);
      }
      quantize_pose(cfg, pose, job);
    }
    const double p[3] = {3 * u(rng), 3 * u(rng), 3 * u(rng)};
    const ShellWord w = quantize_point(cfg, p, "p");
    double pv[3];
    point_value(cfg, w, pv);
    const Transformed tr = transform(cfg, job, w);
    const Located loc = locate(cfg, job, tr);
    ++st.lookups;
    if (!loc.inside) continue;
    ++st.inside;
    const int64_t d = interpolate(cfg, fetch_nodes(cfg, mem.map, job, loc), fractions(cfg, tr));
    // (a) Fractions by division, nested interpolation in 128 bits, nodes from the test's own array.
    Acc f[3];
    uint64_t cell[3];
    for (int i = 0; i < 3; ++i) {
      Acc exact = Acc(job.t[i]);
      for (int j = 0; j < 3; ++j) exact += Acc(job.M[i][j]) * Acc(w[j]);
      cell[i] = uint64_t(floor_div(exact, cfg.TF()));
      f[i] = floor_div(exact, cfg.TF() - cfg.WB) - Acc(cell[i]) * (Acc(1) << cfg.WB);
    }
    auto qa = [&](int dx, int dy, int dz) { return Acc(node(cell[0] + dx, cell[1] + dy, cell[2] + dz)); };
    const Acc W = Acc(1) << cfg.WB;
    Acc yz[2][2];
    for (int dy = 0; dy < 2; ++dy)
      for (int dz = 0; dz < 2; ++dz) yz[dy][dz] = qa(0, dy, dz) * (W - f[0]) + qa(1, dy, dz) * f[0];
    const Acc z0 = yz[0][0] * (W - f[1]) + yz[1][0] * f[1], z1 = yz[0][1] * (W - f[1]) + yz[1][1] * f[1];
    const Acc exact_d = z0 * (W - f[2]) + z1 * f[2];
    if (exact_d != Acc(d)) ++st.exact_mismatch;
    // (b) The double model at the exact position (the shell word's value), in the same cell.
    double y[3];
    float_transform(pose, pv, y);
    bool same_cell = true;
    double fr[3], bound_pos[3];
    for (int i = 0; i < 3; ++i) {
      same_cell &= std::floor(y[i]) == double(cell[i]);
      fr[i] = y[i] - double(cell[i]);
      bound_pos[i] = 1.0 / one + error_bound(cfg, job, i, pv, true) + 1e-12;
      if (double(f[i]) != std::floor(fr[i] * one)) ++st.truncation_differs;
    }
    if (!same_cell) continue;  // a cell boundary within the fixed-point bound: (a) covers it
    double fi = 0, slope = 0;
    for (int c = 0; c < 8; ++c) {
      double wgt = 1;
      for (int i = 0; i < 3; ++i) wgt *= ((c >> i) & 1) ? fr[i] : 1 - fr[i];
      fi += wgt * double(qa(c & 1, c >> 1 & 1, c >> 2 & 1));
    }
    for (int i = 0; i < 3; ++i) {
      double m = 0;
      for (int c = 0; c < 8; ++c) {
        if ((c >> i) & 1) continue;
        const int o = c | (1 << i);
        m = std::max(m, std::fabs(double(qa(o & 1, o >> 1 & 1, o >> 2 & 1) - qa(c & 1, c >> 1 & 1, c >> 2 & 1))));
      }
      slope += m * bound_pos[i];
    }
    const double dev = double(d) / std::ldexp(1.0, 3 * cfg.WB);
    const double diff = std::fabs(dev - fi);
    if (slope > 0) st.worst_ratio = std::max(st.worst_ratio, diff / slope);
    if (diff > slope + 1e-9 * (1 + std::fabs(fi))) ++st.bound_violations;
  }
}

TEST(DistanceProperty, InterpolationIsExactAndWithinTheBoundOfTheDoubleModel) {
  const uint64_t seed = test_seed();
  std::printf("distance property \n");
  struct Named {
    const char* name;
    DeviceConfig cfg;
  };
  std::vector<Named> cfgs = {{"SB8 WB8", distance_config(8, 8)}, {"SB4 WB3", distance_config(4, 3)},
                             {"SB16 WB16", distance_config(16, 16)}, {"SB8 WB1", distance_config(8, 1)}};
  DeviceConfig coarse = distance_config(8, 4);
  coarse.PW = 14, coarse.PF = 3, coarse.MW = 10, coarse.MF = 8, coarse.TW = 24, coarse.DW = 7, coarse.MEMW = 16;
  cfgs.push_back({"coarse SB8 WB4 MEMW16", coarse});
  for (size_t c = 0; c < cfgs.size(); ++c) {
    Stats st;
    run_config(cfgs[c].cfg, seed + c, 200000, st);
    std::printf("%-22s lookups %llu inside %llu worst |D - I|/bound %.3f\n", cfgs[c].name,
                (unsigned long long)st.lookups, (unsigned long long)st.inside, st.worst_ratio);
    EXPECT_GT(st.inside, st.lookups / 4) << cfgs[c].name << ": most lookups must land inside";
    EXPECT_EQ(st.exact_mismatch, 0u) << cfgs[c].name;
    EXPECT_EQ(st.bound_violations, 0u) << cfgs[c].name;
    // The bound is not vacuous: the interpolant really moves by a good part of it.
    EXPECT_GT(st.worst_ratio, 0.2) << cfgs[c].name;
  }
}

TEST(DistanceConfig, ValidationNamesTheParameter) {
  auto fails = [](DeviceConfig c, const std::string& what) {
    try {
      c.validate();
      ADD_FAILURE() << "accepted " << c.to_string();
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails(distance_config(3, 8), "SB = 3 is not 2, 4, 8 or 16");
  fails(distance_config(8, 0), "WB = 0");
  fails(distance_config(8, 25), "WB = 25 is outside 1..16");
  DeviceConfig narrow = distance_config(16, 8);
  narrow.MEMW = 8;
  fails(narrow, "SB = 16 is wider than a voxmap word");
  DeviceConfig shallow = distance_config(8, 8);
  shallow.MAW = 2;
  fails(shallow, "MAW = 2 leaves no row for the 8 banks");
  DeviceConfig coarse = distance_config(8, 8);
  coarse.PF = 2, coarse.MF = 4, coarse.MW = 6;
  fails(coarse, "WB = 8 is outside 1..6");
  // The 2-bit device's text is the paper device's; a distance device's names SB and WB.
  EXPECT_EQ(DeviceConfig{}.to_string(), "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 16 MAW 18 TAGW 16");
  EXPECT_EQ(distance_config(8, 6).to_string(),
            "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 16 MAW 18 TAGW 16 SB 8 WB 6");
  EXPECT_EQ(distance_config(8, 8).IW(), 32);
  EXPECT_FALSE(distance_config(8, 8).same_widths(DeviceConfig{}));
  EXPECT_FALSE(distance_config(8, 8).same_widths(distance_config(8, 7)));
}

TEST(DistanceJobs, ValidationNamesTheTagAndTheField) {
  const DeviceConfig cfg = distance_config(8, 8);
  Job j;
  j.tag = 5;
  j.nx = j.ny = j.nz = 4;
  j.map_base = 8;
  const uint64_t words = 8 + map_words(cfg, j);
  EXPECT_NO_THROW(validate_job(cfg, j, 0, words));
  auto fails = [&](const Job& job, const DeviceConfig& c, uint64_t loaded, const std::string& what) {
    try {
      validate_job(c, job, 0, loaded);
      ADD_FAILURE() << "accepted a job that should fail with " << what;
    } catch (const JobError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  Job odd = j;
  odd.map_base = 12;
  fails(odd, cfg, 12 + map_words(cfg, j), "job tag 5: map_base 12 of a distance voxmap is not on a bank boundary");
  fails(j, cfg, words - 1, "distance map go past the " + std::to_string(words - 1) + " loaded voxmap words");
  Job wide = j;
  wide.threshold = int64_t{1} << 31;
  fails(wide, cfg, words, "threshold 2147483648 does not fit IW = SB + 3*WB = 32 bits");
  wide.threshold = -(int64_t{1} << 31);
  EXPECT_NO_THROW(validate_job(cfg, wide, 0, words));
  Job two_bit = j;
  two_bit.threshold = 1;
  fails(two_bit, DeviceConfig{}, 1000, "threshold 1 on a 2-bit voxmap (SB = 2): it must be 0");
}

TEST(DistanceVectors, Version2RoundTripsAndVersion1StaysAsItWas) {
  GenerateOptions g;
  g.seed = test_seed();
  g.jobs = 120;
  g.config = distance_config(8, 8);
  const GeneratedVectors v = generate_vectors(g);
  std::vector<Record> recs = run_stream(v.config, v.memory, v.jobs);
  annotate_cycles(v.config, v.jobs, recs);
  std::ostringstream out;
  write_vectors(out, v.config, true, v.memory, v.jobs, recs);
  const std::string text = out.str();
  ASSERT_EQ(text.rfind("voxcd-vectors 2\nconfig PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SB 8 WB 8\n", 0), 0u);
  const VectorFile f = parse_vectors(text, "d.vec");
  EXPECT_EQ(f.version, 2);
  EXPECT_TRUE(f.config == v.config);
  ASSERT_EQ(f.jobs.size(), v.jobs.size());
  bool nonzero_threshold = false, nonzero_dist = false;
  for (size_t k = 0; k < f.jobs.size(); ++k) {
    EXPECT_EQ(f.jobs[k].threshold, v.jobs[k].threshold);
    nonzero_threshold |= f.jobs[k].threshold != 0;
  }
  ASSERT_EQ(f.expected.size(), recs.size());
  for (size_t k = 0; k < recs.size(); ++k) {
    EXPECT_TRUE(f.expected[k].same_as(recs[k], true)) << k;
    nonzero_dist |= recs[k].dist != 0;
  }
  EXPECT_TRUE(nonzero_threshold && nonzero_dist);
  EXPECT_EQ(compare_streams(f, recs, true), "");
  // A different distance is a difference, named with the DIST field.
  std::vector<Record> bad = recs;
  for (Record& r : bad)
    if (r.kind == Record::Hit) {
      r.dist += 1;
      break;
    }
  EXPECT_NE(compare_streams(f, bad, false).find("expected 'hit "), std::string::npos);

  // A 2-bit configuration is still written as version 1 (byte for byte what it was).
  g.config = DeviceConfig{};
  const GeneratedVectors v1 = generate_vectors(g);
  std::vector<Record> r1 = run_stream(v1.config, v1.memory, v1.jobs);
  std::ostringstream o1;
  write_vectors(o1, v1.config, false, v1.memory, v1.jobs, r1);
  EXPECT_EQ(o1.str().rfind("voxcd-vectors 1\n", 0), 0u);
  EXPECT_EQ(parse_vectors(o1.str(), "s.vec").version, 1);

  auto fails = [](const std::string& t, const std::string& what) {
    try {
      parse_vectors(t, "x.vec");
      ADD_FAILURE() << "accepted:\n" << t;
    } catch (const VectorError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails("voxcd-vectors 1\nconfig SB 8\n", "x.vec:2: config parameter SB needs format version 2");
  fails("voxcd-vectors 4\n", "x.vec:1: unsupported vector format version '4' (this reads 1, 2 and 3)");
  fails("voxcd-vectors 2\nconfig SB 8\njob 0 ALL 6 0 0 0 1 1 1 65536 0 0 0 65536 0 0 0 65536 0 0 0\n",
        "x.vec:3: 'job' takes 22 fields, found 21");
  fails("voxcd-vectors 2\nconfig SB 8\nhit 0 0 0 0 0 0\n", "x.vec:3: 'hit' takes 7 fields, found 6");
  fails("voxcd-vectors 2\nconfig SB 8 WB 8\nhit 0 0 0 0 0 0 4294967296\n", "DIST 4294967296 does not fit IW = 32 bits");
}

TEST(DistanceTiming, ThreeMoreSlotsBeforeTheHitTest) {
  const DeviceConfig two;
  const DeviceConfig dist = distance_config(8, 8);
  EXPECT_EQ(pipeline_slots(two), kPipelineSlots);
  EXPECT_EQ(pipeline_slots(dist), kPipelineSlots + kDistanceSlots);
  Job j;
  j.tag = 1;
  j.shell_count = 1;
  // A one-point job: its slot reaches the hit test 1 + 9 cycles after acceptance on a distance device.
  const std::vector<Record> recs = {Record::hit(1, 0, 0, 0, 0, 0, -5), Record::done(1, 1)};
  EXPECT_EQ(job_timing(two, {j}, recs)[0].cycles, uint64_t(1 + kPipelineSlots + 1));
  EXPECT_EQ(job_timing(dist, {j}, recs)[0].cycles, uint64_t(1 + kPipelineSlots + kDistanceSlots + 1));
  // FIRST squashes PipeSlots - 1 = 8 slots behind its hit and leaves one empty slot when more remain.
  Job first;
  first.tag = 2;
  first.mode = Mode::First;
  first.shell_count = 4 * 20;  // 20 slots at 4 lanes
  const std::vector<Record> frec = {Record::hit(2, 4, 0, 0, 0, 0, 0), Record::done(2, 1)};
  const JobTiming t = job_timing(dist, {first}, frec)[0];
  EXPECT_EQ(t.slots, 1u + 1u + 8u + 1u);  // the slot before the hit, the hit's, 8 squashed, the empty slot
}

TEST(DistanceFast, CpuBackendMatchesTheSpecificationOnEveryPath) {
  const uint64_t seed = test_seed();
  std::printf("distance kernel: %s, 2-bit kernel: %s\n", FastRunner::distance_kernel(), FastRunner::double_kernel());
  struct Named {
    const char* name;
    DeviceConfig cfg;
  };
  std::vector<Named> cfgs = {{"SB8", distance_config(8, 8)}, {"SB4 WB2", distance_config(4, 2)},
                             {"SB16 WB16", distance_config(16, 16)}, {"SB16 WB8 (vector path)", distance_config(16, 8)}};
  DeviceConfig wide = distance_config(16, 12);
  wide.PW = 32, wide.PF = 16, wide.MW = 26, wide.MF = 24, wide.TW = 64, wide.MEMW = 32, wide.LANES = 2;
  cfgs.push_back({"wide path SB16 WB12", wide});
  DeviceConfig i64 = distance_config(8, 8);
  i64.PW = 28, i64.PF = 10, i64.MW = 24, i64.MF = 20, i64.TW = 56, i64.LANES = 8;
  cfgs.push_back({"int64 path", i64});
  for (const Named& n : cfgs) {
    GenerateOptions g;
    g.seed = seed;
    g.jobs = 300;
    g.config = n.cfg;
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
    annotate_cycles(v.config, v.jobs, want);
    size_t hits = 0;
    for (const Record& r : want) hits += r.kind == Record::Hit;
    EXPECT_GT(hits, 100u) << n.name;
    for (unsigned threads : {1u, 3u}) {
      FastRunner fr(v.config, threads);
      fr.load(v.memory);
      const std::vector<Record> got = fr.run(v.jobs);
      ASSERT_EQ(got.size(), want.size()) << n.name;
      for (size_t i = 0; i < want.size(); ++i)
        ASSERT_TRUE(got[i].same_as(want[i], true))
            << n.name << " threads " << threads << " record " << i << ": expected '" << want[i].to_string(true)
            << "', got '" << got[i].to_string(true) << "'";
    }
  }
}

}  // namespace
}  // namespace voxcd
