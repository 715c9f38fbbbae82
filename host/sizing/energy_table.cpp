#include "voxcd/host/sizing/energy_table.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "voxcd/host/detail/text_file.h"
#include "voxcd/host/detail/tsv.h"
#include "voxcd/host/device/timing_table.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {

// The text of host/sizing/energy.tsv, generated into the build (host/CMakeLists.txt).
extern const char* const kBuiltinEnergyTable;

namespace {

using detail::joined;
using detail::split_tabs;

const std::vector<std::string> kColumns = {
    "target",   "depth",       "mhz",          "scene",         "cycles",    "lookups",   "jobs",    "pairs",
    "internal_mw", "switching_mw", "leakage_mw", "logic_mw",    "sram_nj",   "pj_per_lookup", "logic_pj", "sram_pj",
    "nj_per_pair", "leakage_share", "pj_45nm",    "pj_16nm",     "pj_7nm",    "config"};
constexpr size_t kConfig = 21;  // the config column's index
constexpr const char* kEnergyTarget = "asic-osu018";

struct RowReader {
  const std::string& where;
  int line;
  const std::vector<std::string>& cells;
  EnergyTableError fail(size_t column, const std::string& what) const {
    return EnergyTableError(where + ":" + std::to_string(line) + ": " + kColumns[column] + ": '" + cells[column] +
                            "' " + what);
  }
  double number(size_t column) const {
    double v = 0;
    if (!detail::to_number(cells[column], &v) || v < 0) throw fail(column, "is not a number >= 0");
    return v;
  }
  double positive(size_t column) const {
    const double v = number(column);
    if (!(v > 0)) throw fail(column, "is not a positive number");
    return v;
  }
  int whole(size_t column) const {
    const double v = number(column);
    if (v != std::floor(v) || v > 1e6) throw fail(column, "is not a whole number from 0");
    return int(v);
  }
};

// The config column as a DeviceConfig at the row's depth.
DeviceConfig parse_config(const RowReader& r, int depth) {
  DeviceConfig c;
  try {
    c = parse_config_pairs(r.cells[kConfig], "config");
  } catch (const VectorError& e) {
    const std::string why = e.what();  // "config: unknown config parameter 'X'"
    throw r.fail(kConfig, "is not a configuration: " + (why.rfind("config: ", 0) == 0 ? why.substr(8) : why));
  }
  if (c.depth != 0 && c.depth != depth)
    throw r.fail(kConfig, "names DEPTH " + std::to_string(c.depth) + ", but the row is of depth " + std::to_string(depth));
  c.depth = depth;
  return c;
}

// Every figure column a number >= 0 (those the row keeps are read again by name).
void check_figures(const RowReader& r) {
  for (size_t column = 4; column < kConfig; ++column) r.number(column);
}

EnergyRow parse_row(const RowReader& r) {
  EnergyRow row;
  row.line = r.line;
  row.target = r.cells[0];
  const auto& targets = timing_targets();
  if (std::find(targets.begin(), targets.end(), row.target) == targets.end())
    throw r.fail(0, "is not a target (" + joined(targets) + ")");
  row.depth = r.whole(1);
  row.mhz = r.positive(2);
  row.scene = r.cells[3];
  if (row.scene.empty()) throw r.fail(3, "is empty (name the stimulus)");
  check_figures(r);
  row.lookups = r.positive(5);
  row.pj_per_lookup = r.positive(13);
  row.logic_pj = r.number(14), row.sram_pj = r.number(15);
  row.pj_45nm = r.number(18), row.pj_16nm = r.number(19), row.pj_7nm = r.number(20);
  row.config = r.cells[kConfig];
  row.device = parse_config(r, row.depth);
  return row;
}

EnergyTableError line_error(const std::string& where, int line, const std::string& what) {
  return EnergyTableError(where + ":" + std::to_string(line) + ": " + what);
}

// The row of one data line after the header (its column count checked).
EnergyRow data_row(const std::string& where, int line, const std::vector<std::string>& cells) {
  if (cells.size() != kColumns.size())
    throw line_error(where, line, std::to_string(cells.size()) + " tab-separated columns, expected " +
                                      std::to_string(kColumns.size()) + " (" + joined(kColumns) + ")");
  return parse_row(RowReader{where, line, cells});
}

}  // namespace

EnergyTable parse_energy_table(const std::string& text, const std::string& where) {
  EnergyTable t;
  t.where = where;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool header = false;
  std::set<std::tuple<std::string, std::string, std::string>> seen;  // target, configuration at its depth, scene
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> cells = split_tabs(line);
    if (!header) {
      if (cells != kColumns)
        throw line_error(where, number, "the header is '" + joined(cells) + "', expected the tab-separated columns '" +
                                            joined(kColumns) + "'");
      header = true;
      continue;
    }
    EnergyRow row = data_row(where, number, cells);
    if (!seen.insert({row.target, row.device.to_string(), row.scene}).second)
      throw line_error(where, number, row.target + " at depth " + std::to_string(row.depth) + " on the " + row.scene +
                                          " scene is given twice for one configuration (" + row.config + ")");
    t.rows.push_back(std::move(row));
  }
  if (!header) throw EnergyTableError(where + ": no header line (the columns '" + joined(kColumns) + "')");
  if (t.rows.empty()) throw EnergyTableError(where + ": no rows after the header");
  return t;
}

EnergyTable read_energy_table(const std::string& path) {
  const std::optional<std::string> text = detail::read_text_file(path);
  if (!text) throw EnergyTableError(path + ": cannot read");
  return parse_energy_table(*text, path);
}

const EnergyTable& builtin_energy_table() {
  static const EnergyTable t = parse_energy_table(kBuiltinEnergyTable, "host/sizing/energy.tsv (built in)");
  return t;
}

namespace {

// The kEnergyScene row of asic-osu018 nearest cfg (nullptr when there is none).
const EnergyRow* nearest_energy_row(const EnergyTable& table, const DeviceConfig& cfg) {
  const EnergyRow* best = nullptr;
  for (const EnergyRow& r : table.rows)
    if (r.target == kEnergyTarget && r.scene == kEnergyScene && (!best || nearer(r.device, best->device, cfg)))
      best = &r;
  return best;
}

// "581.02": a figure as the table writes it (six significant digits).
std::string pj_text(double pj) {
  std::ostringstream s;
  s << pj;
  return s.str();
}

}  // namespace

LookupEnergy lookup_energy(const DeviceConfig& cfg, const EnergyTable& table) {
  const EnergyRow* row = nearest_energy_row(table, cfg);
  if (!row)
    throw EnergyTableError(table.where + ": no " + kEnergyTarget + " row of the " + kEnergyScene +
                           " scene to take an energy per lookup from");
  const std::string measured = logic_text(row->device) + " (" + row->scene + " scene)";
  if (same_logic(row->device, cfg))
    return LookupEnergy{row->pj_per_lookup, row->pj_7nm, "measured for " + measured + ", docs/hardware.md", false};
  const std::string differs = logic_difference(cfg, row->device);
  return LookupEnergy{row->pj_per_lookup, row->pj_7nm,
                      "estimate: " + pj_text(row->pj_per_lookup) + " pJ a lookup measured for " + measured +
                          ", not for " + (differs.empty() ? logic_text(cfg) : differs) + ", docs/hardware.md",
                      true};
}

LookupEnergy lookup_energy(const DeviceConfig& cfg) { return lookup_energy(cfg, builtin_energy_table()); }

}  // namespace voxcd
