// Each subcommand of the voxcd tool adds itself to the application here.
#pragma once

#include <CLI/CLI.hpp>

namespace voxcd::cli {

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

}  // namespace voxcd::cli
