// voxcd: the command-line tool. One binary, one subcommand per job.
#include <exception>
#include <iostream>

#include "host/cli/commands.h"

namespace voxcd::cli {
int& exit_code() {
  static int code = 0;
  return code;
}
}  // namespace voxcd::cli

int main(int argc, char** argv) {
  CLI::App app{"voxcd: voxel collision detection on a modelled point-lookup accelerator"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Print help for every subcommand");
  voxcd::cli::add_conform(app);
  voxcd::cli::add_selftest(app);
  voxcd::cli::add_voxelize(app);
  voxcd::cli::add_info(app);
  voxcd::cli::add_pair(app);
  voxcd::cli::add_simulate(app);
  voxcd::cli::add_size(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "voxcd: error: " << e.what() << '\n';
    return 2;
  }
  return voxcd::cli::exit_code();
}
