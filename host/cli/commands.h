// Each subcommand of the voxcd tool adds itself to the application here.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "voxcd/host/device/clock.h"

namespace voxcd::cli {

// The clock a user gave with `option` (--clock), its source "given by --clock"; CLI::ValidationError naming the
// option for zero, negative, NaN or infinity.
inline DeviceClock clock_option(double mhz, const std::string& option) {
  const std::string problem = clock_problem(mhz);
  if (!problem.empty()) throw CLI::ValidationError(option, problem);
  return given_clock(mhz, option);
}

// What --clock's help says the default is: "the scene file's \"clock\", or the clock OpenSTA measured for the
// device's configuration (100.4 MHz for the default one), else an estimate from the nearest one measured, named as
// such (docs/hardware.md, \"The default clock\")".
inline std::string default_clock_help(const std::string& device = "the device's configuration") {
  return "the scene file's \"clock\", or the clock OpenSTA measured for " + device + " (" +
         mhz_text(default_device_clock().mhz) +
         " MHz for the default one), else an estimate from the nearest one measured, named as such (docs/hardware.md, "
         "\"The default clock\")";
}

// The deprecated spellings a run's scene file or options used (RunConfig::notes), one line each on stderr, as
// "voxcd COMMAND: NOTE".
template <class Config>
void print_notes(const Config& c, const char* command) {
  for (const std::string& note : c.notes) std::fprintf(stderr, "voxcd %s: %s\n", command, note.c_str());
}

// Names as a help text lists them: "cpu, ref, rtl".
inline std::string comma_list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The process exit code a subcommand's callback sets (0 by default).
int& exit_code();

void add_conform(CLI::App& app);
void add_selftest(CLI::App& app);
void add_voxelize(CLI::App& app);
void add_info(CLI::App& app);
void add_pair(CLI::App& app);
void add_simulate(CLI::App& app);
void add_size(CLI::App& app);
void add_regress(CLI::App& app);
void add_sweep(CLI::App& app);
void add_view(CLI::App& app);

}  // namespace voxcd::cli
