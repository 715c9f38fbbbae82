// The device clock (host/device/clock.h): the default estimate equals docs/hardware.md's bench:fmax block, every
// clock says where it comes from, and a clock that is no frequency is refused naming where it was given.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {
namespace {

// The text between docs/hardware.md's bench:fmax markers (what bench/fmax.sh wrote).
std::string fmax_block() {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/docs/hardware.md");
  std::stringstream s;
  s << in.rdbuf();
  const std::string doc = s.str();
  const auto begin = doc.find("<!-- bench:fmax:begin -->"), end = doc.find("<!-- bench:fmax:end -->");
  if (begin == std::string::npos || end == std::string::npos || end < begin) return "";
  return doc.substr(begin, end - begin);
}

bool numeric(char c) { return std::isdigit(static_cast<unsigned char>(c)) || c == '.'; }

// The number (digits and points) right before the first `after` in `text`, or "" when there is none.
std::string number_before(const std::string& text, const std::string& after) {
  const size_t at = text.find(after);
  if (at == std::string::npos) return "";
  size_t b = at;
  while (b > 0 && numeric(text[b - 1])) --b;
  return text.substr(b, at - b);
}

// The number right after the first `before` in `text`, or "".
std::string number_after(const std::string& text, const std::string& before) {
  const size_t at = text.find(before);
  if (at == std::string::npos) return "";
  size_t e = at + before.size();
  while (e < text.size() && numeric(text[e])) ++e;
  return text.substr(at + before.size(), e - at - before.size());
}

TEST(DeviceClock, DefaultEqualsTheLogicDepthEstimateOfHardwareMd) {
  const std::string block = fmax_block();
  ASSERT_FALSE(block.empty()) << "docs/hardware.md has no bench:fmax block";
  const std::string levels = number_before(block, " LUT levels and ");
  const std::string carry = number_before(block, " CARRY4 cells");
  const std::string ns_lut = number_after(block, "Assuming ");
  const std::string ns_carry = number_before(block, " ns per CARRY4");
  const std::string path = number_after(block, "the path takes ");
  const std::string mhz = number_after(block, "an estimated clock of ");
  ASSERT_FALSE(levels.empty() || carry.empty() || ns_lut.empty() || ns_carry.empty() || path.empty() || mhz.empty())
      << "the bench:fmax block no longer states the logic-depth estimate as bench/fmax.sh wrote it:\n" << block;
  // When bench/fmax.sh gives another figure, host/device/clock.h's constants must follow it.
  EXPECT_EQ(std::stoi(levels), kEstimateLutLevels);
  EXPECT_EQ(std::stoi(carry), kEstimateCarry4);
  EXPECT_DOUBLE_EQ(std::stod(ns_lut), kEstimateNsPerLut);
  EXPECT_DOUBLE_EQ(std::stod(ns_carry), kEstimateNsPerCarry4);
  EXPECT_NEAR(std::stod(path), default_path_ns(), 1e-9);
  EXPECT_DOUBLE_EQ(std::stod(mhz), kDefaultClockMhz);
  EXPECT_EQ(std::lround(1000 / default_path_ns()), std::lround(kDefaultClockMhz));
}

TEST(DeviceClock, TheDecisionIsWrittenDown) {
  std::ifstream in(std::string(VOXCD_SOURCE_DIR) + "/docs/hardware.md");
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_NE(s.str().find("The default clock"), std::string::npos)
      << "docs/hardware.md should say which clock the tool uses by default, and why";
}

TEST(DeviceClock, TheDefaultSaysItIsAnEstimateAndWhere) {
  const DeviceClock c = default_device_clock();
  EXPECT_EQ(c.mhz, kDefaultClockMhz);
  EXPECT_TRUE(c.estimate);
  EXPECT_EQ(c.source,
            "estimate: synth_xilinx logic depth of the default configuration, 16 LUT levels x 0.5 ns + 2 CARRY4 x "
            "0.1 ns = 8.2 ns (docs/hardware.md)");
  EXPECT_EQ(c.text(), "122 MHz (" + c.source + ")");
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

TEST(DeviceClock, ASceneFileWithoutClockUsesTheEstimate) {
  const SceneFile none = parse_scene_file(R"({"types": [{"shape": "cube"}]})", "a.json");
  EXPECT_EQ(none.clock.mhz, kDefaultClockMhz);
  EXPECT_EQ(none.clock.source, default_device_clock().source);
  const SceneFile given = parse_scene_file(R"({"types": [{"shape": "cube"}], "clock": 90})", "a.json");
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
  s.frames = 10;
  s.clock = default_device_clock();
  s.totals.idle_frames = 10;
  EXPECT_EQ(s.device_rate(), 0);
  EXPECT_EQ(s.device_rate_text(), "none: the frames needed no device cycles");
  s.totals.cycles = 1220;  // one frame of 1220 cycles, nine of none: 122 cycles a frame on average
  s.totals.max_cycles = 1220;
  s.totals.idle_frames = 9;
  EXPECT_EQ(s.device_rate_text(), "1000000 Hz at " + s.clock.text() + "; 9 of 10 frames needed no device cycles");
}

}  // namespace
}  // namespace voxcd
