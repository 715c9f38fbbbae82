// voxcd simulate: the paper's N-body environment (or a scene like it, or a scene file) for a number of frames, with
// a broadphase and pair tests on a device backend; a summary of rates, counts, time per stage and device cycles.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/mpi/frame_exchange.h"
#include "voxcd/host/mpi/world.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/report/json_text.h"
#include "voxcd/host/report/object_report.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/ref/vectors.h"

namespace voxcd::cli {

using report::Json;
using report::json_text;

namespace {

struct SimulateArgs {
  CLI::App* app = nullptr;
  // The options' values (options.where: a scene file, docs/scenes.md); those given override the file (run_config).
  RunConfig options;
  std::string config;  // a whole device configuration, "NAME VALUE" pairs
  std::string mode = "ALL";
  std::string storage = "dense";  // --storage, parsed into options.storage when given
  std::string pruning;            // --pruning: --broadphase's deprecated spelling
  double clock_mhz = 0;  // --clock; unset: the scene file's "clock", or the run's device configuration's (run_clock)
  bool json = false;
  bool progress = true;
  double mpi_timeout = 300;  // seconds a rank waits for a frame's messages
};

// Each option that sets a setting of the run: the option, the setting's field (RunConfig::given), and its name in
// messages (Python's keyword).
struct RunOption {
  const char* option;
  const char* field;
  const char* name;
};
constexpr RunOption kRunOptions[] = {
    {"--objects", "types[0].count", "objects"}, {"--shape", "types[0].shape", "shape"},
    {"--voxel", "types[0].voxel", "voxel"},     {"--resolution", "types[0].resolution", "resolution"},
    {"--density", "density", "density"},        {"--speed", "speed", "speed"},
    {"--seed", "seed", "seed"},                 {"--broadphase", "broadphase", "broadphase"},
    {"--backend", "backend", "backend"},        {"--mode", "mode", "mode"},
    {"--both", "both_directions", "both"},      {"--frames", "frames", "frames"},
    {"--clock", "clock", "clock"},              {"--lanes", "lanes", "lanes"},
    {"--distance-bits", "distance_bits", "distance_bits"}, {"--band", "band", "band"},
    {"--margin", "margin", "margin"},           {"--ccd", "ccd", "ccd"},
    {"--storage", "storage", "storage"},
};

// --pruning, --broadphase's spelling before it was named as everywhere else: the same setting, with a note. Given
// with --broadphase, it must name the same broadphase.
void deprecated_pruning(const SimulateArgs& a, RunConfig& o) {
  if (a.app->count("--pruning") == 0) return;
  if (a.app->count("--broadphase") > 0 && a.pruning != o.broadphase)
    throw CLI::ValidationError("--pruning", "is --broadphase's deprecated spelling, and names '" + a.pruning +
                                                "' where --broadphase names '" + o.broadphase + "'");
  o.broadphase = a.pruning;
  o.given["broadphase"] = SettingSource{"", "broadphase"};
  o.notes.push_back("--pruning is deprecated: use --broadphase (the same option; docs/scenes.md, \"Deprecated "
                    "spellings\")");
}

// The options given, as the settings they override (the others take the scene file's values or the defaults).
RunConfig options_given(const SimulateArgs& a) {
  RunConfig o = a.options;
  for (const RunOption& r : kRunOptions)
    if (a.app->count(r.option) > 0) o.given[r.field] = SettingSource{"", r.name};
  deprecated_pruning(a, o);
  if (o.given.count("mode")) o.mode = mode_option(a.mode);
  if (o.given.count("storage")) o.storage = *parse_storage(a.storage);
  if (o.given.count("clock")) o.clock = clock_option(a.clock_mhz, "--clock");
  if (!a.config.empty()) {
    o.device = parse_config_pairs(a.config, "--config");
    o.given["device"] = SettingSource{"", "config"};
  }
  return o;
}

// The summary's scene and settings: a scene file's types, the device, the (first) type's shape and voxmap, and how
// the run went (broadphase, backend, mode, directions, distance fields, frames, seed).
Json settings_json(const SimulationSummary& s) {
  const RunConfig& c = s.config;
  const ObjectType& type = *s.types[0];
  const auto& d = type.voxmap().dims();
  Json j = Json::object();
  if (!c.builtin()) {
    j["scene"] = c.where;
    j["types"] = Json::array();
    for (const auto& t : s.types)
      j["types"].push_back({{"name", t->name}, {"voxel", t->voxmap().voxel()}, {"shell_count", t->shell().size()},
                            {"shell_points", t->shell().size()}});
  }
  // shell_points and pruning: shell_count's and broadphase's spellings before one vocabulary, kept for one release
  // (docs/scenes.md, "Deprecated spellings").
  j.update({{"device", s.device.to_string()}, {"shape", s.shape()}, {"objects", c.objects()}, {"voxel", s.voxel()},
            {"shell_count", type.shell().size()}, {"shell_points", type.shell().size()},
            {"voxmap", {d[0], d[1], d[2]}}, {"broadphase", c.broadphase}, {"pruning", c.broadphase},
            {"backend", c.backend}, {"mode", mode_name(c.mode)}, {"both_directions", c.both_directions}});
  if (s.distance_bits())
    j.update({{"distance_bits", s.distance_bits()}, {"band", c.band}, {"margin", c.margin}, {"ccd", c.ccd}});
  if (c.storage != ObjectStorage::kDense) j.update({{"storage", storage_name(c.storage)}, {"bl", s.device.BL}});
  j.update({{"frames", c.frames}, {"seed", c.seed}});
  return j;
}

// The totals into j: time, frame rate, the counts, the time per stage, continuous collision's counts, and the
// ranks of a distributed run (`exchanged`: bytes rank 0 sent and received).
void add_totals_json(Json& j, const SimulationSummary& s, double exchanged) {
  const SimulationTotals& tot = s.totals;
  j.update({{"seconds", tot.seconds()}, {"frame_rate_hz", s.frame_rate()}, {"broadphase_pairs", tot.pairs},
            {"pairs_tested", tot.tested}, {"touching_pairs", tot.touching}, {"responses", tot.responses},
            {"wall_bounces", tot.wall_hits}, {"lookups", tot.lookups}, {"hits", tot.hits}, {"contacts", tot.contacts},
            {"stage_seconds", {{"integrate", tot.t_integrate}, {"bounds", tot.t_bounds},
                               {"broadphase", tot.t_broadphase}, {"narrow", tot.t_narrow},
                               {"response", tot.t_response}}}});
  if (s.config.ccd)
    j["no_tunnelling"] = {{"iterations", tot.ccd_iterations}, {"queries", tot.ccd_queries},
                          {"pairs_limited", tot.ccd_limited}, {"time_of_impact_events", tot.ccd_toi},
                          {"bodies_dropped", tot.ccd_dropped}, {"lookups", tot.ccd_lookups}};
  if (s.ranks > 1) j.update({{"ranks", s.ranks}, {"rank0_bytes_per_frame", exchanged / double(s.config.frames)}});
}

// The device into j: lanes, cycles, the clock and the device's frame rate (null without device cycles: not a rate
// of frames that took no time); then the recording and the state hash.
void add_device_json(Json& j, const SimulationSummary& s) {
  const RunConfig& c = s.config;
  const SimulationTotals& tot = s.totals;
  j.update({{"lanes", c.lanes}, {"device_cycles", tot.cycles}, {"device_cycles_per_frame", s.cycles_per_frame()},
            {"device_cycles_max_frame", tot.max_cycles}, {"device_idle_frames", tot.idle_frames},
            {"clock_mhz", s.clock.mhz}, {"clock_source", s.clock.source}, {"clock_estimate", s.clock.estimate},
            {"device_frame_rate_hz", tot.cycles ? Json(s.device_rate()) : Json(nullptr)}});
  if (!c.record.empty()) j.update({{"record", c.record}, {"record_bytes", std::filesystem::file_size(c.record)}});
  std::ostringstream hash;
  hash << std::hex << s.state_hash;
  j["state_hash"] = hash.str();
}

// The summary as JSON, its numbers as a stream prints them (6 significant digits); `exchanged`: bytes rank 0 sent
// and received.
void print_json(const SimulationSummary& s, double exchanged) {
  Json j = settings_json(s);
  add_totals_json(j, s, exchanged);
  add_device_json(j, s);
  std::cout << json_text(j, false, 6) + "\n";
}

// The summary's head: the scene.
void print_scene(const SimulationSummary& s) {
  const RunConfig& c = s.config;
  const ObjectType& type = *s.types[0];
  const auto& d = type.voxmap().dims();
  if (c.builtin()) {
    std::printf("voxcd simulate: %llu x %s in a cube of side %g at density %g, voxel %g (%zu shell points, voxmap "
                "%ux%ux%u), seed %llu\n",
                (unsigned long long)c.objects(), s.shape().c_str(), c.side, c.density, s.voxel(),
                type.shell().size(), d[0], d[1], d[2], (unsigned long long)c.seed);
  } else {
    std::ostringstream side;
    side << c.side;
    std::printf("voxcd simulate: %s: %llu objects of %zu type%s in a cube of side %s, seed %llu\n", c.where.c_str(),
                (unsigned long long)c.objects(), s.types.size(), s.types.size() > 1 ? "s" : "", side.str().c_str(),
                (unsigned long long)c.seed);
    for (const auto& t : s.types) {
      const auto& td = t->voxmap().dims();
      std::printf("  type %-20s voxel %g, %zu shell points, voxmap %ux%ux%u\n", t->name.c_str(), t->voxmap().voxel(),
                  t->shell().size(), td[0], td[1], td[2]);
    }
  }
}

// The summary as text; `exchanged`: bytes rank 0 sent and received.
void print_text(const SimulationSummary& s, double exchanged) {
  print_scene(s);
  const RunConfig& c = s.config;
  const SimulationTotals& tot = s.totals;
  const double F = double(c.frames);
  const double rate = s.frame_rate();
  if (c.device.has_value()) std::printf("device          %s\n", s.device.to_string().c_str());
  std::printf("broadphase %s, backend %s, mode %s%s, %llu frames\n", c.broadphase.c_str(), c.backend.c_str(),
              mode_name(c.mode), c.both_directions ? ", both directions" : "", (unsigned long long)c.frames);
  if (s.distance_bits())
    std::printf("distance        %d-bit fields over +-%g voxels, margin %g%s\n", s.distance_bits(), c.band, c.margin,
                c.ccd ? ", continuous collision" : "");
  if (c.storage != ObjectStorage::kDense)
    std::printf("storage         %s: %s\n", storage_name(c.storage),
                s.device.sparse() ? ("a sparse device, bricks of 2^" + std::to_string(s.device.BL) + " voxels").c_str()
                                  : "every type dense, a dense device");
  if (s.ranks > 1)
    std::printf("frame rate      %.1f Hz (%.3f ms per frame on rank 0 of %d)\n", rate, 1e3 * tot.seconds() / F, s.ranks);
  else
    std::printf("frame rate      %.1f Hz (%.3f ms per frame, one process)\n", rate, 1e3 * tot.seconds() / F);
  if (s.ranks > 1)
    std::printf("ranks           %d: slabs that follow the bodies, each rank's broadphase and device on its slab's "
                "pairs; rank 0 sent and received %.0f bytes per frame; device cycles are the busiest rank's\n",
                s.ranks, exchanged / F);
  std::printf("per frame       %.2f broadphase pairs, %.2f tested (bounding spheres and oriented boxes meet), %.2f touching, %.1f lookups, "
              "%.1f contacts, %.3f responses, %.3f wall bounces\n",
              double(tot.pairs) / F, double(tot.tested) / F, double(tot.touching) / F, double(tot.lookups) / F, double(tot.contacts) / F,
              double(tot.responses) / F, double(tot.wall_hits) / F);
  if (c.ccd)
    std::printf("no tunnelling   per frame %.2f advancement steps, %.2f pair queries (%.1f lookups), %.3f pairs limited, "
                "%.3f time-of-impact events, %.3f bodies whose rest of the frame the cap dropped\n",
                double(tot.ccd_iterations) / F, double(tot.ccd_queries) / F, double(tot.ccd_lookups) / F,
                double(tot.ccd_limited) / F, double(tot.ccd_toi) / F, double(tot.ccd_dropped) / F);
  std::printf("time per stage  integrate %.1f us, bounds %.1f us, broadphase %.1f us, pair tests %.1f us, "
              "response %.1f us\n",
              1e6 * tot.t_integrate / F, 1e6 * tot.t_bounds / F, 1e6 * tot.t_broadphase / F, 1e6 * tot.t_narrow / F,
              1e6 * tot.t_response / F);
  std::printf("device          %.0f cycles per frame (largest %llu) at %d lanes (%s); device frame rate %s\n",
              s.cycles_per_frame(), (unsigned long long)tot.max_cycles, c.lanes,
              c.backend == "rtl" || c.backend == "sysc-rtl" ? "measured on the RTL"
                                                             : "the exact timing model of ref/",
              s.device_rate_text().c_str());
  std::printf("state hash      %016llx\n", (unsigned long long)s.state_hash);
  if (!c.record.empty()) {
    const double bytes = double(std::filesystem::file_size(c.record));
    std::printf("recording       %s: %llu frames, %.0f bytes (%.0f bytes per frame with the types once); "
                "voxcd view %s replays it\n",
                c.record.c_str(), (unsigned long long)c.frames, bytes, bytes / F, c.record.c_str());
  }
}

// The progress callback: a bar on stderr, for runs of 100 frames or more, when `show`.
std::function<void(uint64_t, uint64_t)> progress_bar(bool show) {
  return [show](uint64_t done, uint64_t frames) {
    if (!show || frames < 100 || ((done - 1) % 25 != 0 && done != frames)) return;
    const int width = 40, bar = int(width * done / frames);
    std::fprintf(stderr, "\r[%s%s] %llu/%llu frames", std::string(size_t(bar), '#').c_str(),
                 std::string(size_t(width - bar), '.').c_str(), (unsigned long long)done, (unsigned long long)frames);
    if (done == frames) std::fprintf(stderr, "\n");
  };
}

// This rank's run of the options. An option that cannot be used is a CLI::ValidationError naming it; in a
// distributed run (`exchange`), any error ends every rank now (the others would wait for its messages until the
// timeout).
SimulationSummary run_rank(const SimulateArgs& a, mpi::World& world,
                           const std::shared_ptr<mpi::MpiFrameExchange>& exchange, bool progress) {
  try {
    RunConfig options = options_given(a);
    options.exchange = exchange;
    const RunConfig config = run_config(options);
    if (world.rank() == 0) print_notes(config, "simulate");
    return simulate(config, progress_bar(progress));
  } catch (const OptionError& e) {
    std::string names;
    for (const std::string& o : e.options) names += (names.empty() ? "--" : ", --") + o;
    if (exchange)
      world.abort(2, "voxcd simulate: rank " + std::to_string(world.rank()) + ": " + names + ": " + e.message);
    throw CLI::ValidationError(names, e.message);
  } catch (const std::exception& e) {
    if (!exchange) throw;
    world.abort(2, "voxcd simulate: rank " + std::to_string(world.rank()) + " of " + std::to_string(world.size()) +
                       ": " + e.what());
  }
  return {};
}

int simulate_cmd(const SimulateArgs& a) {
  // Under mpirun or srun, each process is one rank of a distributed run (docs/scale.md); rank 0 prints.
  mpi::World world;
  std::shared_ptr<mpi::MpiFrameExchange> exchange;
  if (world.size() > 1) exchange = std::make_shared<mpi::MpiFrameExchange>(world, a.mpi_timeout);
  const bool progress = a.progress && !a.json && isatty(STDERR_FILENO) && world.rank() == 0;
  const SimulationSummary s = run_rank(a, world, exchange, progress);
  if (world.rank() != 0) return 0;
  const double exchanged = exchange ? double(exchange->bytes_sent() + exchange->bytes_received()) : 0;
  if (a.json)
    print_json(s, exchanged);
  else
    print_text(s, exchanged);
  return 0;
}

// The options of the scene: objects, shape, voxel or resolution, density, speed.
void add_scene_options(CLI::App* c, SimulateArgs& args) {
  SimulateArgs* a = &args;
  c->add_option("--objects", a->options.types[0].count, "Number of objects")
      ->capture_default_str()
      ->check(CLI::Range(1, int(kMaxObjects)));
  c->add_option("--shape", a->options.types[0].shape, "A built-in shape name or a mesh file")->capture_default_str();
  c->add_option("--voxel", a->options.types[0].voxel,
                "Voxel size in world units (default: the paper's 1 scaled with the object, so 1 for its 64 objects at "
                "2.5% and (64/N)^(1/3) for N; docs/simulate.md)");
  c->add_option("--resolution", a->options.types[0].resolution,
                "Or the voxels along an object's longest side (voxel = longest side / N)")
      ->check(CLI::Range(kMinVoxelsAcross, kMaxVoxelsAcross));
  c->add_option("--density", a->options.density, "Fraction of the cube the objects fill")->capture_default_str();
  c->add_option("--speed", a->options.speed, "Largest initial speed per frame, as a fraction of the object's radius")
      ->capture_default_str();
}

// The options of the device and the pair tests: broadphase, backend, lanes, mode, directions, distance fields,
// continuous collision.
void add_device_options(CLI::App* c, SimulateArgs& args) {
  SimulateArgs* a = &args;
  c->add_option("--broadphase", a->options.broadphase, "Broadphase: " + comma_list(broadphase_names()))
      ->capture_default_str();
  c->add_option("--pruning", a->pruning, "Deprecated: --broadphase's old name (the same option, with a note)");
  c->add_option("--backend", a->options.backend, "Device backend: " + comma_list(backend_names()))
      ->capture_default_str();
  c->add_option("--lanes", a->options.lanes, "Lanes of the modelled device")->check(CLI::Range(1, 64))->capture_default_str();
  c->add_option("--mode", a->mode, "ALL (every contact) or FIRST (whether a pair touches)")->capture_default_str();
  c->add_flag("--both,!--no-both", a->options.both_directions,
              "Test both directions of every pair, or with --no-both one (A's shell in B's voxmap); by default as "
              "the scene says: one for the built-in scene (the paper's), both for a scene file without "
              "\"both_directions\"");
  c->add_option("--distance-bits", a->options.distance_bits,
                "Distance voxmaps of B bits (4, 8 or 16): objects carry signed distance fields, contacts the "
                "interpolated depth and the field's gradient")
      ->check(CLI::IsMember(kDistanceBits));
  c->add_option("--storage", a->storage,
                "How the types are kept: dense, sparse (on a sparse device: memory in proportion to the surface) or "
                "auto (docs/objects.md, \"Sparse objects\")")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}));
  c->add_option("--band", a->options.band, "Band of the distance fields, voxels")->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--margin", a->options.margin, "Distance voxmaps: contacts within this distance, world units")->capture_default_str();
  c->add_flag("--ccd", a->options.ccd, "Continuous collision: no body passes through another or a wall between frames "
                               "(needs --distance-bits)");
}

// The options of the run: frames, seed, clock, threads, MPI, the culling stages, and the output.
void add_run_options(CLI::App* c, SimulateArgs& args) {
  SimulateArgs* a = &args;
  c->add_option("--frames", a->options.frames, "Frames to simulate")->capture_default_str();
  c->add_option("--seed", a->options.seed, "Seed of the scene")->capture_default_str();
  c->add_option("--clock", a->clock_mhz,
                "Device clock in MHz for the modelled frame rate (default: " + default_clock_help("the run's device") + ")");
  c->add_option("--threads", a->options.threads, "threads of every stage of a frame and the cpu backend (0: all)")
      ->capture_default_str();
  c->add_option("--mpi-timeout", a->mpi_timeout,
                "Under mpirun or srun: seconds a rank waits for a frame's messages before the run ends with an error "
                "naming the rank and its slab")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c->add_flag("!--no-midphase", a->options.midphase,
              "test every broadphase pair on the device (by default pairs whose oriented boxes are disjoint are dropped "
              "first; the results are the same)");
  c->add_flag("!--no-cull", a->options.cull,
              "submit every shell point of a tested pair (by default only the clusters of points that can land in "
              "the other object's voxmap; the results are the same)");
  c->add_flag("!--no-progress", a->progress, "No progress bar");
  c->add_flag("--json", a->json, "Print the summary as JSON");
  c->add_option("--record", a->options.record,
                "Record the run to FILE as it goes: poses, pairs, contacts and statistics of every frame "
                "(replay it with voxcd view FILE; docs/view.md)");
}

}  // namespace

void add_simulate(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  CLI::App* c = app.add_subcommand("simulate", "The paper's N-body environment, or a scene file: objects moving in a "
                                               "cube, pruned by a broadphase, pair tests on a device backend "
                                               "(docs/simulate.md, docs/scenes.md)");
  a->app = c;
  c->add_option("scene", a->options.where, "A scene file (docs/scenes.md); the options given override it")
      ->check(CLI::ExistingFile);
  c->add_option("--config", a->config,
                "The device's whole configuration as NAME VALUE pairs (e.g. as voxcd size prints it); "
                "--lanes overrides its LANES");
  add_scene_options(c, *a);
  add_device_options(c, *a);
  add_run_options(c, *a);
  c->callback([a] { exit_code() = simulate_cmd(*a); });
}

}  // namespace voxcd::cli
