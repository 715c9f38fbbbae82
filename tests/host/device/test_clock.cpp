// The device clock (host/device/clock.h): a configuration's clock is the OpenSTA figure measured for it (the default
// configuration's that of docs/hardware.md's bench:timing block and of the timing table), or an estimate from the
// nearest configuration measured that says so; a given clock is never replaced; every clock says where it comes
// from, and a clock that is no frequency is refused naming where it was given.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/device/timing_table.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/host/sizing/depth.h"

namespace voxcd {
namespace {

// The default configuration's section of the text between docs/hardware.md's bench:timing markers (what
// bench/timing.sh wrote): from its "<!-- timing config: ... -->" line to the next section or the block's end.
std::string timing_block() {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/docs/hardware.md");
  std::stringstream s;
  s << in.rdbuf();
  const std::string doc = s.str();
  const auto begin = doc.find("<!-- bench:timing:begin -->"), end = doc.find("<!-- bench:timing:end -->");
  if (begin == std::string::npos || end == std::string::npos || end < begin) return "";
  const std::string block = doc.substr(begin, end - begin);
  const std::string marker = "<!-- timing config: ";
  const auto section = block.find(marker + "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 12 MAW 12 TAGW 16 -->");
  if (section == std::string::npos) return "";
  const auto next = block.find(marker, section + marker.size());
  return block.substr(section, next == std::string::npos ? std::string::npos : next - section);
}

// The cells of the first table row of `text` that starts with "| <first> |", trimmed; empty when there is none.
std::vector<std::string> table_row(const std::string& text, const std::string& first) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| " + first + " |", 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream row(line.substr(1));
    for (std::string cell; std::getline(row, cell, '|');) {
      const size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    return cells;
  }
  return {};
}

TEST(DeviceClock, DefaultIsTheOpenStaClockOfHardwareMdAndTheTimingTable) {
  const std::string block = timing_block();
  ASSERT_FALSE(block.empty()) << "docs/hardware.md has no bench:timing block";
  const int depth = depth_of(DeviceConfig{});
  // The summary table: depth, latency, ASIC Fmax (MHz), ...
  const std::vector<std::string> cells = table_row(block, std::to_string(depth));
  ASSERT_GE(cells.size(), 3u) << "the bench:timing block has no row for depth " << depth << ":\n" << block;
  EXPECT_NE(block.find("| depth | latency (cycles) | ASIC Fmax (MHz) |"), std::string::npos)
      << "the summary table's columns moved:\n" << block;
  // When bench/timing.sh gives another figure, host/device/clock.h's constant must follow it.
  EXPECT_DOUBLE_EQ(std::stod(cells[2]), kDefaultClockMhz) << "docs/hardware.md's ASIC Fmax at depth " << depth;
  bool found = false;
  for (const TimingRow& r : builtin_timing_table().target_rows("asic-osu018"))
    if (same_logic(r.device, DeviceConfig{})) {
      found = found || r.depth == depth;
      if (r.depth == depth) {
        EXPECT_DOUBLE_EQ(r.mhz, kDefaultClockMhz) << "host/device/timing.tsv at depth " << depth;
      }
    }
  EXPECT_TRUE(found) << "host/device/timing.tsv has no asic-osu018 row of the default configuration at depth " << depth;
  const DeviceClock c = clock_for(DeviceConfig{});
  EXPECT_EQ(c.mhz, kDefaultClockMhz);
  EXPECT_EQ(c.source, kDefaultClockSource);
  EXPECT_FALSE(c.estimate);
}

TEST(DeviceClock, TheDecisionIsWrittenDown) {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/docs/hardware.md");
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_NE(s.str().find("The default clock"), std::string::npos)
      << "docs/hardware.md should say which clock the tool uses by default, and why";
}

TEST(DeviceClock, TheDefaultSaysItIsAMeasurementForWhichConfigurationAndWhere) {
  const DeviceClock c = default_device_clock();
  EXPECT_EQ(c.mhz, kDefaultClockMhz);
  EXPECT_FALSE(c.estimate);
  EXPECT_EQ(c.source, "OpenSTA, OSU 0.18 um, measured for LANES 4 DEPTH 0, docs/hardware.md");
  std::ostringstream mhz;
  mhz << kDefaultClockMhz;
  EXPECT_EQ(c.text(), mhz.str() + " MHz (OpenSTA, OSU 0.18 um, measured for LANES 4 DEPTH 0, docs/hardware.md)");
}

// The asic-osu018 row of the built-in table at `depth` measured for the default widths at LANES 4.
TimingRow lanes4_row(int depth) {
  for (const TimingRow& r : builtin_timing_table().target_rows("asic-osu018")) {
    DeviceConfig c;
    c.depth = depth;
    if (same_logic(r.device, c)) return r;
  }
  ADD_FAILURE() << "host/device/timing.tsv has no asic-osu018 row of LANES 4 at depth " << depth;
  return {};
}

DeviceConfig with(int lanes, int depth = 0) {
  DeviceConfig c;
  c.LANES = lanes;
  c.depth = depth;
  return c;
}

TEST(DeviceClock, TheDefaultConfigurationGetsItsMeasuredClockWhateverItsMemoryDepths) {
  DeviceConfig c;
  ASSERT_NE(c.MAW, lanes4_row(0).device.MAW) << "the measured row has SAW = MAW = 12, the default device MAW 18";
  for (const auto& [saw, maw] : {std::pair{16, 18}, {12, 12}, {20, 24}}) {
    c.SAW = saw, c.MAW = maw;
    const DeviceClock k = clock_for(c);
    EXPECT_EQ(k.mhz, 100.4) << saw << " " << maw;
    EXPECT_FALSE(k.estimate);
    EXPECT_EQ(k.source, kDefaultClockSource);
  }
}

TEST(DeviceClock, Lanes32IsAnEstimateThatSaysWhatItComesFrom) {
  const DeviceClock c = clock_for(with(32));
  EXPECT_TRUE(c.estimate);
  EXPECT_EQ(c.mhz, lanes4_row(0).mhz) << "the clock of the same depth at LANES 4";
  EXPECT_EQ(c.source, "estimate: the clock of LANES 4 DEPTH 0 (OpenSTA, OSU 0.18 um), not measured for LANES 32, "
                      "docs/hardware.md");
  EXPECT_NE(c.text().find("estimate"), std::string::npos) << "every printed rate says so: " << c.text();
  EXPECT_NE(c.source.find("LANES 4"), std::string::npos);
  EXPECT_NE(c.source.find("LANES 32"), std::string::npos);
}

TEST(DeviceClock, EachDepthMeasuredAtLanes4GetsItsOwnClock) {
  for (int depth = 0; depth <= kMaxDepth; ++depth) {
    const DeviceClock c = clock_for(with(4, depth));
    EXPECT_FALSE(c.estimate) << depth;
    EXPECT_EQ(c.mhz, lanes4_row(depth).mhz) << depth;
    EXPECT_EQ(c.source, "OpenSTA, OSU 0.18 um, measured for LANES 4 DEPTH " + std::to_string(depth) + ", docs/hardware.md");
  }
  EXPECT_EQ(clock_for(with(4, 3)).mhz, 142.3) << "docs/hardware.md's depth 3";
  // Another lane count at depth 3: that depth's clock at LANES 4, as an estimate.
  const DeviceClock c = clock_for(with(16, 3));
  EXPECT_TRUE(c.estimate);
  EXPECT_EQ(c.mhz, 142.3);
  EXPECT_EQ(c.source, "estimate: the clock of LANES 4 DEPTH 3 (OpenSTA, OSU 0.18 um), not measured for LANES 16, "
                      "docs/hardware.md");
}

TEST(DeviceClock, EveryParameterThatChangesLogicMakesAnEstimate) {
  struct Case {
    void (*set)(DeviceConfig&);
    std::string differs;
  };
  const Case cases[] = {
      {[](DeviceConfig& c) { c.SB = 8; }, "SB 8"},
      {[](DeviceConfig& c) { c.SB = 8, c.WB = 6; }, "SB 8 WB 6"},
      {[](DeviceConfig& c) { c.BANKS = 4; }, "BANKS 4"},
      {[](DeviceConfig& c) { c.BL = 3; }, "BL 3"},
      {[](DeviceConfig& c) { c.BL = 3, c.TX = 1; }, "BL 3 TX 1"},
      {[](DeviceConfig& c) { c.MW = 20; }, "MW 20"},
      {[](DeviceConfig& c) { c.PW = 16, c.PF = 4; }, "PW 16 PF 4"},
      {[](DeviceConfig& c) { c.TAGW = 8; }, "TAGW 8"},
      {[](DeviceConfig& c) { c.LANES = 2, c.MEMW = 32; }, "LANES 2 MEMW 32"},
  };
  for (const Case& k : cases) {
    DeviceConfig c;
    k.set(c);
    const DeviceClock got = clock_for(c);
    EXPECT_TRUE(got.estimate) << k.differs;
    EXPECT_EQ(got.mhz, kDefaultClockMhz) << k.differs;
    EXPECT_EQ(got.source, "estimate: the clock of LANES 4 DEPTH 0 (OpenSTA, OSU 0.18 um), not measured for " + k.differs +
                              ", docs/hardware.md");
  }
  DeviceConfig plain;
  plain.WB = 4;  // a 2-bit device has no weights: WB changes no logic there
  EXPECT_FALSE(clock_for(plain).estimate);
}

const std::string kHeader = "target\tdepth\tmhz\tsource\tlanes\tarea_mm2\tluts\tffs\tdsps\tbrams\tlut_levels\tconfig\n";

std::string asic_row(int depth, const std::string& mhz, int lanes, const std::string& config) {
  return "asic-osu018\t" + std::to_string(depth) + "\t" + mhz + "\tOpenSTA, my run\t" + std::to_string(lanes) +
         "\t5\t-\t-\t-\t8\t-\t" + config + "\n";
}

TEST(DeviceClock, AConfigurationMeasuredInATableOfSeveralIsMeasured) {
  const TimingTable t = parse_timing_table(
      kHeader + asic_row(0, "100", 4, "LANES 4 SAW 12 MAW 12") + asic_row(0, "80", 16, "LANES 16 BANKS 4") +
          asic_row(2, "130", 16, "LANES 16 BANKS 4") + asic_row(2, "140", 4, "LANES 4"),
      "t.tsv");
  DeviceConfig banked = with(16);
  banked.BANKS = 4;
  EXPECT_EQ(clock_for(banked, t).mhz, 80);
  EXPECT_FALSE(clock_for(banked, t).estimate);
  EXPECT_EQ(clock_for(banked, t).source, "OpenSTA, my run, measured for LANES 16 DEPTH 0 BANKS 4, docs/hardware.md");
  banked.depth = 2;
  EXPECT_EQ(clock_for(banked, t).mhz, 130);
  // LANES 16 without banks at depth 2: the same depth, then the same LANES (with banks) before LANES 4.
  const DeviceClock near = clock_for(with(16, 2), t);
  EXPECT_TRUE(near.estimate);
  EXPECT_EQ(near.mhz, 130);
  EXPECT_EQ(near.source, "estimate: the clock of LANES 16 DEPTH 2 BANKS 4 (OpenSTA, my run), not measured for BANKS 0, "
                         "docs/hardware.md");
  // A depth no row has: the default configuration's row.
  const DeviceClock deep = clock_for(with(4, 4), t);
  EXPECT_TRUE(deep.estimate);
  EXPECT_EQ(deep.mhz, 100);
  EXPECT_EQ(deep.source, "estimate: the clock of LANES 4 DEPTH 0 (OpenSTA, my run), not measured for DEPTH 4, "
                         "docs/hardware.md");
  const TimingTable no_asic = parse_timing_table(
      kHeader + "xilinx-7\t0\t120\testimate: levels\t4\t-\t1\t1\t1\t1\t8\tLANES 4\n", "x.tsv");
  EXPECT_THROW(clock_for(DeviceConfig{}, no_asic), TimingTableError);
}

TEST(DeviceClock, AGivenClockIsNeverReplaced) {
  RunConfig c;
  c.clock = given_clock(250, "--clock");
  for (int lanes : {1, 4, 32}) EXPECT_EQ(run_clock(c, with(lanes, 3)).text(), "250 MHz (given by --clock)") << lanes;
  c.clock.reset();
  EXPECT_EQ(run_clock(c, with(32)).text(), clock_for(with(32)).text());
  EXPECT_EQ(run_clock(c, DeviceConfig{}).text(), default_device_clock().text());
}

TEST(DeviceClock, ARunsClockFollowsItsDeviceUnlessGiven) {
  RunConfig o;
  o.types[0].count = 8;
  o.frames = 2;
  o.lanes = 32;
  o.given["lanes"] = SettingSource{"", "lanes"};
  o.given["frames"] = SettingSource{"", "frames"};
  o.given["types[0].count"] = SettingSource{"", "objects"};
  const SimulationSummary wide = simulate(run_config(o));
  EXPECT_EQ(wide.device.LANES, 32);
  EXPECT_TRUE(wide.clock.estimate) << wide.clock.text();
  EXPECT_NE(wide.clock.source.find("not measured for LANES 32"), std::string::npos) << wide.clock.source;
  o.device = with(4, 3);
  o.given["device"] = SettingSource{"", "config"};
  o.given.erase("lanes");
  const SimulationSummary deep = simulate(run_config(o));
  EXPECT_EQ(deep.clock.text(), clock_for(with(4, 3)).text());
  EXPECT_FALSE(deep.clock.estimate);
  o.clock = given_clock(75, "--clock");
  o.given["clock"] = SettingSource{"", "clock"};
  EXPECT_EQ(simulate(run_config(o)).clock.text(), "75 MHz (given by --clock)");
  const SimulationSummary plain = simulate(run_config(RunConfig{}));
  EXPECT_EQ(plain.clock.text(), default_device_clock().text()) << "the default configuration: its measured clock";
}

TEST(DeviceClock, AGivenClockNamesWhereItWasGiven) {
  const DeviceClock c = given_clock(150, "--clock");
  EXPECT_EQ(c.mhz, 150);
  EXPECT_FALSE(c.estimate);
  EXPECT_EQ(c.text(), "150 MHz (given by --clock)");
  EXPECT_DOUBLE_EQ(c.rate(1500), 1e5);
  EXPECT_EQ(c.rate(0), 0) << "work of no cycles has no rate";
}

TEST(DeviceClock, AClockThatIsNoFrequencyIsRefusedNamingTheOption) {
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    EXPECT_FALSE(clock_problem(bad).empty()) << bad;
    try {
      given_clock(bad, "--clock");
      ADD_FAILURE() << bad << " was taken as a clock";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--clock: ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find("is not a positive number of MHz"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(clock_problem(0.5), "");
}

TEST(DeviceClock, ASceneFileWithoutClockLeavesItToTheDevice) {
  const RunConfig none = parse_scene_file(R"({"types": [{"shape": "cube"}]})", "a.json");
  EXPECT_FALSE(none.clock.has_value()) << "the run's device configuration decides it (run_clock)";
  const RunConfig given = parse_scene_file(R"({"types": [{"shape": "cube"}], "clock": 90})", "a.json");
  ASSERT_TRUE(given.clock.has_value());
  EXPECT_EQ(given.clock->text(), "90 MHz (given by a.json's \"clock\")");
  EXPECT_EQ(run_clock(given, with(32)).text(), "90 MHz (given by a.json's \"clock\")");
  for (const char* bad : {R"({"types": [{"shape": "cube"}], "clock": 0})", R"({"types": [{"shape": "cube"}], "clock": -2})"}) {
    try {
      parse_scene_file(bad, "a.json");
      ADD_FAILURE() << bad << " was taken";
    } catch (const SceneFileError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("a.json: clock: ", 0), 0u) << e.what();
    }
  }
}

TEST(DeviceClock, FramesWithoutDeviceCyclesHaveNoDeviceRate) {
  SimulationSummary s;
  s.config.frames = 10;
  s.clock = default_device_clock();
  s.totals.idle_frames = 10;
  EXPECT_EQ(s.device_rate(), 0);
  EXPECT_EQ(s.device_rate_text(), "none: the frames needed no device cycles");
  s.clock = given_clock(122, "--clock");
  s.totals.cycles = 1220;  // one frame of 1220 cycles, nine of none: 122 cycles a frame on average
  s.totals.max_cycles = 1220;
  s.totals.idle_frames = 9;
  EXPECT_EQ(s.device_rate_text(), "1000000 Hz at " + s.clock.text() + "; 9 of 10 frames needed no device cycles");
}

}  // namespace
}  // namespace voxcd
