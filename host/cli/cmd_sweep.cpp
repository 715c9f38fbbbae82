// voxcd sweep: a design-space sweep of a scene file (lanes x depths x voxel scales x distance bits x accuracies), each point
// sized and measured as voxcd size does, sharded over MPI ranks with a results file that lets a stopped sweep
// resume; one table (text, CSV, JSON) with the Pareto front, and a plot. docs/sweep.md.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "voxcd/host/regress/testing_fault.h"
#include "voxcd/host/cli/commands.h"
#include "voxcd/host/mpi/work_run.h"
#include "voxcd/host/mpi/world.h"
#include "voxcd/host/sizing/sweep/sweep.h"
#include "voxcd/host/sizing/sweep/sweep_plot.h"
#include "voxcd/host/sizing/sweep/sweep_results.h"
#include "voxcd/host/sizing/sweep/sweep_table.h"

namespace voxcd::cli {

namespace {

struct SweepArgs {
  std::string scene, sweep_file;
  std::string lanes, depth, voxel_scale, distance_bits, accuracy;
  uint64_t frames = 0, sample_frames = 0;
  double clock = 0;
  bool cost = false;
  std::string rtl_dir = default_rtl_dir();
  std::string csv, plot, results;
  bool json = false;
  double timeout = 3600;
  uint64_t stop_after = 0;
};


std::vector<int> int_items(const std::string& text, const std::string& option) {
  std::vector<int> out;
  for (double v : parse_number_list(text, option)) {
    if (v != std::floor(v) || std::abs(v) > 1e6) throw SweepError(option + ": " + std::to_string(v) + " is not a whole number");
    out.push_back(int(v));
  }
  return out;
}

// The whole sweep: the sweep file's keys, the options over them, the scene file's values for what neither gives.
SweepSpec make_spec(const SweepArgs& a, const CLI::App& cmd) {
  SweepSpec s;
  s.scene = a.scene;
  s.sample_frames = 4;
  if (!a.sweep_file.empty()) s = read_sweep_file(a.sweep_file, s);
  if (cmd.count("--lanes")) s.lanes = int_items(a.lanes, "--lanes");
  if (cmd.count("--depth")) s.depths = int_items(a.depth, "--depth");
  if (cmd.count("--voxel-scale")) s.voxel_scales = parse_number_list(a.voxel_scale, "--voxel-scale");
  if (cmd.count("--distance-bits")) s.distance_bits = int_items(a.distance_bits, "--distance-bits");
  if (cmd.count("--accuracy")) s.accuracies = parse_number_list(a.accuracy, "--accuracy");
  if (cmd.count("--frames")) s.frames = a.frames;
  if (cmd.count("--sample-frames")) s.sample_frames = a.sample_frames;
  if (cmd.count("--clock")) {
    const DeviceClock c = clock_option(a.clock, "--clock");
    s.clock = c.mhz, s.clock_source = c.source;
  }
  if (a.cost) s.cost = true;
  s.rtl_dir = a.rtl_dir;
  const RunConfig f = read_scene_file(a.scene);
  print_notes(f, "sweep");
  if (s.lanes.empty()) s.lanes = {1, 2, 4};
  if (s.voxel_scales.empty()) s.voxel_scales = {1};
  if (s.distance_bits.empty()) s.distance_bits = {f.distance_bits};
  if (s.accuracies.empty()) s.accuracies = {f.accuracy > 0 ? f.accuracy : accuracy_or_default(f, make_scene(f))};
  if (s.frames == 0) s.frames = f.frames;
  // No clock given: each point's rate at its own configuration's clock (SweepRunner).
  if (!(s.clock > 0) && f.clock) s.clock = f.clock->mhz, s.clock_source = f.clock->source;
  check_sweep(s, a.sweep_file.empty() ? std::string("the sweep options") : a.sweep_file + " with the options");
  return s;
}

std::string describe(const SweepSpec& s, uint64_t i) { return "point " + std::to_string(i) + " (" + point_at(s, i).text() + ")"; }

mpi::RunItem runner_for(const SweepSpec& s, int rank) {
  auto runner = std::make_shared<SweepRunner>(s);
  return [runner, rank](uint64_t i) {
    testing_fault("POINT", i);
    SweepRow r = runner->run(i);
    r.rank = rank;
    return sweep_row_line(r);
  };
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw std::runtime_error(path + ": cannot write");
}

int sweep_cmd(const SweepArgs& a, const CLI::App& cmd) {
  mpi::World world;
  if (world.rank() != 0) {
    const int rank = world.rank();
    mpi::serve_work(world, [rank](const std::string& setup) {
      return runner_for(sweep_from_json(setup, "the sweep from rank 0"), rank);
    });
    return 0;
  }
  const auto start = std::chrono::steady_clock::now();
  SweepTable t;
  std::unique_ptr<SweepResults> results;
  mpi::RunItem run;
  try {
    if (!(a.timeout > 0)) throw CLI::ValidationError("--timeout must be more than 0 seconds");
    t.spec = make_spec(a, cmd);
    run = runner_for(t.spec, 0);
    if (!a.results.empty()) results = std::make_unique<SweepResults>(a.results, t.spec);
  } catch (...) {
    mpi::release_work(world);
    throw;
  }
  t.clock = t.spec.clock;
  t.frames = t.spec.frames;
  t.ranks = world.size();
  std::vector<bool> done(t.spec.points(), false);
  if (results)
    for (const SweepRow& r : results->finished()) t.rows.push_back(r), done[r.point.index] = true;
  t.from_file = t.rows.size();
  mpi::WorkPlan plan;
  plan.setup = sweep_json(t.spec);
  for (uint64_t i = 0; i < t.spec.points(); ++i)
    if (!done[i]) plan.todo.push_back(i);
  const SweepSpec& spec = t.spec;
  plan.describe = [&spec](uint64_t i) { return describe(spec, i); };
  plan.resume_hint = a.results.empty() ? "give --results FILE to keep finished points"
                                       : "every point finished before is in " + a.results + "; rerun with it to resume";
  plan.timeout = a.timeout;
  plan.stop_after = a.stop_after;
  mpi::coordinate_work(world, plan, run, [&](uint64_t item, const std::string& line, int rank) {
    SweepRow r = parse_sweep_row(line, "the result of rank " + std::to_string(rank));
    if (r.point.index != item)
      throw SweepError("the row of point " + std::to_string(r.point.index) + " came for " + describe(spec, item));
    if (results) results->append(r);
    t.rows.push_back(std::move(r));
  });
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  finish_table(t);
  if (!a.csv.empty()) write_text(a.csv, sweep_csv(t));
  std::string plotted;
  if (!a.plot.empty()) {
    const SweepPlot p = sweep_plot(t);
    write_png(a.plot, p.image);
    plotted = "plot " + a.plot + ": " + p.caption() + "\n";
  }
  std::cout << (a.json ? sweep_table_json(t) : sweep_text(t) + (a.csv.empty() ? "" : "table " + a.csv + " (CSV)\n") +
                                                  plotted)
            << std::flush;
  return t.rows.size() == t.spec.points() ? 0 : 3;
}

}  // namespace

void add_sweep(CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* c = app.add_subcommand(
      "sweep", "A design-space sweep of a scene file (lanes x depths x voxel scales x distance bits x accuracies): error, "
               "contact error (bound and measured), cycles, memory and cost per point, the Pareto front, sharded "
               "over MPI ranks and resumable (docs/sweep.md)");
  c->add_option("scene", a->scene, "A scene file (docs/scenes.md)")->required()->check(CLI::ExistingFile);
  c->add_option("--sweep", a->sweep_file, "Sweep file (JSON, docs/sweep.md); the options below override its keys")
      ->check(CLI::ExistingFile);
  c->add_option("--lanes", a->lanes, "Lane counts, powers of two (default 1,2,4)");
  c->add_option("--depth", a->depth,
                "Pipeline depths, the register stages added to the lanes (default 0; the timing table of "
                "docs/hardware.md gives each depth's clock)");
  c->add_option("--voxel-scale", a->voxel_scale, "Factors on every type's voxel (default 1)");
  c->add_option("--distance-bits", a->distance_bits,
                "0 (2-bit states) or 4, 8, 16 (distance voxmaps with the scene's band) (default: the scene file's)");
  c->add_option("--accuracy", a->accuracy, "Accuracies of the fixed-point path, world units, from which the widths "
                                           "are derived (default: the scene file's)");
  c->add_option("--frames", a->frames, "Frames measured per point (default: the scene file's)")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1000000}));
  c->add_option("--sample-frames", a->sample_frames,
                "Frames per point whose contacts are checked against the meshes (default 4)");
  c->add_option("--clock", a->clock,
                "Device clock, MHz, for the frame rate (default: " + default_clock_help("each point's configuration") + ")");
  c->add_flag("--cost", a->cost, "Also synthesise every point with yosys (synth_xilinx; 10 to 60 s a point)");
  c->add_option("--rtl", a->rtl_dir, "The directory of the RTL file list voxcd.f for --cost")->capture_default_str();
  c->add_option("--csv", a->csv, "Write the table as CSV to FILE");
  c->add_option("--plot", a->plot, "Draw contact error bound against cycles per frame, the front in red, to FILE.png");
  c->add_flag("--json", a->json, "Print the table as JSON");
  c->add_option("--results", a->results, "Results file (JSON lines): finished points are kept and not run again");
  c->add_option("--timeout", a->timeout, "Seconds a rank may take over one point before the run ends with an error")
      ->capture_default_str();
  c->add_option("--stop-after", a->stop_after, "Run at most K points now, then report (resume with --results)");
  c->callback([a, c] { exit_code() = sweep_cmd(*a, *c); });
}

}  // namespace voxcd::cli
