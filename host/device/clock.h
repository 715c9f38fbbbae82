// The device's clock: the one figure every modelled frame rate is computed at, and where that figure comes from (a
// measurement for the device's configuration, an estimate from the nearest one measured, or the user's).
// docs/hardware.md, "The default clock", says why the default is what it is.
#pragma once

#include <string>

#include "voxcd/ref/config.h"

namespace voxcd {

struct TimingTable;

// The default configuration's clock is a measurement: the largest clock at which OpenSTA finds no negative slack for
// the default configuration (LANES 4, default widths) at its default depth, mapped onto the OSU 0.18 um standard
// cells: the asic-osu018 row of docs/hardware.md's bench:timing block and of host/device/timing.tsv, both made by
// bench/timing.sh. tests/host/device/test_clock.cpp fails when this and those disagree.
inline constexpr double kDefaultClockMhz = 100.4;
inline constexpr const char* kDefaultClockSource =
    "OpenSTA, OSU 0.18 um, measured for LANES 4 DEPTH 0, docs/hardware.md";

struct DeviceClock {
  double mhz = 0;
  // Where mhz comes from: "OpenSTA, OSU 0.18 um, measured for LANES 4 DEPTH 0, docs/hardware.md", "estimate: the
  // clock of LANES 4 DEPTH 0 (OpenSTA, OSU 0.18 um), not measured for LANES 32, docs/hardware.md", or "given by
  // --clock".
  std::string source;
  bool estimate = false;  // true when mhz is an estimate, not a measurement or a figure the user chose

  // "100.4 MHz (OpenSTA, ..., docs/hardware.md)": the figure and its source, for every printed rate.
  std::string text() const;
  // Per second of a piece of work taking `cycles` device cycles at this clock (mhz x 10^6 / cycles); 0 when
  // cycles is not positive (work that needs no device cycles has no device rate).
  double rate(double cycles) const;
};

// The clock of a device of configuration cfg, unless one is given: the built-in timing table's asic-osu018 clock
// measured for it (a row of the same logic: the memory depths SAW and MAW may differ, timing_table.h same_logic),
// named "<how>, measured for <logic_text>, docs/hardware.md"; else an estimate: the clock of the row nearest it
// (nearest_row: the same depth before another, then the same LANES, ...; with the table bench/timing.sh made for the
// default configuration, the same depth at LANES 4, else the default configuration's), named "estimate: the clock of
// <that row's logic_text> (<how>), not measured for <what differs>, docs/hardware.md", with `estimate` set.
DeviceClock clock_for(const DeviceConfig& cfg);
// The same from `table` (TimingTableError when it has no asic-osu018 row).
DeviceClock clock_for(const DeviceConfig& cfg, const TimingTable& table);
// The default configuration's clock (clock_for(DeviceConfig{})): kDefaultClockMhz, its source kDefaultClockSource.
DeviceClock default_device_clock();
// A frequency in MHz as every message prints it ("100.4", "1e+03": the stream's default six significant digits).
std::string mhz_text(double mhz);
// "" when mhz is a usable clock (finite and > 0), or why not: "-3 is not a positive number of MHz".
std::string clock_problem(double mhz);
// A clock the user gave; `origin` names where ("--clock", "clock=", "scene.json's \"clock\""), and the source is
// "given by <origin>". std::invalid_argument "<origin>: <clock_problem>" for zero, negative, NaN or infinity.
DeviceClock given_clock(double mhz, const std::string& origin);

}  // namespace voxcd
