#include "voxcd/host/sizing/depth.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/sizing/detail/digits.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

namespace {

std::string ratio_text(double v) { return detail::digits_text(v, 3); }

bool offered(const DeviceConfig& base, int depth) {
  try {
    at_depth(base, depth);
    return true;
  } catch (const ConfigError&) {
    return false;
  }
}

}  // namespace

std::string DepthChoice::why() const {
  std::string s = "depth " + std::to_string(row.depth) + ": " + mhz_text(row.mhz) + " MHz >= " + mhz_text(clock_mhz);
  for (const TimingRow& r : shallower)
    s += "; depth " + std::to_string(r.depth) + ": " + mhz_text(r.mhz) + " MHz < " + mhz_text(clock_mhz);
  return s;
}

DepthChoice choose_depth(const TimingTable& table, const std::string& target, double clock_mhz,
                         const DeviceConfig& base) {
  return choose_depth(table, target, clock_mhz, [&base](int depth) { return offered(base, depth); });
}

DepthChoice choose_depth(const TimingTable& table, const std::string& target, double clock_mhz,
                         const std::function<bool(int)>& offered) {
  const auto& targets = timing_targets();
  if (std::find(targets.begin(), targets.end(), target) == targets.end()) {
    std::string list;
    for (const std::string& t : targets) list += (list.empty() ? "" : ", ") + t;
    throw std::invalid_argument("target '" + target + "' is not one of " + list);
  }
  if (!(clock_mhz > 0)) throw std::invalid_argument("the clock " + mhz_text(clock_mhz) + " is not a positive number of MHz");
  std::vector<TimingRow> rows;
  for (const TimingRow& r : table.target_rows(target))
    if (offered(r.depth)) rows.push_back(r);
  if (rows.empty())
    throw TimingTableError(table.where + ": no row for " + target + " at a depth this device offers");
  DepthChoice c;
  c.target = target;
  c.clock_mhz = clock_mhz;
  c.table = table.where;
  for (const TimingRow& r : rows) {
    if (r.mhz >= clock_mhz) {
      c.row = r;
      std::reverse(c.shallower.begin(), c.shallower.end());
      return c;
    }
    c.shallower.push_back(r);
  }
  const TimingRow& fastest = *std::max_element(
      rows.begin(), rows.end(), [](const TimingRow& a, const TimingRow& b) { return a.mhz < b.mhz; });
  throw SizeError("clock", clock_mhz / fastest.mhz,
                  "no depth meets " + mhz_text(clock_mhz) + " MHz on " + target + " (" + table.where +
                      "): the fastest is depth " + std::to_string(fastest.depth) + " at " + mhz_text(fastest.mhz) +
                      " MHz (" + fastest.source + "); " + mhz_text(clock_mhz) + " MHz is " +
                      ratio_text(clock_mhz / fastest.mhz) + " times faster");
}

int depth_of(const DeviceConfig& cfg) { return cfg.depth; }

DeviceConfig at_depth(const DeviceConfig& cfg, int depth) {
  DeviceConfig c = cfg;
  c.depth = depth;
  c.validate();  // ConfigError for a depth outside 0 .. kMaxDepth
  return c;
}

int latency_cycles(const DeviceConfig& cfg) { return 1 + pipeline_slots(cfg) + 1; }

}  // namespace voxcd
