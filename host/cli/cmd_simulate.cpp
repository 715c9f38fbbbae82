// voxcd simulate: the paper's N-body environment (or a scene like it, or a scene file) for a number of frames, with
// a broadphase and pair tests on a device backend; a summary of rates, counts, time per stage and device cycles.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/host/cli/object_report.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/object/voxelize.h"
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
  double clock_mhz = 200;
  bool json = false;
  bool progress = true;
};

struct Totals {
  uint64_t pairs = 0, tested = 0, touching = 0, responses = 0, wall_hits = 0, lookups = 0, hits = 0, contacts = 0, cycles = 0;
  uint64_t max_cycles = 0;
  double t_integrate = 0, t_bounds = 0, t_broadphase = 0, t_narrow = 0, t_response = 0;
  double seconds() const { return t_integrate + t_bounds + t_broadphase + t_narrow + t_response; }
  void add(const FrameStats& f) {
    pairs += f.pairs, tested += f.tested, touching += f.touching, responses += f.responses, wall_hits += f.wall_hits;
    lookups += f.lookups, hits += f.hits, contacts += f.contacts, cycles += f.device_cycles;
    max_cycles = std::max(max_cycles, f.device_cycles);
    t_integrate += f.t_integrate, t_bounds += f.t_bounds, t_broadphase += f.t_broadphase;
    t_narrow += f.t_narrow, t_response += f.t_response;
  }
};

int simulate_cmd(SimulateArgs a) {
  const auto mode = parse_mode(a.mode);
  if (!mode) throw CLI::ValidationError("--mode", "'" + a.mode + "' is not ALL, FIRST or COUNT");
  a.sim.mode = *mode;
  auto given = [&](const char* opt) { return a.app->count(opt) > 0; };
  if (given("--voxel") && given("--resolution"))
    throw CLI::ValidationError("--voxel, --resolution",
                               "give the voxel size in world units (--voxel) or the voxels along an object's longest "
                               "side (--resolution), not both");
  if (given("--voxel") && !(a.scene.voxel > 0 && std::isfinite(a.scene.voxel)))
    throw CLI::ValidationError("--voxel", "must be a positive number of world units");
  Scene scene;
  std::string description;
  if (!a.file.empty()) {
    SceneFile f = read_scene_file(a.file);
    // Options given on the command line override the file.
    if (given("--objects") || given("--shape") || given("--voxel") || given("--resolution")) {
      if (f.types.size() != 1)
        throw CLI::ValidationError("--objects, --shape, --voxel, --resolution",
                                   "apply only to a scene file with one object type; " + a.file + " has " +
                                       std::to_string(f.types.size()));
      if (given("--objects")) f.types[0].count = a.scene.objects;
      if (given("--shape")) f.types[0].shape = a.scene.shape, f.types[0].mesh.clear(), f.types[0].name = a.scene.shape;
      if (given("--voxel")) f.types[0].voxel = a.scene.voxel, f.types[0].resolution = 0;
      if (given("--resolution")) f.types[0].resolution = a.scene.resolution, f.types[0].voxel = 0;
    }
    if (given("--density")) f.density = a.scene.density, f.density_given = true;
    if (given("--speed")) f.speed = a.scene.speed;
    if (given("--seed")) f.seed = a.scene.seed;
    if (!given("--pruning")) a.sim.pruning = f.broadphase;
    if (!given("--backend")) a.sim.backend = f.backend;
    if (!given("--mode")) {
      a.mode = f.mode;
      a.sim.mode = *parse_mode(f.mode);
    }
    if (!given("--both")) a.sim.both_directions = f.both_directions;
    if (!given("--frames")) a.frames = f.frames;
    if (!given("--clock")) a.clock_mhz = f.clock;
    a.scene.objects = f.objects();
    a.scene.side = f.side;
    a.scene.density = f.density;
    a.scene.seed = f.seed;
    scene = make_scene(f);
    description = a.file + ": " + std::to_string(f.objects()) + " objects of " + std::to_string(f.types.size()) +
                  " type" + (f.types.size() > 1 ? "s" : "") + " in a cube of side " + [&] {
                    std::ostringstream o;
                    o << f.side;
                    return o.str();
                  }();
    a.scene.shape = f.types[0].shape.empty() ? f.types[0].mesh : f.types[0].shape;
  } else {
    scene = make_scene(a.scene);
  }
  if (!a.config.empty()) {
    DeviceConfig cfg = parse_config_pairs(a.config, "--config");
    cfg.validate();
    if (a.app->count("--lanes")) cfg.LANES = a.sim.lanes;
    a.sim.device = cfg;
  }
  if (a.sim.device) a.sim.lanes = a.sim.device->LANES;
  const ObjectType& type = *scene.types[0];
  a.scene.voxel = type.voxmap().voxel();  // as given, from --resolution, or the default
  const std::vector<std::shared_ptr<const ObjectType>> types = scene.types;
  Simulation sim(std::move(scene), a.sim);
  const bool bar = a.progress && !a.json && isatty(STDERR_FILENO) && a.frames >= 100;
  Totals tot;
  for (uint64_t f = 0; f < a.frames; ++f) {
    tot.add(sim.step());
    if (bar && (f % 25 == 0 || f + 1 == a.frames)) {
      const int width = 40, done = int(width * (f + 1) / a.frames);
      std::fprintf(stderr, "\r[%s%s] %llu/%llu frames", std::string(size_t(done), '#').c_str(),
                   std::string(size_t(width - done), '.').c_str(), (unsigned long long)(f + 1),
                   (unsigned long long)a.frames);
      if (f + 1 == a.frames) std::fprintf(stderr, "\n");
    }
  }
  const double F = double(a.frames);
  const double rate = tot.seconds() > 0 ? F / tot.seconds() : 0;
  const double cyc_per_frame = double(tot.cycles) / F;
  const double device_rate = cyc_per_frame > 0 ? a.clock_mhz * 1e6 / cyc_per_frame : 0;
  const auto& d = type.voxmap().dims();
  if (a.json) {
    std::ostringstream o;
    o << "{";
    if (!a.file.empty()) {
      o << "\"scene\": " << json_string(a.file) << ", \"types\": [";
      for (size_t i = 0; i < types.size(); ++i)
        o << (i ? ", " : "") << "{\"name\": " << json_string(types[i]->name) << ", \"voxel\": "
          << types[i]->voxmap().voxel() << ", \"shell_points\": " << types[i]->shell().size() << "}";
      o << "], ";
    }
    o << "\"device\": " << json_string(sim.device_config().to_string()) << ", ";
    o << "\"shape\": " << json_string(a.scene.shape) << ", \"objects\": " << a.scene.objects
      << ", \"voxel\": " << a.scene.voxel << ", \"shell_points\": " << type.shell().size() << ", \"voxmap\": ["
      << d[0] << ", " << d[1] << ", " << d[2] << "], \"pruning\": " << json_string(a.sim.pruning)
      << ", \"backend\": " << json_string(a.sim.backend) << ", \"mode\": " << json_string(a.mode)
      << ", \"both_directions\": " << (a.sim.both_directions ? "true" : "false") << ", \"frames\": " << a.frames
      << ", \"seed\": " << a.scene.seed << ", \"seconds\": " << tot.seconds() << ", \"frame_rate_hz\": " << rate
      << ", \"broadphase_pairs\": " << tot.pairs << ", \"pairs_tested\": " << tot.tested
      << ", \"touching_pairs\": " << tot.touching
      << ", \"responses\": " << tot.responses << ", \"wall_bounces\": " << tot.wall_hits
      << ", \"lookups\": " << tot.lookups << ", \"hits\": " << tot.hits << ", \"contacts\": " << tot.contacts
      << ", \"stage_seconds\": {\"integrate\": " << tot.t_integrate << ", \"bounds\": " << tot.t_bounds
      << ", \"broadphase\": " << tot.t_broadphase << ", \"narrow\": " << tot.t_narrow
      << ", \"response\": " << tot.t_response << "}, \"lanes\": " << a.sim.lanes
      << ", \"device_cycles\": " << tot.cycles << ", \"device_cycles_per_frame\": " << cyc_per_frame
      << ", \"device_cycles_max_frame\": " << tot.max_cycles << ", \"clock_mhz\": " << a.clock_mhz
      << ", \"device_frame_rate_hz\": " << device_rate << ", \"state_hash\": \"" << std::hex << sim.state_hash()
      << std::dec << "\"}\n";
    std::cout << o.str();
    return 0;
  }
  if (a.file.empty()) {
    std::printf("voxcd simulate: %zu x %s in a cube of side %g at density %g, voxel %g (%zu shell points, voxmap "
                "%ux%ux%u), seed %llu\n",
                a.scene.objects, a.scene.shape.c_str(), a.scene.side, a.scene.density, a.scene.voxel,
                type.shell().size(), d[0], d[1], d[2], (unsigned long long)a.scene.seed);
  } else {
    std::printf("voxcd simulate: %s, seed %llu\n", description.c_str(), (unsigned long long)a.scene.seed);
    for (const auto& t : types) {
      const auto& td = t->voxmap().dims();
      std::printf("  type %-20s voxel %g, %zu shell points, voxmap %ux%ux%u\n", t->name.c_str(), t->voxmap().voxel(),
                  t->shell().size(), td[0], td[1], td[2]);
    }
  }
  if (a.sim.device) std::printf("device          %s\n", sim.device_config().to_string().c_str());
  std::printf("pruning %s, backend %s, mode %s%s, %llu frames\n", a.sim.pruning.c_str(), a.sim.backend.c_str(),
              a.mode.c_str(), a.sim.both_directions ? ", both directions" : "", (unsigned long long)a.frames);
  std::printf("frame rate      %.1f Hz (%.3f ms per frame, one process)\n", rate, 1e3 * tot.seconds() / F);
  std::printf("per frame       %.2f broadphase pairs, %.2f tested (bounding spheres and oriented boxes meet), %.2f touching, %.1f lookups, "
              "%.1f contacts, %.3f responses, %.3f wall bounces\n",
              double(tot.pairs) / F, double(tot.tested) / F, double(tot.touching) / F, double(tot.lookups) / F, double(tot.contacts) / F,
              double(tot.responses) / F, double(tot.wall_hits) / F);
  std::printf("time per stage  integrate %.1f us, bounds %.1f us, broadphase %.1f us, pair tests %.1f us, "
              "response %.1f us\n",
              1e6 * tot.t_integrate / F, 1e6 * tot.t_bounds / F, 1e6 * tot.t_broadphase / F, 1e6 * tot.t_narrow / F,
              1e6 * tot.t_response / F);
  std::printf("device          %.0f cycles per frame (largest %llu) at %d lanes (%s): %.0f Hz at %g MHz\n",
              cyc_per_frame, (unsigned long long)tot.max_cycles, a.sim.lanes,
              a.sim.backend == "rtl" || a.sim.backend == "sysc-rtl" ? "measured on the RTL"
                                                                     : "the exact timing model of ref/",
              device_rate, a.clock_mhz);
  std::printf("state hash      %016llx\n", (unsigned long long)sim.state_hash());
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
    for (const auto& b : device_backends()) s += (s.empty() ? "" : ", ") + b;
    return s;
  }())->capture_default_str();
  c->add_option("--lanes", a->sim.lanes, "Lanes of the modelled device")->check(CLI::Range(1, 64))->capture_default_str();
  c->add_option("--mode", a->mode, "ALL (every contact) or FIRST (whether a pair touches)")->capture_default_str();
  c->add_flag("--both", a->sim.both_directions, "Test both directions of every pair");
  c->add_option("--frames", a->frames, "Frames to simulate")->capture_default_str();
  c->add_option("--seed", a->scene.seed, "Seed of the scene")->capture_default_str();
  c->add_option("--clock", a->clock_mhz, "Device clock in MHz for the modelled frame rate")->capture_default_str();
  c->add_option("--threads", a->sim.threads, "cpu backend threads (0: all)")->capture_default_str();
  c->add_flag("!--no-midphase", a->sim.midphase,
              "test every broadphase pair on the device (by default pairs whose oriented boxes are disjoint are dropped "
              "first; the results are the same)");
  c->add_flag("!--no-cull", a->sim.cull,
              "submit every shell point of a tested pair (by default only the clusters of points that can land in "
              "the other object's voxmap; the results are the same)");
  c->add_flag("!--no-progress", a->progress, "No progress bar");
  c->add_flag("--json", a->json, "Print the summary as JSON");
  c->callback([a] { exit_code() = simulate_cmd(*a); });
}

}  // namespace voxcd::cli
