// Each subcommand of the voxcd tool adds itself to the application here.
#pragma once

#include <CLI/CLI.hpp>
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
