// The timing table (host/device/timing_table.h) and the depth chosen from it (depth.h): the built-in table is the
// source tree's host/device/timing.tsv and names every target; a target may have rows of several configurations; a
// table that cannot be used is refused naming the file, the line and the column; the shallowest depth that meets the
// clock is chosen among the rows of the device's lanes (or those that stand in for them, saying so) and the choice
// says why; a clock no depth meets names the fastest depth. Also the block RAMs a configuration takes per target (block_rams.h), the
// latency a depth costs, and the standard-cell area at 0.18 um (asic_cost.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "voxcd/host/sizing/asic_cost.h"
#include "voxcd/host/sizing/block_rams.h"
#include "voxcd/host/sizing/detail/yosys_run.h"
#include "voxcd/host/sizing/depth.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/host/device/timing_table.h"

namespace voxcd {
namespace {

const std::string kHeader = "target\tdepth\tmhz\tsource\tlanes\tarea_mm2\tluts\tffs\tdsps\tbrams\tlut_levels\tconfig\n";

std::string row(const std::string& target, int depth, const std::string& mhz, const std::string& area = "1.5") {
  return target + "\t" + std::to_string(depth) + "\t" + mhz + "\tOpenSTA, OSU 0.18 um\t4\t" + area +
         "\t-\t1000\t-\t8\t-\tPW 24 PF 8\n";
}

// Three depths of one target: 80, 201 and 263 MHz.
TimingTable three_depths() {
  return parse_timing_table("# a comment\n" + kHeader + row("asic-osu018", 0, "80") + row("asic-osu018", 2, "263") +
                                row("asic-osu018", 1, "201") + row("ice40-hx8k", 0, "48.4", "-"),
                            "t.tsv");
}

const auto kAll = [](int) { return true; };

// The message of the TimingTableError that parsing `text` throws ("" when it parses).
std::string table_error(const std::string& text) {
  try {
    parse_timing_table(text, "t.tsv");
  } catch (const TimingTableError& e) {
    return e.what();
  }
  return "";
}

TEST(TimingTable, TheBuiltInTableIsTheSourceTreesAndNamesEveryTarget) {
  const TimingTable& t = builtin_timing_table();
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/host/device/timing.tsv");
  ASSERT_TRUE(in) << "host/device/timing.tsv is missing";
  std::stringstream s;
  s << in.rdbuf();
  const TimingTable source = parse_timing_table(s.str(), "host/device/timing.tsv");
  ASSERT_EQ(t.rows.size(), source.rows.size()) << "the build's table is not the source tree's: reconfigure";
  for (size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.rows[i].target, source.rows[i].target);
    EXPECT_EQ(t.rows[i].depth, source.rows[i].depth);
    EXPECT_EQ(t.rows[i].mhz, source.rows[i].mhz);
    EXPECT_EQ(t.rows[i].config, source.rows[i].config);
    EXPECT_EQ(t.rows[i].device.LANES, t.rows[i].lanes) << "the lanes column is the config's LANES";
    EXPECT_EQ(t.rows[i].device.depth, t.rows[i].depth);
  }
  for (const std::string& target : timing_targets()) {
    const auto rows = t.target_rows(target);
    ASSERT_FALSE(rows.empty()) << target << " has no row";
    EXPECT_EQ(rows.front().depth, 0) << target << ": every RTL has depth 0";
  }
  const auto asic = t.target_rows("asic-osu018");
  EXPECT_EQ(asic.front().source, "OpenSTA, OSU 0.18 um");
  EXPECT_TRUE(asic.front().area_mm2.has_value() && *asic.front().area_mm2 > 0);
  EXPECT_TRUE(t.target_rows("xilinx-7").front().estimate()) << "yosys has no 7-series delays: an estimate";
  EXPECT_FALSE(asic.front().estimate());
}

TEST(TimingTable, ParsesRowsFiguresAndDashes) {
  const TimingTable t = three_depths();
  ASSERT_EQ(t.rows.size(), 4u);
  const auto asic = t.target_rows("asic-osu018");
  ASSERT_EQ(asic.size(), 3u);
  EXPECT_EQ(asic[1].depth, 1);
  EXPECT_EQ(asic[1].mhz, 201);
  EXPECT_EQ(asic[1].line, 5) << "the comment and the header come first";
  EXPECT_EQ(*asic[1].area_mm2, 1.5);
  EXPECT_EQ(*asic[1].ffs, 1000);
  EXPECT_FALSE(asic[1].luts.has_value());
  EXPECT_FALSE(asic[1].lut_levels.has_value());
  EXPECT_EQ(asic[1].config, "PW 24 PF 8");
  EXPECT_EQ(asic[1].device.PW, 24);
  EXPECT_EQ(asic[1].device.LANES, 4) << "the defaults for the names the config leaves out";
  EXPECT_EQ(asic[1].device.depth, 1) << "the row's depth";
  EXPECT_FALSE(t.target_rows("ice40-hx8k").front().area_mm2.has_value());
  EXPECT_TRUE(t.target_rows("xilinx-7").empty());
}

TEST(TimingTable, ATableThatCannotBeUsedIsRefusedNamingTheLineAndColumn) {
  const std::string ok = row("asic-osu018", 0, "80");
  struct Case {
    std::string text, want;
  };
  const Case cases[] = {
      {"", "t.tsv: no header line"},
      {"# only a comment\n", "t.tsv: no header line"},
      {"target\tdepth\tmhz\n" + ok, "t.tsv:1: the header is 'target depth mhz', expected"},
      {kHeader, "t.tsv: no rows after the header"},
      {kHeader + row("asic-tsmc7", 0, "80"), "t.tsv:2: target: 'asic-tsmc7' is not a target (asic-osu018 ice40-hx8k"},
      {kHeader + row("asic-osu018", -1, "80"), "t.tsv:2: depth: '-1' is not a number >= 0"},
      {kHeader + "asic-osu018\t1.5\t80\tx\t4\t-\t-\t-\t-\t-\t-\tc\n", "t.tsv:2: depth: '1.5' is not a whole number"},
      {kHeader + row("asic-osu018", 0, "fast"), "t.tsv:2: mhz: 'fast' is not a number >= 0"},
      {kHeader + row("asic-osu018", 0, "0"), "t.tsv:2: mhz: '0' is not a positive number of MHz"},
      {kHeader + row("asic-osu018", 0, "nan"), "t.tsv:2: mhz: 'nan' is not a number >= 0"},
      {kHeader + row("asic-osu018", 0, "80", "big"), "t.tsv:2: area_mm2: 'big' is not a number >= 0"},
      {kHeader + row("asic-osu018", 0, "80", ""), "t.tsv:2: area_mm2: '' is not a number >= 0"},
      {kHeader + "asic-osu018\t0\t80\n", "t.tsv:2: 3 tab-separated columns, expected 12"},
      {kHeader + ok + ok, "t.tsv:3: asic-osu018 at depth 0 is given twice"},
      {kHeader + "asic-osu018\t0\t80\t\t4\t-\t-\t-\t-\t-\t-\tc\n", "t.tsv:2: source: '' is empty"},
      {kHeader + "asic-osu018\t0\t80\tx\t0\t-\t-\t-\t-\t-\t-\tc\n", "t.tsv:2: lanes: '0' is not a whole number from 1"},
      {kHeader + "asic-osu018\t0\t80\tx\t4\t-\t-\t-\t-\t-\t-\tc\n", "t.tsv:2: config: 'c' is not a configuration: "},
      {kHeader + "asic-osu018\t0\t80\tx\t4\t-\t-\t-\t-\t-\t-\tLANES 0\n",
       "t.tsv:2: config: 'LANES 0' is not a configuration: invalid device configuration: LANES = 0"},
      {kHeader + "asic-osu018\t0\t80\tx\t4\t-\t-\t-\t-\t-\t-\tLANES 16\n",
       "t.tsv:2: lanes: '4' is not the config's LANES 16 (LANES 16)"},
      {kHeader + "asic-osu018\t0\t80\tx\t4\t-\t-\t-\t-\t-\t-\tPW 24 DEPTH 2\n",
       "t.tsv:2: config: 'PW 24 DEPTH 2' names DEPTH 2, but the row is of depth 0"},
      {kHeader + ok + "asic-osu018\t0\t90\tx\t4\t-\t-\t-\t-\t-\t-\tPF 8 PW 24 LANES 4\n",
       "t.tsv:3: asic-osu018 at depth 0 is given twice for one configuration (PF 8 PW 24 LANES 4)"},
  };
  for (const Case& c : cases) {
    const std::string got = table_error(c.text);
    EXPECT_EQ(got.rfind(c.want, 0), 0u) << "table:\n" << c.text << "\nerror: '" << got << "'\nexpected: '" << c.want << "'";
  }
  EXPECT_EQ(table_error(kHeader + ok), "") << "a good table parses";
  EXPECT_EQ(table_error("\r\n" + kHeader.substr(0, kHeader.size() - 1) + "\r\n" + ok), "") << "CRLF line ends";
}

TEST(TimingTable, ATargetMayHaveRowsOfSeveralConfigurations) {
  const TimingTable t = parse_timing_table(
      kHeader + row("asic-osu018", 0, "80") + "asic-osu018\t0\t70\tOpenSTA\t16\t2\t-\t-\t-\t8\t-\tLANES 16 BANKS 4\n" +
          "asic-osu018\t2\t120\tOpenSTA\t4\t2\t-\t-\t-\t8\t-\tPW 24 PF 8 DEPTH 2\n",
      "t.tsv");
  const auto asic = t.target_rows("asic-osu018");
  ASSERT_EQ(asic.size(), 3u);
  EXPECT_EQ(asic[0].mhz, 80) << "table order within a depth";
  EXPECT_EQ(asic[1].device.BANKS, 4);
  EXPECT_EQ(asic[1].lanes, 16);
  EXPECT_EQ(asic[2].device.depth, 2) << "a config may name the row's own depth";
  EXPECT_TRUE(same_logic(asic[0].device, DeviceConfig{}));
  DeviceConfig other_memories;
  other_memories.SAW = 10, other_memories.MAW = 20;
  EXPECT_TRUE(same_logic(asic[0].device, other_memories)) << "SAW and MAW change no logic the flows measure";
  EXPECT_FALSE(same_logic(asic[1].device, DeviceConfig{}));
  EXPECT_EQ(logic_text(asic[1].device), "LANES 16 DEPTH 0 BANKS 4");
  EXPECT_EQ(logic_difference(DeviceConfig{}, asic[1].device), "LANES 4 BANKS 0");
  EXPECT_EQ(nearest_row(t, "asic-osu018", asic[1].device)->mhz, 70);
  EXPECT_EQ(nearest_row(t, "xilinx-7", DeviceConfig{}), nullptr);
}

TEST(TimingTable, AFileThatCannotBeReadIsNamed) {
  try {
    read_timing_table("/nonexistent/timing.tsv");
    FAIL() << "a missing file was read";
  } catch (const TimingTableError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/timing.tsv: cannot read");
  }
}

TEST(DepthChoice, TheShallowestDepthThatMeetsTheClockAndWhy) {
  const TimingTable t = three_depths();
  const DepthChoice c = choose_depth(t, "asic-osu018", 250, kAll);
  EXPECT_EQ(c.depth(), 2);
  EXPECT_EQ(c.why(), "depth 2: 263 MHz >= 250; depth 1: 201 MHz < 250; depth 0: 80 MHz < 250");
  EXPECT_EQ(choose_depth(t, "asic-osu018", 201, kAll).depth(), 1) << "a clock exactly met is met";
  EXPECT_EQ(choose_depth(t, "asic-osu018", 200, kAll).why(), "depth 1: 201 MHz >= 200; depth 0: 80 MHz < 200");
  EXPECT_EQ(choose_depth(t, "asic-osu018", 50, kAll).why(), "depth 0: 80 MHz >= 50");
  // Only the depths the device offers count.
  EXPECT_EQ(choose_depth(t, "asic-osu018", 150, [](int d) { return d != 1; }).depth(), 2);
}

TEST(DepthChoice, AClockNoDepthMeetsNamesTheFastest) {
  const TimingTable t = three_depths();
  try {
    choose_depth(t, "asic-osu018", 300, kAll);
    FAIL() << "300 MHz was met";
  } catch (const SizeError& e) {
    EXPECT_EQ(e.constraint, "clock");
    EXPECT_NEAR(e.factor, 300.0 / 263, 1e-12);
    EXPECT_EQ(std::string(e.what()),
              "clock: no depth meets 300 MHz on asic-osu018 (t.tsv): the fastest is depth 2 at 263 MHz (OpenSTA, "
              "OSU 0.18 um); 300 MHz is 1.14 times faster");
  }
  // The device offers depth 0 only: its figure is the fastest there is.
  try {
    choose_depth(t, "asic-osu018", 100, [](int d) { return d == 0; });
    FAIL() << "100 MHz was met at depth 0";
  } catch (const SizeError& e) {
    EXPECT_NE(std::string(e.what()).find("the fastest is depth 0 at 80 MHz"), std::string::npos) << e.what();
  }
  EXPECT_THROW(choose_depth(t, "xilinx-7", 100, kAll), TimingTableError) << "no row for the target";
  EXPECT_THROW(choose_depth(t, "xilinx-9", 100, kAll), std::invalid_argument);
  EXPECT_THROW(choose_depth(t, "asic-osu018", 0, kAll), std::invalid_argument);
}

TEST(DepthChoice, TheDeviceOffersDepthZeroAndTheBuiltInTableChoosesFromIt) {
  EXPECT_EQ(depth_of(DeviceConfig{}), 0) << "depth 0 is the default (today's datapath)";
  EXPECT_EQ(depth_of(at_depth(DeviceConfig{}, 0)), 0);
  EXPECT_THROW(at_depth(DeviceConfig{}, -1), ConfigError);
  EXPECT_THROW(at_depth(DeviceConfig{}, 1000), ConfigError);
  const TimingRow zero = builtin_timing_table().target_rows("asic-osu018").front();
  const DepthChoice c = choose_depth(builtin_timing_table(), "asic-osu018", zero.mhz / 2);
  EXPECT_EQ(c.depth(), 0);
  EXPECT_EQ(c.table, "host/device/timing.tsv (built in)");
  EXPECT_EQ(c.stand_in, "") << "the built-in asic rows are of the default configuration's LANES 4";
}

// The rows of LANES 4 (80, 201, 263 MHz at depths 0, 1, 2) and of LANES 16 BANKS 4 (60 and 150 MHz at depths 0, 2).
TimingTable two_configurations() {
  std::string text = kHeader + row("asic-osu018", 0, "80") + row("asic-osu018", 1, "201") + row("asic-osu018", 2, "263");
  for (const auto& [depth, mhz] : {std::pair{0, "60"}, {2, "150"}})
    text += "asic-osu018\t" + std::to_string(depth) + "\t" + mhz + "\tOpenSTA\t16\t2\t-\t-\t-\t8\t-\tLANES 16 BANKS 4\n";
  return parse_timing_table(text, "t.tsv");
}

DeviceConfig lanes_banks(int lanes, int banks) {
  DeviceConfig c;
  c.LANES = lanes;
  c.BANKS = banks;
  return c;
}

TEST(DepthChoice, TheRowsOfTheDevicesLanesAndBanks) {
  const TimingTable t = two_configurations();
  const DepthChoice banked = choose_depth(t, "asic-osu018", 100, lanes_banks(16, 4));
  EXPECT_EQ(banked.depth(), 2);
  EXPECT_EQ(banked.why(), "depth 2: 150 MHz >= 100; depth 0: 60 MHz < 100") << "its own rows: no depth 1";
  EXPECT_EQ(banked.stand_in, "");
  EXPECT_EQ(banked.row.config, "LANES 16 BANKS 4");
  const DepthChoice lanes4 = choose_depth(t, "asic-osu018", 100, lanes_banks(4, 0));
  EXPECT_EQ(lanes4.depth(), 1);
  EXPECT_EQ(lanes4.stand_in, "");
  try {
    choose_depth(t, "asic-osu018", 200, lanes_banks(16, 4));
    FAIL() << "200 MHz was met by LANES 16 BANKS 4";
  } catch (const SizeError& e) {
    EXPECT_NE(std::string(e.what()).find("the fastest is depth 2 at 150 MHz (OpenSTA); "), std::string::npos) << e.what();
  }
}

TEST(DepthChoice, LanesNotMeasuredTakeTheLanes4RowsAndSaySo) {
  const TimingTable t = two_configurations();
  const DepthChoice c = choose_depth(t, "asic-osu018", 100, lanes_banks(32, 0));
  EXPECT_EQ(c.depth(), 1);
  EXPECT_EQ(c.stand_in, "the clocks of LANES 4, none measured at LANES 32");
  EXPECT_EQ(c.why(), "depth 1: 201 MHz >= 100; depth 0: 80 MHz < 100; the clocks of LANES 4, none measured at LANES 32");
  EXPECT_EQ(choose_depth(t, "asic-osu018", 100, lanes_banks(16, 0)).stand_in,
            "the clocks of LANES 4, none measured at LANES 16") << "LANES 16 was measured with banks only";
  try {
    choose_depth(t, "asic-osu018", 300, lanes_banks(32, 0));
    FAIL() << "300 MHz was met";
  } catch (const SizeError& e) {
    EXPECT_NE(std::string(e.what()).find("(OpenSTA, OSU 0.18 um; the clocks of LANES 4, none measured at LANES 32)"),
              std::string::npos) << e.what();
  }
  // A target measured at another lane count only (the iCE40's LANES 1): its rows, said to stand in.
  const TimingTable ice = parse_timing_table(
      kHeader + "ice40-hx8k\t0\t60\tnextpnr\t1\t-\t1\t-\t0\t4\t-\tLANES 1\n", "i.tsv");
  const DepthChoice i = choose_depth(ice, "ice40-hx8k", 20, DeviceConfig{});
  EXPECT_EQ(i.depth(), 0);
  EXPECT_EQ(i.stand_in, "the clocks of LANES 1, none measured at LANES 4");
  EXPECT_EQ(choose_depth(ice, "ice40-hx8k", 20, lanes_banks(1, 0)).stand_in, "");
}

TEST(DepthChoice, LatencyIsTheQueueTheSlotsAndTheOutputRegister) {
  // docs/hardware.md, "Latency": a one-point job's hit record is on the pins in cycle 8 (2-bit device), 3 later on a
  // distance device.
  EXPECT_EQ(latency_cycles(DeviceConfig{}), 8 + depth_of(DeviceConfig{}));
  DeviceConfig d;
  d.SB = 8;
  EXPECT_EQ(latency_cycles(d), 11);
}

DeviceConfig lanes(int l, int saw = 12, int maw = 12) {
  DeviceConfig c;
  c.LANES = l;
  c.SAW = saw;
  c.MAW = maw;
  return c;
}

TEST(BlockRams, CountsMatchWhatSynthesisBuilt) {
  // docs/hardware.md's synth_xilinx table (default widths, SAW = MAW = 12): 16, 24, 40, 72 RAMB36.
  EXPECT_EQ(block_rams(lanes(1), "xilinx-7").count, 16);
  EXPECT_EQ(block_rams(lanes(2), "xilinx-7").count, 24);
  EXPECT_EQ(block_rams(lanes(4), "xilinx-7").count, 40);
  EXPECT_EQ(block_rams(lanes(8), "xilinx-7").count, 72);
  EXPECT_EQ(block_rams(lanes(4), "xilinx-7").unit, "RAMB36");
  // docs/size.md's worked example: PW 8, LANES 2, SAW 14, MAW 10: 16 RAMB36.
  DeviceConfig mixed = lanes(2, 14, 10);
  mixed.PW = 8;
  EXPECT_EQ(block_rams(mixed, "xilinx-7").count, 16);
  // The iCE40 place-and-route configuration (PW 10, MEMW 16, SAW 8, MAW 9, LANES 1): 4 of nextpnr's RAMs.
  DeviceConfig small = lanes(1, 8, 9);
  small.PW = 10;
  small.MEMW = 16;
  EXPECT_EQ(block_rams(small, "ice40-hx8k").count, 4);
  EXPECT_EQ(block_rams(small, "ice40-up5k").count, 4);
  EXPECT_EQ(block_rams(small, "ice40-hx8k").available, 32) << "the HX8K's 32 RAMs (nextpnr: 4 / 32)";
  EXPECT_EQ(block_rams(small, "ice40-up5k").available, 30);
  EXPECT_EQ(block_rams(small, "xilinx-7").available, 0) << "no one 7-series part";
  // ASIC: one SRAM macro per memory (bench/timing.sh's 4 shell banks and 4 voxmap copies at LANES 4).
  EXPECT_EQ(block_rams(lanes(4), "asic-osu018").count, 8);
  EXPECT_EQ(block_rams(lanes(4), "asic-osu018").unit, "SRAM macros");
  DeviceConfig banked = lanes(4);
  banked.BANKS = 4;
  EXPECT_EQ(block_rams(banked, "asic-osu018").count, 8) << "4 shell banks, 4 shared voxmap banks";
  EXPECT_EQ(block_rams(banked, "xilinx-7").count, 16) << "docs/hardware.md's banks table: 16 RAMB36";
  DeviceConfig distance = lanes(1);
  distance.SB = 8;
  EXPECT_EQ(block_rams(distance, "xilinx-7").count, 16) << "docs/hardware.md's distance table: 16 RAMB36";
  EXPECT_THROW(block_rams(lanes(1), "xilinx-9"), std::invalid_argument);
}

// A sparse device's voxmap memory has two read ports (voxcd_ram2): yosys builds it as true dual-port RAMB36 (ports at
// most 36 bits wide) and, on an iCE40, as a copy per read port. The counts are what yosys 0.23 built for these
// configurations (synth_xilinx; synth_ice40, before place and route), and each differs from the one-port count.
TEST(BlockRams, ASparseDevicesVoxmapHasTwoReadPorts) {
  DeviceConfig c = lanes(1, 10, 9);
  c.PW = 24, c.PF = 1, c.MW = 14, c.MF = 13, c.TW = 24, c.DW = 5;
  EXPECT_EQ(block_rams(c, "xilinx-7").count, 3) << "yosys: 3";
  c.BL = 3;
  EXPECT_EQ(memory_shapes(c).back().read_ports, 2);
  EXPECT_EQ(block_rams(c, "xilinx-7").count, 4) << "yosys: 4 (the voxmap 512 x 64 in 36-bit ports: 2)";
  c.MAW = 11;
  EXPECT_EQ(block_rams(c, "xilinx-7").count, 6) << "yosys: 6";
  c = lanes(1, 8, 9);
  c.PW = 24, c.PF = 1, c.MW = 14, c.MF = 13, c.TW = 24, c.DW = 5, c.BL = 3;
  EXPECT_EQ(block_rams(c, "ice40-hx8k").count, 21) << "yosys: 21 (the shell 5, the voxmap 8 a copy, 2 copies)";
  c.MAW = 10;
  EXPECT_EQ(block_rams(c, "ice40-hx8k").count, 37) << "yosys: 37";
  // One read port: the voxmap once (yosys: 10 and 18 blocks for MAW 9 and 10, 8 more).
  c.BL = 0;
  const double maw10 = block_rams(c, "ice40-hx8k").count;
  c.MAW = 9;
  EXPECT_EQ(maw10 - block_rams(c, "ice40-hx8k").count, 8);
  EXPECT_EQ(block_rams(c, "asic-osu018").count, 2);
  // yosys_cost sets BL like every other parameter (without it a sparse configuration synthesised as a dense one).
  EXPECT_EQ(detail::chparam_device(c).find(" -set BL "), std::string::npos);
  c.BL = 3;
  EXPECT_EQ(block_rams(c, "asic-osu018").count, 2) << "one SRAM macro a memory, whatever its read ports";
  EXPECT_NE(detail::chparam_device(c).find(" -set BL 3 "), std::string::npos) << detail::chparam_device(c);
}

TEST(AsicCost, ASmallConfigurationMapsOntoTheCellLibrary) {
  EXPECT_THROW(asic_cost(DeviceConfig{}, 0, VOXCD_SOURCE_DIR "/rtl"), std::invalid_argument);
  DeviceConfig small = lanes(1, 8, 9);
  small.PW = 10, small.PF = 2, small.MW = 8, small.MF = 6, small.TW = 20, small.DW = 5, small.MEMW = 16, small.TAGW = 4;
  const AsicCost c = asic_cost(small, 100, VOXCD_SOURCE_DIR "/rtl");
  EXPECT_GT(c.flip_flops, 100u);
  EXPECT_GT(c.cells, c.flip_flops);
  // The area is the cells' own: between the smallest cell's (16 um^2) and the largest's (176 um^2) times the count.
  EXPECT_GE(c.area_mm2 * 1e6, 16.0 * double(c.cells));
  EXPECT_LE(c.area_mm2 * 1e6, 176.0 * double(c.cells));
  EXPECT_NE(c.command.find("-D 10000"), std::string::npos) << "mapped for 100 MHz: " << c.command;
  // A sparse device's memories (voxcd_ram2, two read ports) are SRAM macros too: their bits are not cells.
  DeviceConfig sparse = small;
  sparse.PW = 24, sparse.MEMW = 64, sparse.BL = 3;
  const AsicCost s = asic_cost(sparse, 100, VOXCD_SOURCE_DIR "/rtl");
  EXPECT_LT(s.flip_flops, uint64_t{1} << 14) << "fewer than the voxmap's 2^9 x 64 bits";
  EXPECT_GT(s.flip_flops, c.flip_flops) << "a sparse device's registers";
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Adders, subtractors and comparators of 1 to 64 bits mapped with the Kogge-Stone carry unit are equal to their RTL
// (a SAT proof over every input), and the map was used.
TEST(AsicCost, TheKoggeStoneCarryUnitEqualsTheAdders) {
  EXPECT_EQ(std::string(kogge_stone_map()), file_text(VOXCD_SOURCE_DIR "/host/sizing/kogge_stone.v"))
      << "the library's map is not the source tree's: reconfigure";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "voxcd_test_kogge_stone";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "kogge_stone.v") << kogge_stone_map();
  std::ofstream(dir / "adders.v")
      << "module adders(input a1, b1, input [1:0] a2, b2, input [2:0] a3, b3, input [6:0] a7, b7,\n"
         "  input signed [31:0] a32, b32, input [63:0] a64, b64, input ci,\n"
         "  output [1:0] s1, output [2:0] s2, output [2:0] s3, output [6:0] d7, output [31:0] d32,\n"
         "  output lt32, ge64, output [64:0] s64);\n"
         "  assign s1 = a1 + b1; assign s2 = a2 + b2; assign s3 = a3 + b3 + ci; assign d7 = a7 - b7;\n"
         "  assign d32 = a32 - b32; assign lt32 = a32 < b32; assign ge64 = a64 >= b64; assign s64 = a64 + b64;\n"
         "endmodule\n";
  const std::string script =
      "read_verilog adders.v; synth -top adders -run begin:fine; opt -fast -full; memory_map; opt -full; "
      "techmap -map +/techmap.v -map kogge_stone.v; opt -fast; rename adders gate; read_verilog adders.v; proc; "
      "rename adders gold; miter -equiv -flatten -make_outputs gold gate miter; hierarchy -top miter; "
      "sat -verify -prove trigger 0 miter";
  const std::string cmd =
      "cd '" + dir.string() + "' && yosys -l log.txt -q -p '" + script + "' > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "not equal, or yosys failed; see " << (dir / "log.txt").string();
  EXPECT_NE(file_text((dir / "log.txt").string()).find("_80_voxcd_lcu_kogge_stone"), std::string::npos)
      << "the Kogge-Stone map was not used";
  // A broken map (one prefix step dropped) must fail the same proof, so the proof can fail.
  std::string broken = kogge_stone_map();
  const size_t at = broken.find("(p[k*WIDTH + j] & g[k*WIDTH + j - (1 << k)])");
  ASSERT_NE(at, std::string::npos);
  broken.replace(at, std::string("(p[k*WIDTH + j] & g[k*WIDTH + j - (1 << k)])").size(), "1'b0");
  std::ofstream(dir / "kogge_stone.v") << broken;
  EXPECT_NE(std::system(cmd.c_str()), 0) << "a broken carry unit passed the proof";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxcd
