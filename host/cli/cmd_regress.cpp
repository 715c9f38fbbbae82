// voxcd regress: a conformance campaign (seeds x configurations x lane counts x backends) sharded over the ranks
// of an MPI run, with a results file that lets a stopped campaign resume, and one merged report.
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/mpi/campaign_run.h"
#include "voxcd/host/mpi/world.h"
#include "voxcd/host/package/paths.h"
#include "voxcd/host/regress/campaign.h"
#include "voxcd/host/regress/coverage.h"

namespace voxcd::cli {

namespace {

struct RegressArgs {
  std::string campaign;
  std::string seeds;
  std::string configs = "default";
  std::string lanes = "4";
  std::string backends = "cpu";
  uint64_t jobs = 200;
  bool cycles = false;
  mpi::RunOptions run;
  std::string waivers;  // "" = rtl/coverage.waivers beside the RTL
  std::string aim;      // stimulus bins, separated by ','
  bool aim_at_holes = false;
  double stall = 0.0;
  bool json = false;
};

// This program's path, for the reproduce commands.
std::string program_path() {
  char buf[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  return n > 0 ? std::string(buf, size_t(n)) : std::string("voxcd");
}

// The campaign from --campaign or from the lists; CampaignError or CLI::ValidationError.
Campaign make_campaign(const RegressArgs& a, const CLI::App& cmd) {
  if (!a.campaign.empty()) {
    for (const char* o : {"--seeds", "--configs", "--lanes", "--backends", "--jobs-per-shard", "--cycles", "--aim",
                          "--stall"})
      if (cmd.count(o)) throw CLI::ValidationError(std::string(o) + " cannot be given with --campaign (the file "
                                                   "holds the whole campaign)");
    return read_campaign_file(a.campaign);
  }
  if (a.seeds.empty()) throw CLI::ValidationError("regress needs --seeds LIST or --campaign FILE");
  Campaign c = campaign_from_lists(a.seeds, a.configs, a.lanes, a.backends, a.jobs, a.cycles);
  c.aim = parse_aim(a.aim, "--aim");
  c.stall = a.stall;
  validate_campaign(c, "the command line");
  return c;
}

// --aim-at-holes: the campaign also aims at the stimulus bins the coverage directory's last report left empty.
void aim_at_holes(const RegressArgs& a, Campaign& c) {
  if (!a.aim_at_holes) return;
  if (a.run.coverage.empty()) throw CLI::ValidationError("--aim-at-holes needs --coverage DIR (its last report)");
  const std::string bins = a.run.coverage + "/bins.txt";
  const std::vector<std::string> holes = aimable_holes(bins);
  for (const std::string& h : holes)
    if (std::find(c.aim.begin(), c.aim.end(), h) == c.aim.end()) c.aim.push_back(h);
  validate_campaign(c, "--aim-at-holes (" + bins + ")");
}

// --coverage needs the rtl backend, and its directory made (every rank writes there).
void check_coverage(const RegressArgs& a, const Campaign& c) {
  if (a.run.coverage.empty()) return;
  if (std::find(c.backends.begin(), c.backends.end(), "rtl") == c.backends.end())
    throw CLI::ValidationError("--coverage counts the coverage of the RTL: the campaign needs the rtl backend");
  std::error_code ec;
  std::filesystem::create_directories(a.run.coverage, ec);
  if (ec) throw CLI::ValidationError("--coverage: cannot make the directory " + a.run.coverage + ": " + ec.message());
}

// The merged coverage of the run's directory, printed after the campaign's report (docs/verification.md).
void report_coverage(const RegressArgs& a) {
  const std::string waivers = !a.waivers.empty() ? a.waivers : rtl_dir() + "/coverage.waivers";
  const CoverageReport cov = merge_coverage(a.run.coverage, waivers);
  std::cout << cov.text() << std::flush;
}

// A coverage campaign runs every rtl shard on the coverage models: the rtl backend is ready when their module is
// (a build may have them without the ordinary models, as bench/coverage.sh's does).
void use_coverage_module(const RegressArgs& a) {
  if (a.run.coverage.empty()) return;
  try {
    ::setenv("VOXCD_RTL_MODULE", rtl_module_path(true).c_str(), 1);
  } catch (const std::runtime_error&) {
    // No coverage module: the first shard says so, with how to build it.
  }
}

int regress(const RegressArgs& a, const CLI::App& cmd) {
  use_coverage_module(a);
  mpi::World world;
  if (world.rank() != 0) {
    mpi::serve(world, a.run.shard());
    return 0;
  }
  // --coverage DIR alone: merge and report what DIR holds (the counts of earlier campaigns, the AXI tests', a team's).
  if (!a.run.coverage.empty() && a.campaign.empty() && a.seeds.empty()) {
    mpi::release_workers(world);
    report_coverage(a);
    return 0;
  }
  Campaign c;
  try {
    if (!(a.run.timeout > 0)) throw CLI::ValidationError("--timeout must be more than 0 seconds");
    c = make_campaign(a, cmd);
    aim_at_holes(a, c);
    check_coverage(a, c);
  } catch (...) {
    mpi::release_workers(world);
    throw;
  }
  if (!c.aim.empty()) {
    std::cout << "aiming every second job at " << c.aim.size() << " stimulus bins:";
    for (const std::string& b : c.aim) std::cout << ' ' << b;
    std::cout << '\n';
  }
  const Report r = mpi::coordinate(world, c, a.run);
  const std::string program = program_path();
  std::cout << (a.json ? r.json(program) + "\n" : r.text(program)) << std::flush;
  if (!a.run.coverage.empty()) report_coverage(a);
  if (r.failures() > 0) return 1;
  return r.complete() ? 0 : 3;
}

}  // namespace

void add_regress(CLI::App& app) {
  auto a = std::make_shared<RegressArgs>();
  CLI::App* c = app.add_subcommand("regress", "Run a conformance campaign (seeds x configs x lanes x backends) "
                                              "sharded over MPI ranks, resumable from a results file "
                                              "(docs/regress.md)");
  c->add_option("--campaign", a->campaign, "Campaign file (JSON; instead of the lists below)");
  c->add_option("--seeds", a->seeds, "Seeds, e.g. 1-16 or 1,5,9 or 1-4,10");
  c->add_option("--configs", a->configs, "Configurations separated by ';', each NAME VALUE pairs or default, e.g. "
                                         "\"default;SB 8 WB 8\"")->capture_default_str();
  c->add_option("--lanes", a->lanes, "Lane counts, e.g. 1,2,4")->capture_default_str();
  c->add_option("--backends", a->backends, "Backends, e.g. rtl,cpu")->capture_default_str();
  c->add_option("--jobs-per-shard", a->jobs, "Random jobs per shard")->capture_default_str();
  c->add_flag("--cycles", a->cycles, "Also compare the cycles of every completion record");
  c->add_option("--results", a->run.results, "Results file (JSON lines): finished shards are kept and not run again");
  c->add_option("--timeout", a->run.timeout, "Seconds a rank may take over one shard before the run ends with an "
                                             "error")->capture_default_str();
  c->add_option("--stop-after", a->run.stop_after, "Run at most K shards now, then report (resume with --results)");
  c->add_option("--threads", a->run.threads, "cpu backend threads per rank (0 = one per hardware thread)")
      ->capture_default_str();
  c->add_option("--stall", a->stall, "rtl: probability that each output stream's consumer is not ready in a "
                                         "cycle (random back-pressure; cycles compared net of stalls)")
      ->capture_default_str();
  c->add_option("--coverage", a->run.coverage, "rtl: run on the coverage models, write every shard's counts into "
                                               "DIR and print the merged line, branch, toggle and functional "
                                               "coverage (docs/verification.md)");
  c->add_option("--waivers", a->waivers, "Coverage waivers (default: coverage.waivers beside the RTL)");
  c->add_option("--aim", a->aim, "Stimulus bins every second job of a shard aims at, separated by ',' "
                                 "(coverage-directed stimulus)");
  c->add_flag("--aim-at-holes", a->aim_at_holes, "Also aim at the stimulus bins --coverage DIR's last report left "
                                                 "empty (DIR/bins.txt)");
  c->add_flag("--json", a->json, "Print the report as JSON");
  c->callback([a, c] { exit_code() = regress(*a, *c); });
}

}  // namespace voxcd::cli
