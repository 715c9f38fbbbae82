#include "voxcd/host/sizing/depth.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/sizing/digits.h"
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

// The lanes and banks a row was measured at, and their text ("LANES 4", "LANES 16 BANKS 4").
using LanesBanks = std::pair<int, int>;
LanesBanks lanes_banks(const DeviceConfig& c) { return {c.LANES, c.BANKS}; }
std::string lanes_banks_text(LanesBanks g) {
  return "LANES " + std::to_string(g.first) + (g.second ? " BANKS " + std::to_string(g.second) : "");
}

void check_request(const std::string& target, double clock_mhz) {
  const auto& targets = timing_targets();
  if (std::find(targets.begin(), targets.end(), target) == targets.end()) {
    std::string list;
    for (const std::string& t : targets) list += (list.empty() ? "" : ", ") + t;
    throw std::invalid_argument("target '" + target + "' is not one of " + list);
  }
  if (!(clock_mhz > 0)) throw std::invalid_argument("the clock " + mhz_text(clock_mhz) + " is not a positive number of MHz");
}

// The target's rows at `at` of the depths offered, by ascending depth: one a depth, the nearest base's.
std::vector<TimingRow> rows_at(const TimingTable& table, const std::string& target, LanesBanks at,
                               const DeviceConfig& base, const std::function<bool(int)>& offered) {
  TimingTable candidates{table.where, {}};
  for (const TimingRow& r : table.target_rows(target))
    if (lanes_banks(r.device) == at && offered(r.depth)) candidates.rows.push_back(r);
  std::vector<TimingRow> out;
  for (const TimingRow& r : candidates.rows) {
    if (!out.empty() && out.back().depth == r.depth) continue;
    DeviceConfig wanted = base;
    wanted.depth = r.depth;
    out.push_back(*nearest_row(candidates, target, wanted));  // at r's depth: nearest_row weighs the depth first
  }
  return out;
}

// The rows to choose from (rows_at): base's LANES and BANKS, else LANES 4 BANKS 0, else the target's first row's;
// `stand_in` says which when they are not base's.
std::vector<TimingRow> measured_rows(const TimingTable& table, const std::string& target, const DeviceConfig& base,
                                     const std::function<bool(int)>& offered, std::string* stand_in) {
  std::vector<LanesBanks> order = {lanes_banks(base), LanesBanks{DeviceConfig{}.LANES, 0}};
  for (const TimingRow& r : table.rows)
    if (r.target == target) {
      order.push_back(lanes_banks(r.device));
      break;
    }
  for (const LanesBanks& at : order) {
    std::vector<TimingRow> rows = rows_at(table, target, at, base, offered);
    if (rows.empty()) continue;
    if (at != lanes_banks(base))
      *stand_in = "the clocks of " + lanes_banks_text(at) + ", none measured at " + lanes_banks_text(lanes_banks(base));
    return rows;
  }
  throw TimingTableError(table.where + ": no row for " + target + " at a depth this device offers");
}

// The shallowest of `rows` (ascending depth) that meets the clock; SizeError "clock" naming the fastest otherwise.
DepthChoice shallowest(DepthChoice c, const std::vector<TimingRow>& rows) {
  for (const TimingRow& r : rows) {
    if (r.mhz >= c.clock_mhz) {
      c.row = r;
      std::reverse(c.shallower.begin(), c.shallower.end());
      return c;
    }
    c.shallower.push_back(r);
  }
  const TimingRow& fastest = *std::max_element(
      rows.begin(), rows.end(), [](const TimingRow& a, const TimingRow& b) { return a.mhz < b.mhz; });
  throw SizeError("clock", c.clock_mhz / fastest.mhz,
                  "no depth meets " + mhz_text(c.clock_mhz) + " MHz on " + c.target + " (" + c.table +
                      "): the fastest is depth " + std::to_string(fastest.depth) + " at " + mhz_text(fastest.mhz) +
                      " MHz (" + fastest.source + (c.stand_in.empty() ? "" : "; " + c.stand_in) + "); " +
                      mhz_text(c.clock_mhz) + " MHz is " + ratio_text(c.clock_mhz / fastest.mhz) + " times faster");
}

DepthChoice choose(const TimingTable& table, const std::string& target, double clock_mhz, const DeviceConfig& base,
                   const std::function<bool(int)>& offered) {
  check_request(target, clock_mhz);
  DepthChoice c;
  c.target = target;
  c.clock_mhz = clock_mhz;
  c.table = table.where;
  const std::vector<TimingRow> rows = measured_rows(table, target, base, offered, &c.stand_in);
  return shallowest(c, rows);
}

}  // namespace

std::string DepthChoice::why() const {
  std::string s = "depth " + std::to_string(row.depth) + ": " + mhz_text(row.mhz) + " MHz >= " + mhz_text(clock_mhz);
  for (const TimingRow& r : shallower)
    s += "; depth " + std::to_string(r.depth) + ": " + mhz_text(r.mhz) + " MHz < " + mhz_text(clock_mhz);
  return stand_in.empty() ? s : s + "; " + stand_in;
}

DepthChoice choose_depth(const TimingTable& table, const std::string& target, double clock_mhz,
                         const DeviceConfig& base) {
  return choose(table, target, clock_mhz, base, [&base](int depth) { return offered(base, depth); });
}

DepthChoice choose_depth(const TimingTable& table, const std::string& target, double clock_mhz,
                         const std::function<bool(int)>& offered) {
  return choose(table, target, clock_mhz, DeviceConfig{}, offered);
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
