#include "voxcd/host/device/timing_table.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "voxcd/host/detail/text_file.h"
#include "voxcd/host/detail/tsv.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {

// The text of host/device/timing.tsv, generated into the build (host/CMakeLists.txt).
extern const char* const kBuiltinTimingTable;

namespace {

const std::vector<std::string> kColumns = {"target", "depth", "mhz",   "source", "lanes",      "area_mm2",
                                           "luts",   "ffs",   "dsps",  "brams",  "lut_levels", "config"};

using detail::joined;
using detail::split_tabs;
using detail::to_number;

struct RowReader {
  const std::string& where;
  int line;
  const std::vector<std::string>& cells;
  TimingTableError fail(size_t column, const std::string& what) const {
    return TimingTableError(where + ":" + std::to_string(line) + ": " + kColumns[column] + ": '" + cells[column] +
                            "' " + what);
  }
  double number(size_t column) const {
    double v = 0;
    if (!to_number(cells[column], &v) || v < 0) throw fail(column, "is not a number >= 0");
    return v;
  }
  int whole(size_t column, int least) const {
    const double v = number(column);
    if (v != std::floor(v) || v < least || v > 1e6)
      throw fail(column, "is not a whole number from " + std::to_string(least));
    return int(v);
  }
  std::optional<double> figure(size_t column) const {
    if (cells[column] == "-") return std::nullopt;
    return number(column);
  }
};

// The config column as a DeviceConfig at the row's depth; its LANES must be the lanes column's.
DeviceConfig parse_config(const RowReader& r, const TimingRow& row) {
  DeviceConfig c;
  try {
    c = parse_config_pairs(r.cells[11], "config");
  } catch (const VectorError& e) {
    const std::string why = e.what();  // "config: unknown config parameter 'X'"
    throw r.fail(11, "is not a configuration: " + (why.rfind("config: ", 0) == 0 ? why.substr(8) : why));
  }
  if (c.depth != 0 && c.depth != row.depth)
    throw r.fail(11, "names DEPTH " + std::to_string(c.depth) + ", but the row is of depth " + std::to_string(row.depth));
  if (c.LANES != row.lanes)
    throw r.fail(4, "is not the config's LANES " + std::to_string(c.LANES) + " (" + r.cells[11] + ")");
  c.depth = row.depth;
  return c;
}

TimingRow parse_row(const RowReader& r) {
  TimingRow row;
  row.line = r.line;
  row.target = r.cells[0];
  const auto& targets = timing_targets();
  if (std::find(targets.begin(), targets.end(), row.target) == targets.end())
    throw r.fail(0, "is not a target (" + joined(targets) + ")");
  row.depth = r.whole(1, 0);
  row.mhz = r.number(2);
  if (!(row.mhz > 0)) throw r.fail(2, "is not a positive number of MHz");
  row.source = r.cells[3];
  if (row.source.empty()) throw r.fail(3, "is empty (say how the clock was found)");
  row.lanes = r.whole(4, 1);
  row.area_mm2 = r.figure(5);
  row.luts = r.figure(6);
  row.ffs = r.figure(7);
  row.dsps = r.figure(8);
  row.brams = r.figure(9);
  if (r.cells[10] != "-") row.lut_levels = r.whole(10, 0);
  row.config = r.cells[11];
  row.device = parse_config(r, row);
  return row;
}

// The parameters that change logic, by name, LANES and DEPTH first, then in DeviceConfig::to_string's order; WB only
// on a distance device (elsewhere it is the default's).
std::vector<std::pair<const char*, int>> logic_params(const DeviceConfig& c) {
  return {{"LANES", c.LANES}, {"DEPTH", c.depth}, {"PW", c.PW},     {"PF", c.PF},     {"MW", c.MW},
          {"MF", c.MF},       {"TW", c.TW},       {"DW", c.DW},     {"MEMW", c.MEMW}, {"TAGW", c.TAGW},
          {"SB", c.SB},       {"WB", c.distance() ? c.WB : DeviceConfig{}.WB},          {"BANKS", c.BANKS},
          {"BL", c.BL},       {"TX", c.TX}};
}

// "NAME VALUE" of each of cfg's parameters that differs from `from`'s, but those named in `skip`.
std::string differences(const DeviceConfig& cfg, const DeviceConfig& from, const std::set<std::string>& skip = {}) {
  const auto a = logic_params(cfg), b = logic_params(from);
  std::string s;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].second != b[i].second && !skip.count(a[i].first))
      s += (s.empty() ? "" : " ") + std::string(a[i].first) + " " + std::to_string(a[i].second);
  return s;
}

// How far a measured configuration is from cfg, in the order nearest_row weighs it (smaller is nearer): its depth,
// LANES, BANKS, the other parameters, and whether it is the default configuration.
std::tuple<bool, bool, bool, bool, bool> remoteness(const DeviceConfig& measured, const DeviceConfig& cfg) {
  const bool others = !differences(measured, cfg, {"LANES", "BANKS", "DEPTH"}).empty();
  return {measured.depth != cfg.depth, measured.LANES != cfg.LANES, measured.BANKS != cfg.BANKS, others,
          !same_logic(measured, DeviceConfig{})};
}

}  // namespace

const std::vector<std::string>& timing_targets() {
  static const std::vector<std::string> t = {"asic-osu018", "ice40-hx8k", "ice40-up5k", "xilinx-7"};
  return t;
}

std::vector<TimingRow> TimingTable::target_rows(const std::string& target) const {
  std::vector<TimingRow> out;
  for (const TimingRow& r : rows)
    if (r.target == target) out.push_back(r);
  std::stable_sort(out.begin(), out.end(), [](const TimingRow& a, const TimingRow& b) { return a.depth < b.depth; });
  return out;
}

TimingTable parse_timing_table(const std::string& text, const std::string& where) {
  TimingTable t;
  t.where = where;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool header = false;
  std::set<std::pair<std::string, std::string>> seen;  // target, configuration at its depth
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split_tabs(line);
    if (!header) {
      if (cells != kColumns)
        throw TimingTableError(where + ":" + std::to_string(number) + ": the header is '" + joined(cells) +
                               "', expected the tab-separated columns '" + joined(kColumns) + "'");
      header = true;
      continue;
    }
    if (cells.size() != kColumns.size())
      throw TimingTableError(where + ":" + std::to_string(number) + ": " + std::to_string(cells.size()) +
                             " tab-separated columns, expected " + std::to_string(kColumns.size()) + " (" +
                             joined(kColumns) + ")");
    TimingRow row = parse_row(RowReader{where, number, cells});
    if (!seen.insert({row.target, row.device.to_string()}).second)
      throw TimingTableError(where + ":" + std::to_string(number) + ": " + row.target + " at depth " +
                             std::to_string(row.depth) + " is given twice for one configuration (" + row.config + ")");
    t.rows.push_back(std::move(row));
  }
  if (!header) throw TimingTableError(where + ": no header line (the columns '" + joined(kColumns) + "')");
  if (t.rows.empty()) throw TimingTableError(where + ": no rows after the header");
  return t;
}

TimingTable read_timing_table(const std::string& path) {
  const std::optional<std::string> text = detail::read_text_file(path);
  if (!text) throw TimingTableError(path + ": cannot read");
  return parse_timing_table(*text, path);
}

const TimingTable& builtin_timing_table() {
  static const TimingTable t = parse_timing_table(kBuiltinTimingTable, "host/device/timing.tsv (built in)");
  return t;
}

bool same_logic(const DeviceConfig& measured, const DeviceConfig& cfg) {
  return logic_params(measured) == logic_params(cfg);
}

bool nearer(const DeviceConfig& a, const DeviceConfig& b, const DeviceConfig& cfg) {
  return remoteness(a, cfg) < remoteness(b, cfg);
}

const TimingRow* nearest_row(const TimingTable& table, const std::string& target, const DeviceConfig& cfg) {
  const TimingRow* best = nullptr;
  for (const TimingRow& r : table.rows)
    if (r.target == target && (!best || nearer(r.device, best->device, cfg))) best = &r;
  return best;
}

std::string logic_text(const DeviceConfig& cfg) {
  const std::string rest = differences(cfg, DeviceConfig{}, {"LANES", "DEPTH"});
  return "LANES " + std::to_string(cfg.LANES) + " DEPTH " + std::to_string(cfg.depth) + (rest.empty() ? "" : " " + rest);
}

std::string logic_difference(const DeviceConfig& cfg, const DeviceConfig& from) { return differences(cfg, from); }

}  // namespace voxcd
