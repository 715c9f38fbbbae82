// Coverage of rtl/ (host/regress/coverage.h, stimulus_bins.h): the stimulus bins of hand-made vectors, and the merge,
// the waivers and the report of hand-written coverage data (Verilator's format) through verilator_coverage.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "voxcd/host/regress/coverage.h"
#include "voxcd/host/regress/stimulus_bins.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd {
namespace {

namespace fs = std::filesystem;

// One job over an identity pose on a 4 x 4 x 4 map; its points at x = the given voxel coordinates (fixed point), y
// and z in voxel 0.
VectorFile points_at_x(const std::vector<int64_t>& xs, Mode mode = Mode::All) {
  VectorFile f;
  const DeviceConfig& c = f.config;
  for (int64_t x : xs) f.memory.shell.push_back({x, 1, 1});
  f.memory.map.assign(4 * 4 * 4 / (c.MEMW / 2), 0);
  Job j;
  j.mode = mode;
  j.shell_count = uint32_t(xs.size());
  j.nx = j.ny = j.nz = 4;
  for (int i = 0; i < 3; ++i) j.M[i][i] = int64_t{1} << c.MF;
  f.jobs.push_back(j);
  return f;
}

TEST(StimulusBins, FacesFarPointsAndNegativeFloorsAreCountedFromRefsStages) {
  const DeviceConfig c;
  const int64_t one = int64_t{1} << c.PF;  // one voxel
  const VectorFile f = points_at_x({-one, 0, 3 * one, 4 * one, ((int64_t{1} << c.DW) + 1) * one, -one / 2});
  const std::map<std::string, uint64_t> b = stimulus_bins(f);
  EXPECT_EQ(b.at("face.x.-1"), 2u);  // -1 and the floor of -0.5
  EXPECT_EQ(b.at("face.x.0"), 1u);
  EXPECT_EQ(b.at("face.x.n-1"), 1u);
  EXPECT_EQ(b.at("face.x.n"), 1u);
  EXPECT_EQ(b.at("far.x.wraps"), 1u);  // 2^DW + 1: its low DW bits are 1, inside
  EXPECT_EQ(b.at("floor.x.negative"), 1u);
  EXPECT_EQ(b.at("face.y.0"), 6u);
  EXPECT_EQ(b.at("far.y.wraps"), 0u);
  EXPECT_EQ(b.at("config.lanes.4"), 1u);
  EXPECT_EQ(b.at("config.depth.0"), 1u);
  EXPECT_EQ(b.at("job.map.dense"), 1u);
  EXPECT_EQ(b.count("distance.at"), 0u) << "a 2-bit device has no distance bins";
  EXPECT_EQ(b.at("first.position.3"), 0u) << "every position of the slot is a bin, hit or not";
}

TEST(StimulusBins, FirstHitsCountAtTheirPositionInTheSlot) {
  const DeviceConfig c;
  const int64_t one = int64_t{1} << c.PF;
  VectorFile f = points_at_x({-one, -one, -one, -one, -one, 0}, Mode::First);
  f.memory.map[0] = 1;  // voxel 0 is state 1
  f.jobs[0].hit_mask = 0x2;
  f.expected = {Record::hit(0, 5, 0, 0, 0, 1), Record::done(0, 1)};
  const std::map<std::string, uint64_t> b = stimulus_bins(f);
  EXPECT_EQ(b.at("first.position.1"), 1u) << "point 5 is lane 1 of its slot of 4";
  EXPECT_EQ(b.at("first.position.0"), 0u);
}

// The vectors of a seed as a vector file, with ref/'s expected stream.
VectorFile generated(const DeviceConfig& cfg, uint64_t seed, size_t jobs, const std::vector<std::string>& aim) {
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.config = cfg;
  g.aim = aim;
  const GeneratedVectors v = generate_vectors(g);
  VectorFile f;
  f.config = v.config;
  f.memory = v.memory;
  f.jobs = v.jobs;
  f.expected = run_stream(v.config, v.memory, v.jobs);
  return f;
}

TEST(StimulusBins, AimedVectorsHitTheBinsTheRandomOnesMissOrRarelyHit) {
  DeviceConfig cfg;
  cfg.SB = 8;
  cfg.WB = 8;
  const std::vector<std::string> aim = {"distance.at", "first.position.3", "face.x.n", "far.z.wraps",
                                        "floor.y.negative"};
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const auto plain = stimulus_bins(generated(cfg, seed, 40, {}));
    const auto aimed = stimulus_bins(generated(cfg, seed, 40, aim));
    for (const std::string& b : aim) {
      // 20 of the 40 jobs aim, 4 at each bin: each of those hits it at least once.
      EXPECT_GE(aimed.at(b), 4u) << b << " seed " << seed;
      EXPECT_GE(aimed.at(b), plain.at(b) / 4) << b << " seed " << seed;
    }
  }
  EXPECT_THROW(generated(cfg, 1, 4, {"CoverFullSlot"}), std::invalid_argument) << "an RTL bin has no template";
  EXPECT_TRUE(aimable_bin("first.position.12"));
  EXPECT_FALSE(aimable_bin("first.position."));
  EXPECT_FALSE(aimable_bin("face.w.0"));
}

// A coverage data file of Verilator's format with the given points: {page, file, line, comment, hierarchy, count}.
struct P {
  std::string page, file;
  int line;
  std::string what, hier;
  uint64_t count;
};
void write_dat(const fs::path& path, const std::vector<P>& points) {
  std::ofstream o(path);
  o << "# SystemC::Coverage-3\n";
  for (const P& p : points)
    o << "C '\001f\002" << p.file << "\001l\002" << p.line << "\001n\0023\001page\002" << p.page << "\001o\002"
      << p.what << "\001h\002" << p.hier << "' " << p.count << "\n";
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Coverage, MergesShardsAppliesWaiversAndNamesEmptyBins) {
  const fs::path d = fresh_dir("voxcd_coverage_merge");
  // Two shards: the same line point hit in one, missed in the other (hit after the merge); a branch missed in both
  // and waived; a toggle missed and not waived; two bins of which one is never hit.
  write_dat(d / "a-shard-0.dat", {{"v_line/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 10, "block", "TOP.voxcd.u_q", 0},
                                  {"v_branch/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 12, "if", "TOP.voxcd.u_q", 3},
                                  {"v_branch/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 12, "else", "TOP.voxcd.u_q", 0},
                                  {"v_toggle/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 3, "count_q[1]", "TOP.voxcd.u_q", 0},
                                  {"v_toggle/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 4, "hits_q[5]", "TOP.voxcd.u_q", 0},
                                  {"v_toggle/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 4, "hits_q[9]", "TOP.voxcd.u_q", 0},
                                  {"v_toggle/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 4, "hits_q[10]", "TOP.voxcd.u_q", 0},
                                  {"v_user/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 20, "CoverFull",
                                   "TOP.voxcd.u_q.CoverFull", 0},
                                  {"v_user/voxcd_device", "/x/rtl/voxcd_device.sv", 30, "CoverSquash",
                                   "TOP.voxcd.g_l__BRA__*__KET__.CoverSquash", 0}});
  write_dat(d / "a-shard-1.dat", {{"v_line/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 10, "block", "TOP.voxcd.u_q", 7},
                                  {"v_user/voxcd_fifo", "/x/rtl/voxcd_fifo.sv", 20, "CoverFull",
                                   "TOP.voxcd.u_q.CoverFull", 2}});
  std::ofstream(d / "a-shard-0.bins") << "face.x.0 4\nface.x.n 0\n";
  std::ofstream(d / "a-shard-1.bins") << "face.x.0 1\nface.x.n 0\n";
  const fs::path waivers = d / "w.txt";
  std::ofstream(waivers) << "# test\nbranch voxcd_fifo.sv:11-13  the else of a full queue cannot happen\n"
                            "line voxcd_skid.sv:5  a waiver that matches nothing\n"
                            "toggle voxcd_fifo.sv:hits_q[4-9]  a count of at most 15: bits 4 and up stay 0\n";
  const CoverageReport r = merge_coverage(d.string(), waivers.string());
  EXPECT_EQ(r.data_files, 2u);
  EXPECT_EQ(r.kinds.at("line").hit, 1u);
  EXPECT_EQ(r.kinds.at("line").missed, 0u);
  EXPECT_EQ(r.kinds.at("branch").hit, 1u);
  EXPECT_EQ(r.kinds.at("branch").waived, 1u);
  EXPECT_EQ(r.kinds.at("toggle").missed, 2u);  // count_q[1], and hits_q[10] past the waiver's bit range
  EXPECT_EQ(r.kinds.at("toggle").waived, 2u);  // hits_q[5] and hits_q[9]
  EXPECT_EQ(r.bins.at("u_q.CoverFull"), 2u);
  EXPECT_EQ(r.bins.at("face.x.0"), 5u);
  EXPECT_EQ(r.empty_bins, (std::vector<std::string>{"face.x.n", "g_l[*].CoverSquash"}));
  ASSERT_EQ(r.stale_waivers.size(), 1u);
  EXPECT_NE(r.stale_waivers[0].find("w.txt:3"), std::string::npos) << r.stale_waivers[0];
  for (const char* f : {"merged.dat", "coverage.info", "bins.txt", "summary.txt", "missed.txt", "html/index.html"})
    EXPECT_TRUE(fs::exists(d / f)) << f;
  const std::string text = r.text();
  EXPECT_NE(text.find("functional bins still empty: 2"), std::string::npos) << text;
  EXPECT_EQ(r.missed_points, (std::vector<std::string>{"voxcd_fifo.sv:3 toggle count_q[1]",
                                                       "voxcd_fifo.sv:4 toggle hits_q[10]"}));
}

TEST(Coverage, BadWaiversAndEmptyDirectoriesAreErrorsThatSayWhere) {
  const fs::path d = fresh_dir("voxcd_coverage_bad");
  EXPECT_THROW(
      {
        try {
          merge_coverage(d.string(), "");
        } catch (const CoverageError& e) {
          EXPECT_NE(std::string(e.what()).find("holds no coverage data"), std::string::npos) << e.what();
          throw;
        }
      },
      CoverageError);
  write_dat(d / "s.dat", {{"v_line/voxcd_fifo", "voxcd_fifo.sv", 10, "block", "TOP.voxcd.u_q", 1}});
  const fs::path waivers = d / "w.txt";
  for (const auto& [text, want] : std::vector<std::pair<std::string, std::string>>{
           {"line voxcd_fifo.sv:10\n", "w.txt:1: the waiver of voxcd_fifo.sv:10 gives no reason"},
           {"\nbogus x y\n", "w.txt:2: unknown waiver kind 'bogus'"},
           {"toggle voxcd_fifo.sv:q[9-2] backwards\n", "w.txt:1: voxcd_fifo.sv:q[9-2]: not a bit range"},
           {"line voxcd_fifo.sv:9-3 why\n", "not a line range"},
           {"branch voxcd_fifo.sv why\n", "expected FILE:LINE"}}) {
    std::ofstream(waivers) << text;
    try {
      merge_coverage(d.string(), waivers.string());
      ADD_FAILURE() << "no error for " << text;
    } catch (const CoverageError& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace voxcd
