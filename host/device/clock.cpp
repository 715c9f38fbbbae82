#include "voxcd/host/device/clock.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace voxcd {

std::string mhz_text(double mhz) {
  std::ostringstream s;
  s << mhz;
  return s.str();
}

std::string DeviceClock::text() const { return mhz_text(mhz) + " MHz (" + source + ")"; }

double DeviceClock::rate(double cycles) const { return cycles > 0 ? mhz * 1e6 / cycles : 0; }

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
