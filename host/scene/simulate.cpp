#include "voxcd/host/scene/simulate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/ref/types.h"

namespace voxcd {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

SimulateOptionError::SimulateOptionError(std::vector<std::string> options_, const std::string& message_)
    : std::invalid_argument(joined(options_) + ": " + message_), options(std::move(options_)), message(message_) {}

void SimulationTotals::add(const FrameStats& f) {
  pairs += f.pairs, tested += f.tested, touching += f.touching, responses += f.responses, wall_hits += f.wall_hits;
  lookups += f.lookups, hits += f.hits, contacts += f.contacts, cycles += f.device_cycles;
  max_cycles = std::max(max_cycles, f.device_cycles);
  idle_frames += f.device_cycles == 0;
  ccd_iterations += f.ccd_iterations, ccd_queries += f.ccd_queries, ccd_limited += f.ccd_limited;
  ccd_toi += f.ccd_toi, ccd_dropped += f.ccd_dropped, ccd_lookups += f.ccd_lookups;
  t_integrate += f.t_integrate, t_bounds += f.t_bounds, t_broadphase += f.t_broadphase;
  t_narrow += f.t_narrow, t_response += f.t_response;
}

double SimulationSummary::frame_rate() const {
  return totals.seconds() > 0 ? double(frames) / totals.seconds() : 0;
}

double SimulationSummary::cycles_per_frame() const { return double(totals.cycles) / double(frames); }

double SimulationSummary::device_rate() const { return clock.rate(cycles_per_frame()); }

std::string SimulationSummary::device_rate_text() const {
  if (totals.cycles == 0) return "none: the frames needed no device cycles";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f Hz at ", device_rate());
  std::string t = buf + clock.text();
  if (totals.idle_frames)
    t += "; " + std::to_string(totals.idle_frames) + " of " + std::to_string(frames) + " frames needed no device cycles";
  return t;
}

ResolvedRun resolve_run(const SimulateRequest& req) {
  ResolvedRun out;
  SimulationSummary& s = out.summary;
  SceneSpec spec;
  SimOptions sim;
  std::string mode = req.mode.value_or("ALL");
  const auto parsed_mode = parse_mode(mode);
  if (!parsed_mode) throw SimulateOptionError({"mode"}, "'" + mode + "' is not ALL, FIRST or COUNT");
  sim.mode = *parsed_mode;
  if (req.voxel && req.resolution)
    throw SimulateOptionError({"voxel", "resolution"},
                              "give the voxel size in world units (--voxel) or the voxels along an object's longest "
                              "side (--resolution), not both");
  if (req.voxel && !(*req.voxel > 0 && std::isfinite(*req.voxel)))
    throw SimulateOptionError({"voxel"}, "must be a positive number of world units");
  if (req.objects && (*req.objects < 1 || *req.objects > (uint64_t{1} << 20)))
    throw SimulateOptionError({"objects"}, std::to_string(*req.objects) + " is outside [1, 1048576]");
  if (req.resolution && (*req.resolution < kMinVoxelsAcross || *req.resolution > 1020))
    throw SimulateOptionError({"resolution"}, std::to_string(*req.resolution) + " is outside [" +
                                                  std::to_string(kMinVoxelsAcross) + ", 1020]");
  if (req.distance_bits && *req.distance_bits != 0 && *req.distance_bits != 4 && *req.distance_bits != 8 &&
      *req.distance_bits != 16)
    throw SimulateOptionError({"distance_bits"}, std::to_string(*req.distance_bits) + " is not 4, 8 or 16");
  if (req.band && !(*req.band > 0 && std::isfinite(*req.band)))
    throw SimulateOptionError({"band"}, "must be a positive number of voxels");
  if (req.margin && !std::isfinite(*req.margin)) throw SimulateOptionError({"margin"}, "must be a finite number");
  if (!req.record.empty() && req.exchange)
    throw SimulateOptionError({"record"}, "a distributed run cannot be recorded yet: record it in one process");
  if (req.objects) spec.objects = *req.objects;
  if (req.shape) spec.shape = *req.shape;
  if (req.voxel) spec.voxel = *req.voxel;
  if (req.resolution) spec.resolution = *req.resolution;
  if (req.density) spec.density = *req.density;
  if (req.speed) spec.speed = *req.speed;
  if (req.seed) spec.seed = *req.seed;
  if (req.distance_bits) spec.distance_bits = sim.distance_bits = *req.distance_bits;
  // A whole distance configuration without --distance-bits: the objects' fields take its SB.
  if (!req.distance_bits && req.device && req.device->distance()) spec.distance_bits = req.device->SB;
  if (req.band) spec.band = *req.band;
  if (req.margin) sim.margin = *req.margin;
  if (req.ccd) sim.ccd = *req.ccd;
  if (req.pruning) sim.pruning = *req.pruning;
  if (req.backend) sim.backend = *req.backend;
  if (req.both_directions) sim.both_directions = *req.both_directions;
  if (req.lanes) sim.lanes = *req.lanes;
  sim.threads = req.threads;
  sim.midphase = req.midphase;
  sim.cull = req.cull;
  uint64_t frames = req.frames.value_or(1000);
  DeviceClock clock = req.clock.value_or(default_device_clock());

  Scene scene;
  if (!req.file.empty() || req.text) {
    SceneFile f = req.text ? parse_scene_file(*req.text, req.file.empty() ? "scene" : req.file) : read_scene_file(req.file);
    // The options given override the file.
    if (req.objects || req.shape || req.voxel || req.resolution) {
      if (f.types.size() != 1)
        throw SimulateOptionError({"objects", "shape", "voxel", "resolution"},
                                  "apply only to a scene file with one object type; " + f.where + " has " +
                                      std::to_string(f.types.size()));
      if (req.objects) f.types[0].count = spec.objects;
      if (req.shape) f.types[0].shape = spec.shape, f.types[0].mesh.clear(), f.types[0].name = spec.shape;
      if (req.voxel) f.types[0].voxel = spec.voxel, f.types[0].resolution = 0;
      if (req.resolution) f.types[0].resolution = spec.resolution, f.types[0].voxel = 0;
    }
    if (req.density) f.density = spec.density, f.density_given = true;
    if (req.speed) f.speed = spec.speed;
    if (req.seed) f.seed = spec.seed;
    if (!req.pruning) sim.pruning = f.broadphase;
    if (!req.backend) sim.backend = f.backend;
    if (!req.mode) {
      mode = f.mode;
      sim.mode = *parse_mode(f.mode);
    }
    if (!req.both_directions) sim.both_directions = f.both_directions;
    if (!req.frames) frames = f.frames;
    if (!req.clock) clock = f.clock;
    if (req.distance_bits) f.distance_bits = *req.distance_bits;
    else if (req.device && req.device->distance()) f.distance_bits = req.device->SB;
    if (req.band) f.band = *req.band;
    if (!req.ccd) sim.ccd = f.ccd;
    spec.distance_bits = sim.distance_bits = f.distance_bits;
    spec.band = f.band;
    spec.objects = f.objects();
    spec.side = f.side;
    spec.density = f.density;
    spec.seed = f.seed;
    scene = make_scene(f);
    spec.shape = f.types[0].shape.empty() ? f.types[0].mesh : f.types[0].shape;
    s.file = f.where;
  } else {
    scene = make_scene(spec);
  }
  if (req.device) {
    DeviceConfig cfg = *req.device;
    cfg.validate();
    if (req.lanes) cfg.LANES = *req.lanes;
    sim.device = cfg;
  }
  if (sim.device) sim.lanes = sim.device->LANES;
  if (sim.ccd && (sim.device ? !sim.device->distance() : sim.distance_bits == 0))
    throw SimulateOptionError({"ccd"}, "continuous collision bounds each step by the distance fields: it needs "
                                       "distance voxmaps (--distance-bits 4, 8 or 16)");

  s.shape = spec.shape;
  s.objects = spec.objects;
  s.side = spec.side;
  s.density = spec.density;
  s.voxel = scene.types[0]->voxmap().voxel();  // as given, from the resolution, or the default
  s.seed = spec.seed;
  s.types = scene.types;
  s.device_given = sim.device.has_value();
  s.pruning = sim.pruning;
  s.backend = sim.backend;
  s.mode = mode;
  s.both_directions = sim.both_directions;
  s.distance_bits = sim.device ? (sim.device->distance() ? sim.device->SB : 0) : sim.distance_bits;
  s.band = spec.band;
  s.margin = sim.margin;
  s.ccd = sim.ccd;
  s.frames = frames;
  s.clock = clock;
  s.lanes = sim.lanes;

  sim.exchange = req.exchange;
  s.ranks = req.exchange ? req.exchange->ranks() : 1;
  out.scene = std::move(scene);
  out.options = std::move(sim);
  return out;
}

SimulationSummary simulate(const SimulateRequest& req, const std::function<void(uint64_t, uint64_t)>& progress) {
  ResolvedRun r = resolve_run(req);
  SimulationSummary& s = r.summary;
  const uint64_t frames = s.frames;
  Simulation run(std::move(r.scene), r.options);
  s.device = run.device_config();
  std::unique_ptr<RecordWriter> rec;
  if (!req.record.empty()) rec = std::make_unique<RecordWriter>(req.record, run, record_settings(s));
  for (uint64_t f = 0; f < frames; ++f) {
    const FrameStats st = run.step();
    s.totals.add(st);
    if (rec) rec->frame(run, st);
    if (progress) progress(f + 1, frames);
  }
  if (rec) rec->close();
  s.state_hash = run.state_hash();
  return std::move(s);
}

}  // namespace voxcd
