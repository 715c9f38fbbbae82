#include "voxcd/host/device/clock.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "voxcd/host/device/timing_table.h"

namespace voxcd {

namespace {
constexpr const char* kClockTarget = "asic-osu018";  // the target whose clocks every modelled rate uses
}  // namespace

std::string mhz_text(double mhz) {
  std::ostringstream s;
  s << mhz;
  return s.str();
}

std::string DeviceClock::text() const { return mhz_text(mhz) + " MHz (" + source + ")"; }

double DeviceClock::rate(double cycles) const { return cycles > 0 ? mhz * 1e6 / cycles : 0; }

DeviceClock clock_for(const DeviceConfig& cfg) { return clock_for(cfg, builtin_timing_table()); }

DeviceClock clock_for(const DeviceConfig& cfg, const TimingTable& table) {
  const TimingRow* row = nearest_row(table, kClockTarget, cfg);
  if (!row) throw TimingTableError(table.where + ": no " + kClockTarget + " row to take a device clock from");
  if (same_logic(row->device, cfg) && !row->estimate())
    return DeviceClock{row->mhz, row->source + ", measured for " + logic_text(row->device) + ", docs/hardware.md", false};
  const std::string differs = logic_difference(cfg, row->device);
  return DeviceClock{row->mhz,
                     "estimate: the clock of " + logic_text(row->device) + " (" + row->source + "), not measured" +
                         (differs.empty() ? "" : " for " + differs) + ", docs/hardware.md",
                     true};
}

DeviceClock default_device_clock() {
  DeviceClock c;
  c.mhz = kDefaultClockMhz;
  c.estimate = false;
  c.source = kDefaultClockSource;
  return c;
}

std::string clock_problem(double mhz) {
  if (mhz > 0 && std::isfinite(mhz)) return "";
  return mhz_text(mhz) + " is not a positive number of MHz";
}

DeviceClock given_clock(double mhz, const std::string& origin) {
  const std::string problem = clock_problem(mhz);
  if (!problem.empty()) throw std::invalid_argument(origin + ": " + problem);
  return DeviceClock{mhz, "given by " + origin, false};
}

}  // namespace voxcd
