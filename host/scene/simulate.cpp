#include "voxcd/host/scene/simulate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/ref/types.h"

namespace voxcd {

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
  return totals.seconds() > 0 ? double(config.frames) / totals.seconds() : 0;
}

double SimulationSummary::cycles_per_frame() const { return double(totals.cycles) / double(config.frames); }

double SimulationSummary::device_rate() const { return clock.rate(cycles_per_frame()); }

std::string SimulationSummary::device_rate_text() const {
  if (totals.cycles == 0) return "none: the frames needed no device cycles";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.0f Hz at ", device_rate());
  std::string t = buf + clock.text();
  if (totals.idle_frames)
    t += "; " + std::to_string(totals.idle_frames) + " of " + std::to_string(config.frames) +
         " frames needed no device cycles";
  return t;
}

std::string SimulationSummary::shape() const {
  const SceneTypeSpec& t = config.types.at(0);
  return t.shape.empty() ? t.mesh : t.shape;
}

double SimulationSummary::voxel() const { return types.at(0)->voxmap().voxel(); }

RunConfig run_config(const RunConfig& options, const std::optional<std::string>& text) {
  if (options.where.empty() && !text) return apply_options(RunConfig{}, options);
  RunConfig file = text ? parse_scene_file(*text, options.where.empty() ? "scene" : options.where)
                        : read_scene_file(options.where);
  return apply_options(std::move(file), options);
}

SimulationSummary summary_of(const RunConfig& config, const Simulation& run) {
  SimulationSummary s;
  s.config = config;
  s.types = run.scene().types;
  s.device = run.device_config();
  s.clock = run_clock(config, s.device);
  s.ranks = config.exchange ? config.exchange->ranks() : 1;
  return s;
}

SimulationSummary simulate(const RunConfig& config, const std::function<void(uint64_t, uint64_t)>& progress) {
  const uint64_t frames = config.frames;
  Simulation run(make_scene(config), config);
  SimulationSummary s = summary_of(config, run);
  std::unique_ptr<RecordWriter> rec;
  if (!config.record.empty()) rec = std::make_unique<RecordWriter>(config.record, run, record_settings(s));
  for (uint64_t f = 0; f < frames; ++f) {
    const FrameStats st = run.step();
    s.totals.add(st);
    if (rec) rec->frame(run, st);
    if (progress) progress(f + 1, frames);
  }
  if (rec) rec->close();
  s.state_hash = run.state_hash();
  return s;
}

}  // namespace voxcd
