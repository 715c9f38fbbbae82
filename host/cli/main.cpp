// voxcd: the command-line tool. One binary, one subcommand per job.
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/device/device.h"
#include "voxcd/version.h"

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
  // The version, then which backends can run here: the device models are built on their own (docs/build.md).
  app.set_version_flag("--version", [] {
    std::string s = std::string("voxcd ") + VOXCD_VERSION + "\nbackends:";
    for (const voxcd::BackendStatus& b : voxcd::backend_status()) {
      s += "\n  " + b.name + std::string(10 - b.name.size(), ' ');
      s += b.ready ? "ready" : "not ready: " + b.why_not;
    }
    return s;
  });
  // The subcommands, in the order the help lists them.
  using namespace voxcd::cli;
  for (void (*add)(CLI::App&) : {add_conform, add_selftest, add_voxelize, add_info, add_pair, add_simulate, add_size,
                                 add_regress, add_sweep, add_view})
    add(app);
  // CLI11 reports a first word that is no subcommand only as a missing subcommand: name it, and the known ones.
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known |= sub->check_name(argv[1]);
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "voxcd: '" << argv[1] << "' is not a subcommand (the subcommands: " << names << ")\n"
                << "Run with --help or --help-all for more information.\n";
      return int(CLI::ExitCodes::RequiredError);
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    // One write, so that nothing another process writes to the same stream (an MPI launcher) lands inside it.
    const std::string line = std::string("voxcd: error: ") + e.what() + "\n";
    std::fwrite(line.data(), 1, line.size(), stderr);
    std::fflush(stderr);
    return 2;
  }
  return voxcd::cli::exit_code();
}
