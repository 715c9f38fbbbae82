// rtl/voxcd_arch_pkg.sv and the C++ DeviceConfig (ref/config.h) name the same widths with the same defaults, and the
// package's pipeline depth is the timing model's. The package is parsed here, so a change to one side alone fails.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/timing.h"

namespace voxcd {
namespace {

std::map<std::string, long> package_params() {
  std::ifstream f(VOXCD_RTL_DIR "/voxcd_arch_pkg.sv");
  EXPECT_TRUE(f.good()) << VOXCD_RTL_DIR "/voxcd_arch_pkg.sv";
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  std::map<std::string, long> out;
  const std::regex re(R"(localparam\s+(?:int\s+unsigned|logic\s*\[\d+:0\])\s+(\w+)\s*=\s*(?:\d+'b([01]+)|(\d+))\s*;)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    out[m[1]] = m[2].matched ? std::stol(m[2], nullptr, 2) : std::stol(m[3]);
  }
  return out;
}

TEST(RtlPackage, WidthsMatchDeviceConfig) {
  const auto p = package_params();
  const DeviceConfig c;
  const std::pair<const char*, int> want[] = {{"PW", c.PW},   {"PF", c.PF},       {"MW", c.MW},   {"MF", c.MF},
                                              {"TW", c.TW},   {"DW", c.DW},       {"MEMW", c.MEMW},
                                              {"LANES", c.LANES}, {"SAW", c.SAW}, {"MAW", c.MAW}, {"TAGW", c.TAGW},
                                              {"SB", c.SB},   {"WB", c.WB},       {"BL", c.BL},
                                              {"TX", c.TX}};
  for (const auto& [name, value] : want) {
    ASSERT_TRUE(p.count(name)) << "voxcd_arch_pkg.sv has no " << name;
    EXPECT_EQ(p.at(name), value) << name << ": voxcd_arch_pkg.sv and DeviceConfig disagree";
  }
}

TEST(RtlPackage, PipelineMatchesTheModels) {
  const auto p = package_params();
  ASSERT_TRUE(p.count("PipeSlots"));
  EXPECT_EQ(p.at("PipeSlots"), kPipelineSlots);
  ASSERT_TRUE(p.count("DistSlots"));
  EXPECT_EQ(p.at("DistSlots"), kDistanceSlots);
  DeviceConfig dist;
  dist.SB = 8;
  EXPECT_EQ(pipeline_slots(dist), p.at("PipeSlots") + p.at("DistSlots"));
  EXPECT_EQ(pipeline_slots(DeviceConfig{}), p.at("PipeSlots"));
}

// A sparse device's registers (W, E, K; and F on a distance device): the package's counts are the timing model's.
TEST(RtlPackage, SparseSlotsMatchTheModels) {
  const auto p = package_params();
  ASSERT_TRUE(p.count("SparseSlots"));
  ASSERT_TRUE(p.count("SparseDistSlots"));
  EXPECT_EQ(p.at("SparseSlots"), kSparseSlots);
  EXPECT_EQ(p.at("SparseDistSlots"), kSparseDistanceSlots);
  DeviceConfig sparse;
  sparse.BL = 3;
  EXPECT_EQ(pipeline_slots(sparse), p.at("PipeSlots") + p.at("SparseSlots"));
  sparse.SB = 8;
  sparse.depth = kMaxDepth;
  EXPECT_EQ(pipeline_slots(sparse),
            p.at("PipeSlots") + p.at("DistSlots") + p.at("SparseDistSlots") + p.at("MaxDepth"));
}

// The depth: the package's default and deepest are DeviceConfig's, its stages come in the order ref/config.h names
// (each rank once, below the deepest), and each unit is one slot register of the timing model.
TEST(RtlPackage, DepthMatchesDeviceConfig) {
  const auto p = package_params();
  ASSERT_TRUE(p.count("Depth"));
  EXPECT_EQ(p.at("Depth"), DeviceConfig{}.depth);
  ASSERT_TRUE(p.count("MaxDepth"));
  EXPECT_EQ(p.at("MaxDepth"), kMaxDepth);
  const std::pair<const char*, int> ranks[] = {
      {"RankIn", kRankIn}, {"RankAddr", kRankAddr}, {"RankRead", kRankRead}, {"RankSum", kRankSum},
      {"RankFloor", kRankFloor}};
  std::vector<bool> seen(size_t(kMaxDepth), false);
  for (const auto& [name, value] : ranks) {
    ASSERT_TRUE(p.count(name)) << "voxcd_arch_pkg.sv has no " << name;
    EXPECT_EQ(p.at(name), value) << name;
    ASSERT_GE(value, 0);
    ASSERT_LT(value, kMaxDepth) << name;
    EXPECT_FALSE(seen[size_t(value)]) << name << " shares its rank";
    seen[size_t(value)] = true;
  }
  DeviceConfig deep;
  deep.depth = kMaxDepth;
  EXPECT_EQ(pipeline_slots(deep), p.at("PipeSlots") + p.at("MaxDepth"));
}

}  // namespace
}  // namespace voxcd
