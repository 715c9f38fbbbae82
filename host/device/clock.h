// The device's clock: the one figure every modelled frame rate is computed at, and where that figure comes from
// (a measurement, an estimate, or the user's). docs/hardware.md, "Measured clock", says why the default is what it is.
#pragma once

#include <string>

namespace voxcd {

// The default clock is docs/hardware.md's logic-depth estimate of the default configuration (its bench:fmax block,
// made by bench/fmax.sh): the longest path after synth_xilinx -flatten, at round delays per cell. There is no
// place-and-route measurement of the default configuration (the iCE40 figures are of a reduced one).
// tests/host/test_clock.cpp fails when these and the document disagree.
inline constexpr int kEstimateLutLevels = 16;         // LUT levels on the longest path
inline constexpr double kEstimateNsPerLut = 0.5;      // the LUT and its routing, ns
inline constexpr int kEstimateCarry4 = 2;             // CARRY4 cells on the path
inline constexpr double kEstimateNsPerCarry4 = 0.1;   // ns
inline constexpr double kDefaultClockMhz = 122;       // 1000 / 8.2 ns, rounded as the document prints it

struct DeviceClock {
  double mhz = 0;
  std::string source;     // where mhz comes from: "estimate: ...", "measured: ..." or "given by --clock"
  bool estimate = false;  // true when mhz is an estimate, not a measurement or a figure the user chose

  // "122 MHz (estimate: ...)": the figure and its source, for every printed rate.
  std::string text() const;
  // Per second of a piece of work taking `cycles` device cycles at this clock (mhz x 10^6 / cycles); 0 when
  // cycles is not positive (work that needs no device cycles has no device rate).
  double rate(double cycles) const;
};

// The estimated length of the default configuration's longest path, ns (levels x delays above: 8.2).
double default_path_ns();
// The clock every rate uses unless one is given: kDefaultClockMhz, its source saying how it was estimated.
DeviceClock default_device_clock();
// "" when mhz is a usable clock (finite and > 0), or why not: "-3 is not a positive number of MHz".
std::string clock_problem(double mhz);
// A clock the user gave; `origin` names where ("--clock", "clock=", "scene.json's \"clock\""), and the source is
// "given by <origin>". std::invalid_argument "<origin>: <clock_problem>" for zero, negative, NaN or infinity.
DeviceClock given_clock(double mhz, const std::string& origin);

}  // namespace voxcd
