// voxcd conform: run conformance vector files on a backend and compare, print the backend's stream, or generate
// random vectors with expectations from ref/.
#include <iostream>
#include <optional>
#include <sstream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/device/conform.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/regress/campaign.h"
#include "voxcd/ref/vectors.h"

namespace voxcd::cli {

namespace {

struct ConformArgs {
  std::vector<std::string> files;
  ConformOptions run;  // the backend and the device model's settings, for every file
  bool print = false;
  bool generate = false;
  uint64_t seed = 1;
  size_t jobs = 200;
  size_t cloud = 2000;
  std::string output;
  std::string config;
  std::string aim;  // stimulus bins separated by ','
};

int generate(const ConformArgs& a) {
  if (a.output.empty()) throw CLI::ValidationError("--generate needs -o FILE");
  GenerateOptions g;
  g.seed = a.seed;
  g.jobs = a.jobs;
  g.cloud_points = a.cloud;
  g.aim = parse_aim(a.aim, "--aim");
  if (!a.config.empty()) g.config = parse_config_pairs(a.config, "--config");
  if (a.run.lanes) g.config.LANES = *a.run.lanes;
  if (a.run.banks) g.config.BANKS = *a.run.banks;
  if (a.run.depth) g.config.depth = *a.run.depth;
  const GeneratedFile w = write_generated_vectors(a.output, g, a.config);
  std::cout << "wrote " << a.output << ": " << w.jobs << " jobs, " << w.shell_words << " shell words, " << w.map_words
            << " map words, " << w.lookups << " lookups, seed " << a.seed << '\n';
  return 0;
}

// Runs one file; returns "" on success or the reason it failed.
std::string run_file(const ConformArgs& a, const std::string& path, std::ostream& print_to) {
  const ConformResult r = run_conformance(path, a.run, !a.print);
  if (!r.ok() || !a.print) return r.error;
  print_to << "# " << path << " on " << a.run.backend << '\n';
  std::string buf;
  for (const Record& rec : r.stream) {
    buf = rec.to_string(r.version >= 2);
    buf += '\n';
    print_to << buf;
  }
  return "";
}

int conform(const ConformArgs& a) {
  if (a.generate) return generate(a);
  if (a.files.empty()) throw CLI::ValidationError("conform needs FILE... (or --generate)");
  size_t passed = 0, failed = 0;
  for (const std::string& path : a.files) {
    const std::string err = run_file(a, path, std::cout);
    if (err.empty()) {
      ++passed;
      if (!a.print) std::cout << "ok   " << path << '\n';
    } else {
      ++failed;
      std::cout << "FAIL " << err << '\n';
    }
  }
  (a.print ? std::cerr : std::cout) << passed << " passed, " << failed << " failed" << std::endl;
  return failed ? 1 : 0;
}

}  // namespace

void add_conform(CLI::App& app) {
  auto a = std::make_shared<ConformArgs>();
  CLI::App* c = app.add_subcommand("conform", "Run conformance vector files on a backend and compare with their "
                                              "expectations (docs/conformance.md), or generate vectors");
  c->add_option("files", a->files, "Vector files");
  c->add_option("--backend", a->run.backend, "Backend: " + comma_list(backend_names()))->capture_default_str();
  c->add_option("--lanes", a->run.lanes, "Lanes of the device model (default: the file's LANES)")
      ->check(CLI::Range(1, 64));
  c->add_option("--banks", a->run.banks,
                "Shared voxmap banks of the device model (0: a copy per lane; default: the file's BANKS)")
      ->check(CLI::Range(0, 64));
  c->add_option("--depth", a->run.depth,
                "Pipeline depth of the device model: register stages added to every lane, 0.." +
                    std::to_string(kMaxDepth) + " (default: the file's DEPTH, or 0)")
      ->check(CLI::Range(0, kMaxDepth));
  c->add_flag("--cycles", a->run.cycles, "Also compare the cycles of every completion record");
  c->add_flag("--print", a->print, "Print the backend's own output stream instead of comparing");
  c->add_option("--trace", a->run.trace, "rtl: write an FST waveform to this file");
  c->add_option("--stall", a->run.stall, "rtl: probability that each output stream's consumer is not ready in a "
                                         "cycle (random back-pressure; --cycles then compares cycles net of stalls)")
      ->check(CLI::Range(0.0, 0.99));
  c->add_option("--stall-seed", a->run.stall_seed, "rtl: seed of the back-pressure")->capture_default_str();
  c->add_option("--coverage", a->run.coverage, "rtl: run on the coverage models and write their counts to this "
                                               "file (docs/verification.md)");
  c->add_flag("--generate", a->generate, "Generate random vectors with expectations from ref (needs -o)");
  c->add_option("--seed", a->seed, "Random seed for --generate")->capture_default_str();
  c->add_option("--jobs", a->jobs, "Number of jobs for --generate")->capture_default_str();
  c->add_option("--cloud-points", a->cloud, "Points in the random cloud block of the shell for --generate")
      ->capture_default_str();
  c->add_option("-o,--output", a->output, "Output file for --generate");
  c->add_option("--aim", a->aim, "Stimulus bins for --generate to aim every second job at, separated by ',' "
                                 "(coverage-directed stimulus, docs/verification.md)");
  c->add_option("--config", a->config,
                "Device configuration for --generate as NAME VALUE pairs, e.g. \"PW 20 PF 6 MW 16 MF 14\" "
                "(others default)");
  c->callback([a] { exit_code() = conform(*a); });
}

}  // namespace voxcd::cli
