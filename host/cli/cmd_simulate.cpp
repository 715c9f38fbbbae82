// voxcd simulate: the paper's N-body environment (or a scene like it, or a scene file) for a number of frames, with
// a broadphase and pair tests on a device backend; a summary of rates, counts, time per stage and device cycles.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/cli/object_report.h"
#include "voxcd/host/mpi/frame_exchange.h"
#include "voxcd/host/mpi/world.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/ref/vectors.h"

namespace voxcd::cli {

namespace {

struct SimulateArgs {
  std::string file;    // a scene file (docs/scenes.md); the options below override it where given
  std::string config;  // a whole device configuration, "NAME VALUE" pairs
  CLI::App* app = nullptr;
  SceneSpec scene;
  SimOptions sim;
  std::string mode = "ALL";
  uint64_t frames = 1000;
  double clock_mhz = 0;  // --clock; unset: the scene file's "clock" or default_device_clock()
  int distance_bits = 0;
  double band = 4.0, margin = 0;
  bool ccd = false;
  bool json = false;
  bool progress = true;
  std::string record;  // --record FILE
  double mpi_timeout = 300;  // seconds a rank waits for a frame's messages
};

// The request of the options given (the others take the scene file's values or the defaults).
SimulateRequest request(const SimulateArgs& a) {
  auto given = [&](const char* opt) { return a.app->count(opt) > 0; };
  SimulateRequest r;
  r.file = a.file;
  if (given("--objects")) r.objects = a.scene.objects;
  if (given("--shape")) r.shape = a.scene.shape;
  if (given("--voxel")) r.voxel = a.scene.voxel;
  if (given("--resolution")) r.resolution = a.scene.resolution;
  if (given("--density")) r.density = a.scene.density;
  if (given("--speed")) r.speed = a.scene.speed;
  if (given("--seed")) r.seed = a.scene.seed;
  if (given("--pruning")) r.pruning = a.sim.pruning;
  if (given("--backend")) r.backend = a.sim.backend;
  if (given("--mode")) r.mode = a.mode;
  if (given("--both")) r.both_directions = a.sim.both_directions;
  if (given("--frames")) r.frames = a.frames;
  if (given("--clock")) r.clock = clock_option(a.clock_mhz, "--clock");
  if (given("--lanes")) r.lanes = a.sim.lanes;
  if (given("--distance-bits")) r.distance_bits = a.distance_bits;
  if (given("--band")) r.band = a.band;
  if (given("--margin")) r.margin = a.margin;
  if (given("--ccd")) r.ccd = a.ccd;
  if (!a.config.empty()) r.device = parse_config_pairs(a.config, "--config");
  r.threads = a.sim.threads;
  r.midphase = a.sim.midphase;
  r.cull = a.sim.cull;
  r.record = a.record;
  return r;
}

int simulate_cmd(const SimulateArgs& a) {
  // Under mpirun or srun, each process is one rank of a distributed run (docs/scale.md); rank 0 prints.
  mpi::World world;
  std::shared_ptr<mpi::MpiFrameExchange> exchange;
  if (world.size() > 1) exchange = std::make_shared<mpi::MpiFrameExchange>(world, a.mpi_timeout);
  const bool progress = a.progress && !a.json && isatty(STDERR_FILENO) && world.rank() == 0;
  SimulateRequest req = request(a);
  req.exchange = exchange;
  SimulationSummary s;
  try {
    s = simulate(req, [&](uint64_t done, uint64_t frames) {
      if (!progress || frames < 100 || ((done - 1) % 25 != 0 && done != frames)) return;
      const int width = 40, bar = int(width * done / frames);
      std::fprintf(stderr, "\r[%s%s] %llu/%llu frames", std::string(size_t(bar), '#').c_str(),
                   std::string(size_t(width - bar), '.').c_str(), (unsigned long long)done,
                   (unsigned long long)frames);
      if (done == frames) std::fprintf(stderr, "\n");
    });
  } catch (const SimulateOptionError& e) {
    std::string names;
    for (const std::string& o : e.options) names += (names.empty() ? "--" : ", --") + o;
    if (exchange) {
      world.abort(2, "voxcd simulate: rank " + std::to_string(world.rank()) + ": " + names + ": " + e.message);
    }
    throw CLI::ValidationError(names, e.message);
  } catch (const std::exception& e) {
    if (!exchange) throw;
    // One rank's error ends every rank now (the others would wait for its messages until the timeout).
    world.abort(2, "voxcd simulate: rank " + std::to_string(world.rank()) + " of " + std::to_string(world.size()) +
                       ": " + e.what());
  }
  if (world.rank() != 0) return 0;
  const double exchanged = exchange ? double(exchange->bytes_sent() + exchange->bytes_received()) : 0;
  const SimulationTotals& tot = s.totals;
  const ObjectType& type = *s.types[0];
  const double F = double(s.frames);
  const double rate = s.frame_rate();
  const double cyc_per_frame = s.cycles_per_frame();
  const double device_rate = s.device_rate();
  const auto& d = type.voxmap().dims();
  if (a.json) {
    std::ostringstream o;
    o << "{";
    if (!s.file.empty()) {
      o << "\"scene\": " << json_string(s.file) << ", \"types\": [";
      for (size_t i = 0; i < s.types.size(); ++i)
        o << (i ? ", " : "") << "{\"name\": " << json_string(s.types[i]->name) << ", \"voxel\": "
          << s.types[i]->voxmap().voxel() << ", \"shell_points\": " << s.types[i]->shell().size() << "}";
      o << "], ";
    }
    o << "\"device\": " << json_string(s.device.to_string()) << ", ";
    o << "\"shape\": " << json_string(s.shape) << ", \"objects\": " << s.objects
      << ", \"voxel\": " << s.voxel << ", \"shell_points\": " << type.shell().size() << ", \"voxmap\": ["
      << d[0] << ", " << d[1] << ", " << d[2] << "], \"pruning\": " << json_string(s.pruning)
      << ", \"backend\": " << json_string(s.backend) << ", \"mode\": " << json_string(s.mode)
      << ", \"both_directions\": " << (s.both_directions ? "true" : "false");
    if (s.distance_bits)
      o << ", \"distance_bits\": " << s.distance_bits << ", \"band\": " << s.band << ", \"margin\": " << s.margin
        << ", \"ccd\": " << (s.ccd ? "true" : "false");
    o << ", \"frames\": " << s.frames
      << ", \"seed\": " << s.seed << ", \"seconds\": " << tot.seconds() << ", \"frame_rate_hz\": " << rate
      << ", \"broadphase_pairs\": " << tot.pairs << ", \"pairs_tested\": " << tot.tested
      << ", \"touching_pairs\": " << tot.touching
      << ", \"responses\": " << tot.responses << ", \"wall_bounces\": " << tot.wall_hits
      << ", \"lookups\": " << tot.lookups << ", \"hits\": " << tot.hits << ", \"contacts\": " << tot.contacts
      << ", \"stage_seconds\": {\"integrate\": " << tot.t_integrate << ", \"bounds\": " << tot.t_bounds
      << ", \"broadphase\": " << tot.t_broadphase << ", \"narrow\": " << tot.t_narrow
      << ", \"response\": " << tot.t_response << "}";
    if (s.ccd)
      o << ", \"no_tunnelling\": {\"iterations\": " << tot.ccd_iterations << ", \"queries\": " << tot.ccd_queries
        << ", \"pairs_limited\": " << tot.ccd_limited << ", \"time_of_impact_events\": " << tot.ccd_toi
        << ", \"bodies_dropped\": " << tot.ccd_dropped << ", \"lookups\": " << tot.ccd_lookups << "}";
    if (s.ranks > 1)
      o << ", \"ranks\": " << s.ranks << ", \"rank0_bytes_per_frame\": " << exchanged / F;
    o << ", \"lanes\": " << s.lanes
      << ", \"device_cycles\": " << tot.cycles << ", \"device_cycles_per_frame\": " << cyc_per_frame
      << ", \"device_cycles_max_frame\": " << tot.max_cycles << ", \"device_idle_frames\": " << tot.idle_frames
      << ", \"clock_mhz\": " << s.clock.mhz
      << ", \"clock_source\": " << json_string(s.clock.source)
      << ", \"clock_estimate\": " << (s.clock.estimate ? "true" : "false") << ", \"device_frame_rate_hz\": ";
    // No device cycles: no device rate (null), not a rate of frames that took no time.
    if (tot.cycles) o << device_rate;
    else o << "null";
    if (!a.record.empty())
      o << ", \"record\": " << json_string(a.record) << ", \"record_bytes\": " << std::filesystem::file_size(a.record);
    o << ", \"state_hash\": \"" << std::hex << s.state_hash
      << std::dec << "\"}\n";
    std::cout << o.str();
    return 0;
  }
  if (s.file.empty()) {
    std::printf("voxcd simulate: %llu x %s in a cube of side %g at density %g, voxel %g (%zu shell points, voxmap "
                "%ux%ux%u), seed %llu\n",
                (unsigned long long)s.objects, s.shape.c_str(), s.side, s.density, s.voxel, type.shell().size(), d[0],
                d[1], d[2], (unsigned long long)s.seed);
  } else {
    std::ostringstream side;
    side << s.side;
    std::printf("voxcd simulate: %s: %llu objects of %zu type%s in a cube of side %s, seed %llu\n", s.file.c_str(),
                (unsigned long long)s.objects, s.types.size(), s.types.size() > 1 ? "s" : "", side.str().c_str(),
                (unsigned long long)s.seed);
    for (const auto& t : s.types) {
      const auto& td = t->voxmap().dims();
      std::printf("  type %-20s voxel %g, %zu shell points, voxmap %ux%ux%u\n", t->name.c_str(), t->voxmap().voxel(),
                  t->shell().size(), td[0], td[1], td[2]);
    }
  }
  if (s.device_given) std::printf("device          %s\n", s.device.to_string().c_str());
  std::printf("pruning %s, backend %s, mode %s%s, %llu frames\n", s.pruning.c_str(), s.backend.c_str(),
              s.mode.c_str(), s.both_directions ? ", both directions" : "", (unsigned long long)s.frames);
  if (s.distance_bits)
    std::printf("distance        %d-bit fields over +-%g voxels, margin %g%s\n", s.distance_bits, s.band, s.margin,
                s.ccd ? ", continuous collision" : "");
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
  if (s.ccd)
    std::printf("no tunnelling   per frame %.2f advancement steps, %.2f pair queries (%.1f lookups), %.3f pairs limited, "
                "%.3f time-of-impact events, %.3f bodies whose rest of the frame the cap dropped\n",
                double(tot.ccd_iterations) / F, double(tot.ccd_queries) / F, double(tot.ccd_lookups) / F,
                double(tot.ccd_limited) / F, double(tot.ccd_toi) / F, double(tot.ccd_dropped) / F);
  std::printf("time per stage  integrate %.1f us, bounds %.1f us, broadphase %.1f us, pair tests %.1f us, "
              "response %.1f us\n",
              1e6 * tot.t_integrate / F, 1e6 * tot.t_bounds / F, 1e6 * tot.t_broadphase / F, 1e6 * tot.t_narrow / F,
              1e6 * tot.t_response / F);
  std::printf("device          %.0f cycles per frame (largest %llu) at %d lanes (%s); device frame rate %s\n",
              cyc_per_frame, (unsigned long long)tot.max_cycles, s.lanes,
              s.backend == "rtl" || s.backend == "sysc-rtl" ? "measured on the RTL"
                                                             : "the exact timing model of ref/",
              s.device_rate_text().c_str());
  std::printf("state hash      %016llx\n", (unsigned long long)s.state_hash);
  if (!a.record.empty()) {
    const double bytes = double(std::filesystem::file_size(a.record));
    std::printf("recording       %s: %llu frames, %.0f bytes (%.0f bytes per frame with the types once); "
                "voxcd view %s replays it\n",
                a.record.c_str(), (unsigned long long)s.frames, bytes, bytes / F, a.record.c_str());
  }
  return 0;
}

}  // namespace

void add_simulate(CLI::App& app) {
  auto a = std::make_shared<SimulateArgs>();
  CLI::App* c = app.add_subcommand("simulate", "The paper's N-body environment, or a scene file: objects moving in a "
                                               "cube, pruned by a broadphase, pair tests on a device backend "
                                               "(docs/simulate.md, docs/scenes.md)");
  a->app = c;
  c->add_option("scene", a->file, "A scene file (docs/scenes.md); the options given override it")
      ->check(CLI::ExistingFile);
  c->add_option("--config", a->config,
                "The device's whole configuration as NAME VALUE pairs (e.g. as voxcd size prints it); "
                "--lanes overrides its LANES");
  c->add_option("--objects", a->scene.objects, "Number of objects")->capture_default_str()->check(CLI::Range(1, 1 << 20));
  c->add_option("--shape", a->scene.shape, "A built-in shape name or a mesh file")->capture_default_str();
  c->add_option("--voxel", a->scene.voxel,
                "Voxel size in world units (default: the paper's 1 scaled with the object, so 1 for its 64 objects at "
                "2.5% and (64/N)^(1/3) for N; docs/simulate.md)");
  c->add_option("--resolution", a->scene.resolution,
                "Or the voxels along an object's longest side (voxel = longest side / N)")
      ->check(CLI::Range(uint32_t(kMinVoxelsAcross), uint32_t(1020)));
  c->add_option("--density", a->scene.density, "Fraction of the cube the objects fill")->capture_default_str();
  c->add_option("--speed", a->scene.speed, "Largest initial speed per frame, as a fraction of the object's radius")
      ->capture_default_str();
  c->add_option("--pruning", a->sim.pruning, "Broadphase: " + [] {
    std::string s;
    for (const auto& b : broadphase_names()) s += (s.empty() ? "" : ", ") + b;
    return s;
  }())->capture_default_str();
  c->add_option("--backend", a->sim.backend, "Device backend: " + [] {
    std::string s;
    for (const auto& b : backend_names()) s += (s.empty() ? "" : ", ") + b;
    return s;
  }())->capture_default_str();
  c->add_option("--lanes", a->sim.lanes, "Lanes of the modelled device")->check(CLI::Range(1, 64))->capture_default_str();
  c->add_option("--mode", a->mode, "ALL (every contact) or FIRST (whether a pair touches)")->capture_default_str();
  c->add_flag("--both", a->sim.both_directions, "Test both directions of every pair");
  c->add_option("--distance-bits", a->distance_bits,
                "Distance voxmaps of B bits (4, 8 or 16): objects carry signed distance fields, contacts the "
                "interpolated depth and the field's gradient")
      ->check(CLI::IsMember({4, 8, 16}));
  c->add_option("--band", a->band, "Band of the distance fields, voxels")->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--margin", a->margin, "Distance voxmaps: contacts within this distance, world units")->capture_default_str();
  c->add_flag("--ccd", a->ccd, "Continuous collision: no body passes through another or a wall between frames "
                               "(needs --distance-bits)");
  c->add_option("--frames", a->frames, "Frames to simulate")->capture_default_str();
  c->add_option("--seed", a->scene.seed, "Seed of the scene")->capture_default_str();
  c->add_option("--clock", a->clock_mhz,
                "Device clock in MHz for the modelled frame rate (default: the scene file's \"clock\", or " +
                    default_device_clock().text() + ")");
  c->add_option("--threads", a->sim.threads, "threads of every stage of a frame and the cpu backend (0: all)")
      ->capture_default_str();
  c->add_option("--mpi-timeout", a->mpi_timeout,
                "Under mpirun or srun: seconds a rank waits for a frame's messages before the run ends with an error "
                "naming the rank and its slab")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c->add_flag("!--no-midphase", a->sim.midphase,
              "test every broadphase pair on the device (by default pairs whose oriented boxes are disjoint are dropped "
              "first; the results are the same)");
  c->add_flag("!--no-cull", a->sim.cull,
              "submit every shell point of a tested pair (by default only the clusters of points that can land in "
              "the other object's voxmap; the results are the same)");
  c->add_flag("!--no-progress", a->progress, "No progress bar");
  c->add_flag("--json", a->json, "Print the summary as JSON");
  c->add_option("--record", a->record,
                "Record the run to FILE as it goes: poses, pairs, contacts and statistics of every frame "
                "(replay it with voxcd view FILE; docs/view.md)");
  c->callback([a] { exit_code() = simulate_cmd(*a); });
}

}  // namespace voxcd::cli
