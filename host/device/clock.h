// The device's clock: the one figure every modelled frame rate is computed at, and where that figure comes from
// (a measurement or the user's). docs/hardware.md, "The default clock", says why the default is what it is.
#pragma once

#include <string>

namespace voxcd {

// The default clock is a measurement: the largest clock at which OpenSTA finds no negative slack for the default
// configuration (LANES 4, default widths) at its default depth, mapped onto the OSU 0.18 um standard cells: the
// asic-osu018 row of docs/hardware.md's bench:timing block and of host/sizing/timing.tsv, both made by
// bench/timing.sh. tests/host/device/test_clock.cpp fails when this and those disagree.
inline constexpr double kDefaultClockMhz = 100.4;
inline constexpr const char* kDefaultClockSource = "OpenSTA, OSU 0.18 um, docs/hardware.md";

struct DeviceClock {
  double mhz = 0;
  std::string source;     // where mhz comes from: kDefaultClockSource, or "given by --clock"
  bool estimate = false;  // true when mhz is an estimate, not a measurement or a figure the user chose

  // "100.4 MHz (OpenSTA, OSU 0.18 um, docs/hardware.md)": the figure and its source, for every printed rate.
  std::string text() const;
  // Per second of a piece of work taking `cycles` device cycles at this clock (mhz x 10^6 / cycles); 0 when
  // cycles is not positive (work that needs no device cycles has no device rate).
  double rate(double cycles) const;
};

// The clock every rate uses unless one is given: kDefaultClockMhz, its source kDefaultClockSource.
DeviceClock default_device_clock();
// A frequency in MHz as every message prints it ("100.4", "1e+03": the stream's default six significant digits).
std::string mhz_text(double mhz);
// "" when mhz is a usable clock (finite and > 0), or why not: "-3 is not a positive number of MHz".
std::string clock_problem(double mhz);
// A clock the user gave; `origin` names where ("--clock", "clock=", "scene.json's \"clock\""), and the source is
// "given by <origin>". std::invalid_argument "<origin>: <clock_problem>" for zero, negative, NaN or infinity.
DeviceClock given_clock(double mhz, const std::string& origin);

}  // namespace voxcd
