// The energy table (host/sizing/energy_table.h) and `voxcd size`'s energy (size.h): the built-in table is the source
// tree's host/sizing/energy.tsv; a table that cannot be used is refused naming the file, the line and the column; a
// configuration of the measured logic gets the simulate scene's measured energy per lookup, any other an estimate
// from the nearest row that names it; a frame's energy is its lookups x the energy per lookup, and the power that x
// the requested rate.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/energy_table.h"
#include "voxcd/host/sizing/size.h"

namespace voxcd {
namespace {

const std::string kHeader =
    "target\tdepth\tmhz\tscene\tcycles\tlookups\tjobs\tpairs\tinternal_mw\tswitching_mw\tleakage_mw\tlogic_mw\t"
    "sram_nj\tpj_per_lookup\tlogic_pj\tsram_pj\tnj_per_pair\tleakage_share\tpj_45nm\tpj_16nm\tpj_7nm\tconfig\n";
const std::string kDefaultLogic = "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 12 MAW 12 TAGW 16";

// A row of the table with its energy per lookup `pj` (7 nm: 1.053).
std::string row(const std::string& scene, const std::string& pj, const std::string& config = kDefaultLogic,
                int depth = 0) {
  return "asic-osu018\t" + std::to_string(depth) + "\t100.4\t" + scene +
         "\t50517\t200029\t2496\t1241\t138.4\t28.39\t0.0088\t166.8\t32268.6\t" + pj + "\t419.58\t161.44\t93.65\t0.00025\t" +
         "18.97\t1.946\t1.053\t" + config + "\n";
}

// The message of the EnergyTableError that parsing `text` throws ("" when it parses).
std::string table_error(const std::string& text) {
  try {
    parse_energy_table(text, "e.tsv");
  } catch (const EnergyTableError& e) {
    return e.what();
  }
  return "";
}

TEST(EnergyTable, TheBuiltInTableIsTheSourceTrees) {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/host/sizing/energy.tsv");
  ASSERT_TRUE(in) << "host/sizing/energy.tsv is missing";
  std::stringstream s;
  s << in.rdbuf();
  const EnergyTable source = parse_energy_table(s.str(), "host/sizing/energy.tsv");
  const EnergyTable& t = builtin_energy_table();
  ASSERT_EQ(t.rows.size(), source.rows.size()) << "the build's table is not the source tree's: reconfigure";
  for (size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.rows[i].scene, source.rows[i].scene);
    EXPECT_EQ(t.rows[i].pj_per_lookup, source.rows[i].pj_per_lookup);
    EXPECT_EQ(t.rows[i].config, source.rows[i].config);
  }
  EXPECT_EQ(t.rows.at(0).scene, "simulate");
  EXPECT_DOUBLE_EQ(t.rows.at(0).pj_per_lookup, 581.02);
  EXPECT_DOUBLE_EQ(t.rows.at(0).pj_7nm, 1.053);
}

TEST(EnergyTable, AGoodTableParses) {
  const EnergyTable t = parse_energy_table("# made by hand\n" + kHeader + row("simulate", "500") + row("room", "600") +
                                               row("simulate", "700", kDefaultLogic, 2),
                                           "e.tsv");
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[1].scene, "room");
  EXPECT_EQ(t.rows[1].line, 4);
  EXPECT_DOUBLE_EQ(t.rows[1].pj_per_lookup, 600);
  EXPECT_DOUBLE_EQ(t.rows[1].lookups, 200029);
  EXPECT_EQ(t.rows[2].depth, 2);
  EXPECT_EQ(t.rows[2].device.depth, 2);
  EXPECT_EQ(t.rows[2].device.LANES, 4);
}

TEST(EnergyTable, BadTablesNameTheFileTheLineAndTheColumn) {
  const std::pair<std::string, std::string> cases[] = {
      {"", "e.tsv: no header line"},
      {kHeader, "e.tsv: no rows after the header"},
      {"target\tdepth\n", "e.tsv:1: the header is 'target depth', expected"},
      {kHeader + "asic-osu018\t0\n", "e.tsv:2: 2 tab-separated columns, expected 22"},
      {kHeader + "# x\n" + row("simulate", "-1"), "e.tsv:3: pj_per_lookup: '-1' is not a number >= 0"},
      {kHeader + row("simulate", "0"), "e.tsv:2: pj_per_lookup: '0' is not a positive number"},
      {kHeader + row("simulate", "lots"), "e.tsv:2: pj_per_lookup: 'lots' is not a number >= 0"},
      {kHeader + row("", "500"), "e.tsv:2: scene: '' is empty"},
      {kHeader + row("simulate", "500", "PW 24 XX 3"), "e.tsv:2: config: 'PW 24 XX 3' is not a configuration"},
      {kHeader + row("simulate", "500", "PW 24 DEPTH 3"), "e.tsv:2: config: 'PW 24 DEPTH 3' names DEPTH 3"},
      {kHeader + row("simulate", "500") + row("simulate", "600"), "e.tsv:3: asic-osu018 at depth 0 on the simulate "
                                                                  "scene is given twice"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(table_error(text).rfind(message, 0), 0u) << table_error(text);
  std::string bad_target = kHeader + row("simulate", "500");
  bad_target.replace(kHeader.size(), 11, "asic-xyz018");
  EXPECT_EQ(table_error(bad_target).rfind("e.tsv:2: target: 'asic-xyz018' is not a target", 0), 0u);
  EXPECT_THROW(read_energy_table("/nonexistent/energy.tsv"), EnergyTableError);
}

TEST(EnergyTable, TheDefaultConfigurationsEnergyIsMeasured) {
  const LookupEnergy e = lookup_energy(DeviceConfig{});
  EXPECT_FALSE(e.estimate);
  EXPECT_DOUBLE_EQ(e.pj, 581.02);
  EXPECT_DOUBLE_EQ(e.pj_7nm, 1.053);
  EXPECT_EQ(e.source, "measured for LANES 4 DEPTH 0 (simulate scene), docs/hardware.md");
}

TEST(EnergyTable, OtherLogicIsAnEstimateNamingItsSource) {
  DeviceConfig c;
  c.LANES = 2;
  c.PW = 16;
  const LookupEnergy e = lookup_energy(c);
  EXPECT_TRUE(e.estimate);
  EXPECT_DOUBLE_EQ(e.pj, 581.02);
  EXPECT_EQ(e.source,
            "estimate: 581.02 pJ a lookup measured for LANES 4 DEPTH 0 (simulate scene), not for LANES 2 PW 16, "
            "docs/hardware.md");
  c = DeviceConfig{};
  c.depth = 2;  // the nearest row is of the same depth when the table has one
  const EnergyTable t = parse_energy_table(kHeader + row("simulate", "500") + row("room", "900", kDefaultLogic, 2) +
                                               row("simulate", "700", kDefaultLogic, 2),
                                           "e.tsv");
  EXPECT_DOUBLE_EQ(lookup_energy(c, t).pj, 700);
  EXPECT_FALSE(lookup_energy(c, t).estimate);
  c.depth = 1;
  EXPECT_TRUE(lookup_energy(c, t).estimate);
  EXPECT_DOUBLE_EQ(lookup_energy(c, t).pj, 500);  // the default configuration's on a tie of depth
}

TEST(EnergyTable, ATableWithoutTheSimulateSceneIsRefused) {
  const EnergyTable t = parse_energy_table(kHeader + row("room", "600"), "e.tsv");
  EXPECT_THROW(lookup_energy(DeviceConfig{}, t), EnergyTableError);
}

TEST(SizeEnergy, AFramesEnergyIsItsLookupsTimesTheEnergyPerLookupAndThePowerThatTimesTheRate) {
  SizeReport r;
  r.config = DeviceConfig{};
  LaneMeasure m;
  m.lanes = 4;
  m.lookups = 1000;
  r.lanes = {m};
  r.rate = 2000;
  r.energy = lookup_energy(r.config);
  EXPECT_FALSE(r.energy.estimate);
  EXPECT_DOUBLE_EQ(r.frame_energy_j(), 1000 * 581.02e-12);
  EXPECT_DOUBLE_EQ(r.power_w(), 1000 * 581.02e-12 * 2000);
  EXPECT_DOUBLE_EQ(r.frame_energy_7nm_j(), 1000 * 1.053e-12);
  EXPECT_DOUBLE_EQ(r.power_7nm_w(), 1000 * 1.053e-12 * 2000);
}

TEST(SizeEnergy, ADerivedConfigurationGetsAnEstimateUnlessTheTableMeasuredItsLogic) {
  const RunConfig f = read_scene_file(std::string(VOXCD_SCENES_DIR) + "/small.json");
  const Scene scene = make_scene(f);
  SizeReport r = derive_size(f, scene, {});
  EXPECT_TRUE(r.energy.estimate);
  EXPECT_EQ(r.energy.source.rfind("estimate: 581.02 pJ a lookup measured for LANES 4 DEPTH 0 (simulate scene), not "
                                  "for LANES 1 ",
                                  0),
            0u)
      << r.energy.source;
  EXPECT_GT(r.chosen().lookups, 0);
  EXPECT_DOUBLE_EQ(r.frame_energy_j(), r.chosen().lookups * 581.02e-12);
  EXPECT_DOUBLE_EQ(r.power_w(), r.frame_energy_j() * r.rate);
  // A table that measured the derived configuration's logic (at other memory depths) gives it a measurement.
  DeviceConfig measured = r.config;
  measured.SAW = measured.MAW = 12;
  SizeRequest req;
  req.energy = parse_energy_table(kHeader + row("simulate", "500") + row("simulate", "250", measured.to_string()),
                                  "e.tsv");
  r = derive_size(f, scene, req);
  EXPECT_FALSE(r.energy.estimate) << r.energy.source;
  EXPECT_DOUBLE_EQ(r.frame_energy_j(), r.chosen().lookups * 250e-12);
  const nlohmann::json j = nlohmann::json::parse(size_json(r));
  EXPECT_EQ(j.at("energy_estimate"), false);
  EXPECT_DOUBLE_EQ(j.at("energy_per_frame_j").get<double>(), r.frame_energy_j());
  EXPECT_DOUBLE_EQ(j.at("power_w").get<double>(), r.power_w());
  EXPECT_EQ(j.at("energy_lookups_of"), "mean frame");
  EXPECT_NE(size_text(r).find("\nenergy          "), std::string::npos);
}

}  // namespace
}  // namespace voxcd
