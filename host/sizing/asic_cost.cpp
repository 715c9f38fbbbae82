#include "voxcd/host/sizing/asic_cost.h"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "voxcd/host/package/paths.h"
#include "voxcd/host/sizing/detail/yosys_run.h"

namespace voxcd {

// host/sizing/kogge_stone.v, generated into the build (host/CMakeLists.txt).
extern const char* const kKoggeStoneMap;

namespace {

// ABC_SCRIPT of bench/timing.sh: ABC's mapping for the clock ({D}) with buffering and gate sizing; commas are blanks.
const char* const kAbcScript =
    "+strash;&get,-n;&fraig,-x;&put;dc2;strash;&get,-n;&dch,-f;&nf,{D};&put;buffer,-N,12;upsize,{D};dnsize,{D};stime,-p";

// The chip area yosys's `stat -liberty` prints for the top module, in the liberty's units (square micrometres).
double chip_area_um2(const std::string& out) {
  const std::string key = "Chip area for module '\\voxcd_device': ";
  const size_t at = out.find(key);
  if (at == std::string::npos)
    throw std::runtime_error("yosys: its statistics name no chip area:\n" + out.substr(0, 2000));
  return std::stod(out.substr(at + key.size()));
}

// A standard cell of the OSU library in a `stat` line: a drive-strength name (NAND2X1, DFFPOSX1) or one of the few
// without one.
bool is_cell_name(const std::string& w) {
  if (w == "DFFSR" || w == "LATCH" || w == "FAX1" || w == "HAX1") return true;
  if (w.empty() || w[0] < 'A' || w[0] > 'Z') return false;
  const size_t x = w.rfind('X');
  if (x == std::string::npos || x == 0 || x + 1 == w.size()) return false;
  for (size_t i = 0; i < w.size(); ++i) {
    const char ch = w[i];
    const bool digit = ch >= '0' && ch <= '9';
    if (i > x ? !digit : !(digit || (ch >= 'A' && ch <= 'Z'))) return false;
  }
  return true;
}

// Adds every "<cell> <count>" line of the statistics to c.cells, the flip-flops to c.flip_flops as well.
void count_cells(const std::string& out, AsicCost& c) {
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string name, count;
    if (!(words >> name >> count) || !is_cell_name(name)) continue;
    if (count.find_first_not_of("0123456789") != std::string::npos) continue;
    const uint64_t n = std::stoull(count);
    c.cells += n;
    if (name.rfind("DFF", 0) == 0) c.flip_flops += n;
  }
}

}  // namespace

const char* kogge_stone_map() { return kKoggeStoneMap; }

std::string asic_synth_commands() {
  return "synth -top voxcd_device -flatten -run begin:fine; opt -fast -full; memory_map; opt -full; "
         "techmap -map +/techmap.v -map kogge_stone.v; opt -fast; abc -fast; opt -fast; "
         "synth -top voxcd_device -run check:";
}

AsicCost asic_cost(const DeviceConfig& cfg, double clock_mhz, const std::string& dir) {
  if (!std::filesystem::exists(kOsu018Liberty))
    throw std::runtime_error(std::string("the OSU 0.18 um cells (") + kOsu018Liberty +
                             ") are missing: install the Debian package qflow-tech-osu018");
  if (!(clock_mhz > 0)) throw std::invalid_argument("asic_cost: the clock is not a positive number of MHz");
  const std::string lib = kOsu018Liberty;
  std::ostringstream script;
  script << detail::chparam_device(cfg) << "; hierarchy -top voxcd_device; proc; rename -top voxcd_device; "
         << "blackbox $paramod*voxcd_ram $paramod*voxcd_ram2; " << asic_synth_commands()
         << "; dfflibmap -liberty " << lib << "; abc -liberty " << lib << " -D " << std::lround(1e6 / clock_mhz) << " -script \"" << kAbcScript
         << "\"; opt_clean -purge; tee -q -o area.txt stat -liberty " << lib;
  const detail::YosysRun run = detail::run_yosys(dir.empty() ? rtl_dir() : dir, script.str(), "area.txt",
                                                 {{"kogge_stone.v", kogge_stone_map()}});
  AsicCost c;
  c.command = run.command;
  c.seconds = run.seconds;
  c.clock_mhz = clock_mhz;
  c.area_mm2 = chip_area_um2(run.output) / 1e6;  // the liberty's areas are square micrometres
  count_cells(run.output, c);
  c.version = detail::yosys_version();
  return c;
}

}  // namespace voxcd
