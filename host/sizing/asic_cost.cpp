#include "voxcd/host/sizing/asic_cost.h"

#include <cmath>
#include <filesystem>
#include <regex>
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
         << "blackbox $paramod*voxcd_ram; " << asic_synth_commands() << "; dfflibmap -liberty " << lib
         << "; abc -liberty " << lib << " -D " << std::lround(1e6 / clock_mhz) << " -script \"" << kAbcScript
         << "\"; opt_clean -purge; tee -q -o area.txt stat -liberty " << lib;
  const detail::YosysRun run = detail::run_yosys(dir.empty() ? rtl_dir() : dir, script.str(), "area.txt",
                                                 {{"kogge_stone.v", kogge_stone_map()}});
  AsicCost c;
  c.command = run.command;
  c.seconds = run.seconds;
  c.clock_mhz = clock_mhz;
  std::smatch m;
  if (!std::regex_search(run.output, m, std::regex(R"(Chip area for module '\\voxcd_device': ([0-9.]+))")))
    throw std::runtime_error("yosys: its statistics name no chip area:\n" + run.output.substr(0, 2000));
  c.area_mm2 = std::stod(m[1].str()) / 1e6;  // the liberty's areas are square micrometres
  const std::regex cell(R"(\n\s+([A-Z][A-Z0-9]*X[0-9]+|DFFSR|LATCH|FAX1|HAX1)\s+([0-9]+))");
  for (auto it = std::sregex_iterator(run.output.begin(), run.output.end(), cell); it != std::sregex_iterator(); ++it) {
    const uint64_t n = std::stoull((*it)[2].str());
    c.cells += n;
    if ((*it)[1].str().rfind("DFF", 0) == 0) c.flip_flops += n;
  }
  c.version = detail::yosys_version();
  return c;
}

}  // namespace voxcd
