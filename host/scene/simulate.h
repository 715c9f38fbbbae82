// A run of `voxcd simulate` (docs/simulate.md, docs/scenes.md): its configuration (the built-in scene, or a scene file
// with the options given overriding it), stepped for a number of frames; and its summary: the configuration, the
// totals of every frame, the rates, the device's cycles and the hash of the final state. The tool prints the summary,
// the Python module returns it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/scene/run_config.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// The configuration of a run: the scene file `options.where` (its text `text` when given, `options.where` then only
// naming it in messages and resolving relative mesh paths: "scene" when empty), or the built-in scene when neither,
// with the settings `options` gives overriding it (apply_options). SceneFileError for the file, OptionError
// for an option that cannot be used.
RunConfig run_config(const RunConfig& options, const std::optional<std::string>& text = std::nullopt);

// The sums of a run's FrameStats.
struct SimulationTotals {
  uint64_t pairs = 0, tested = 0, touching = 0, responses = 0, wall_hits = 0, lookups = 0, hits = 0, contacts = 0;
  uint64_t cycles = 0;      // device cycles of every frame
  uint64_t max_cycles = 0;  // of the largest frame
  uint64_t idle_frames = 0; // frames that needed no device cycles
  // Continuous collision (FrameStats::ccd_*).
  uint64_t ccd_iterations = 0, ccd_queries = 0, ccd_limited = 0, ccd_toi = 0, ccd_dropped = 0, ccd_lookups = 0;
  double t_integrate = 0, t_bounds = 0, t_broadphase = 0, t_narrow = 0, t_response = 0;  // seconds
  double seconds() const { return t_integrate + t_bounds + t_broadphase + t_narrow + t_response; }
  void add(const FrameStats& f);
};

// What a run did, and the configuration it ran with.
struct SimulationSummary {
  RunConfig config;
  std::vector<std::shared_ptr<const ObjectType>> types;
  DeviceConfig device;  // the device configuration the run used
  DeviceClock clock;    // the clock of its rates: config.clock when given, else the device's (run_clock)
  int ranks = 1;        // processes of a distributed run
  SimulationTotals totals;
  uint64_t state_hash = 0;  // Simulation::state_hash after the last frame

  const std::string& file() const { return config.where; }  // the scene file ("" for the built-in scene)
  std::string shape() const;  // the first type's shape name or mesh file
  double voxel() const;       // the first type's voxel: as given, from the resolution, or the default
  int distance_bits() const { return config.device_distance_bits(); }  // 0: 2-bit voxmaps
  double frame_rate() const;        // frames per second of the host (0 when no time was measured)
  double cycles_per_frame() const;  // mean device cycles
  double device_rate() const;       // frames per second the device's mean cycles allow at `clock` (0 without cycles)
  // The device's frame rate as printed: "4485 Hz at 100.4 MHz (OpenSTA, ...)" (its source says "estimate" when the
  // clock was not measured for the device), with "; 3 of 10 frames needed no device
  // cycles" when some did not, or "none: the frames needed no device cycles" when none did.
  std::string device_rate_text() const;
};

// A run's summary before it runs: the configuration, the scene's types, the device configuration `run` uses and the
// clock of its rates (run_clock); the totals and hash still to come.
SimulationSummary summary_of(const RunConfig& config, const Simulation& run);

// Makes the configuration's scene (make_scene) and runs it for config.frames frames, recording it to config.record
// when given, calling progress(done, frames) after each frame when given. check()'s errors; SceneFileError,
// std::invalid_argument, MeshError, PlacementError, DeviceError ... from what it calls.
SimulationSummary simulate(const RunConfig& config,
                           const std::function<void(uint64_t done, uint64_t frames)>& progress = {});

}  // namespace voxcd
