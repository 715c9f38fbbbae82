// The device clock (host/device/clock.h): the default is the OpenSTA figure of docs/hardware.md's bench:timing block
// and of the timing table, every clock says where it comes from, and a clock that is no frequency is refused naming
// where it was given.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/sizing/depth.h"
#include "voxcd/host/sizing/timing_table.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {
namespace {

// The text between docs/hardware.md's bench:timing markers (what bench/timing.sh wrote).
std::string timing_block() {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/docs/hardware.md");
  std::stringstream s;
  s << in.rdbuf();
  const std::string doc = s.str();
  const auto begin = doc.find("<!-- bench:timing:begin -->"), end = doc.find("<!-- bench:timing:end -->");
  if (begin == std::string::npos || end == std::string::npos || end < begin) return "";
  return doc.substr(begin, end - begin);
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
    if (r.depth == depth) {
      found = true;
      EXPECT_DOUBLE_EQ(r.mhz, kDefaultClockMhz) << "host/sizing/timing.tsv's asic-osu018 row at depth " << depth;
      EXPECT_EQ(r.source + ", docs/hardware.md", kDefaultClockSource);
    }
  EXPECT_TRUE(found) << "host/sizing/timing.tsv has no asic-osu018 row at depth " << depth;
}

TEST(DeviceClock, TheDecisionIsWrittenDown) {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/docs/hardware.md");
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_NE(s.str().find("The default clock"), std::string::npos)
      << "docs/hardware.md should say which clock the tool uses by default, and why";
}

TEST(DeviceClock, TheDefaultSaysItIsAMeasurementAndWhere) {
  const DeviceClock c = default_device_clock();
  EXPECT_EQ(c.mhz, kDefaultClockMhz);
  EXPECT_FALSE(c.estimate);
  EXPECT_EQ(c.source, "OpenSTA, OSU 0.18 um, docs/hardware.md");
  std::ostringstream mhz;
  mhz << kDefaultClockMhz;
  EXPECT_EQ(c.text(), mhz.str() + " MHz (OpenSTA, OSU 0.18 um, docs/hardware.md)");
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

TEST(DeviceClock, ASceneFileWithoutClockUsesTheDefault) {
  const RunConfig none = parse_scene_file(R"({"types": [{"shape": "cube"}]})", "a.json");
  EXPECT_EQ(none.clock.mhz, kDefaultClockMhz);
  EXPECT_EQ(none.clock.source, default_device_clock().source);
  const RunConfig given = parse_scene_file(R"({"types": [{"shape": "cube"}], "clock": 90})", "a.json");
  EXPECT_EQ(given.clock.text(), "90 MHz (given by a.json's \"clock\")");
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
  s.config.clock = default_device_clock();
  s.totals.idle_frames = 10;
  EXPECT_EQ(s.device_rate(), 0);
  EXPECT_EQ(s.device_rate_text(), "none: the frames needed no device cycles");
  s.config.clock = given_clock(122, "--clock");
  s.totals.cycles = 1220;  // one frame of 1220 cycles, nine of none: 122 cycles a frame on average
  s.totals.max_cycles = 1220;
  s.totals.idle_frames = 9;
  EXPECT_EQ(s.device_rate_text(), "1000000 Hz at " + s.config.clock.text() + "; 9 of 10 frames needed no device cycles");
}

}  // namespace
}  // namespace voxcd
