// A run of `voxcd simulate` (docs/simulate.md, docs/scenes.md): the built-in scene, or a scene file with the options
// given overriding it, stepped for a number of frames; and its summary: the totals of every frame, the rates, the
// device's cycles and the hash of the final state. The tool prints the summary, the Python module returns it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/device/clock.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// What is asked of a run. Each option that is set overrides the scene file's value (or, for the built-in scene, the
// default of SceneSpec and SimOptions); an option left unset takes the file's value, or that default.
struct SimulateRequest {
  std::string file;                 // a scene file; "" = the built-in scene
  // The scene file's text instead of reading `file`, which then only names it in messages and resolves relative
  // mesh paths ("scene" when empty: the working directory).
  std::optional<std::string> text;
  // The scene. objects, shape, voxel and resolution apply to a scene file only when it has one object type.
  std::optional<uint64_t> objects;
  std::optional<std::string> shape;  // a built-in shape name or a mesh file
  std::optional<double> voxel;       // world units
  std::optional<uint32_t> resolution;
  std::optional<double> density, speed;
  std::optional<uint64_t> seed;
  // How it runs.
  std::optional<std::string> pruning;  // a broadphase name
  std::optional<std::string> backend;
  std::optional<std::string> mode;     // ALL, FIRST or COUNT
  std::optional<bool> both_directions;
  std::optional<uint64_t> frames;      // default 1000 (a scene file's `frames` otherwise)
  // The device clock for the modelled frame rate (given_clock names where it was given); unset: the scene file's
  // "clock", or default_device_clock() (OpenSTA's clock of the default configuration, docs/hardware.md).
  std::optional<DeviceClock> clock;
  std::optional<int> lanes;            // default 4; overrides the LANES of `device`
  std::optional<DeviceConfig> device;  // the device's whole configuration (SimOptions::device)
  std::optional<int> distance_bits;    // 4, 8, 16: distance voxmaps (SimOptions::distance_bits); default 0
  std::optional<double> band;          // the distance fields' band, voxels; default 4
  std::optional<double> margin;        // world units (SimOptions::margin); default 0
  std::optional<bool> ccd;             // continuous collision (SimOptions::ccd); default off
  unsigned threads = 0;                // cpu backend threads (0: all); results never depend on it
  // A distributed run: this process is one rank (SimOptions::exchange); results never depend on the ranks.
  std::shared_ptr<FrameExchange> exchange;
  bool midphase = true;                // SimOptions::midphase
  bool cull = true;                    // SimOptions::cull
  // A file to record the run to as it goes (host/scene/record.h, docs/view.md); "" records nothing. Not with
  // `exchange`.
  std::string record;
};

// An option that cannot be used, before anything is loaded: `options` names it (or the options in conflict) as
// the request's fields do ("mode"; "voxel", "resolution"), `message` says what is wrong, and what() is
// "mode: 'X' is not ALL, FIRST or COUNT" (the options joined by ", ", a colon, the message).
struct SimulateOptionError : std::invalid_argument {
  SimulateOptionError(std::vector<std::string> options_, const std::string& message_);
  std::vector<std::string> options;
  std::string message;
};

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

// What a run did, with the options as they were resolved.
struct SimulationSummary {
  std::string file;   // the scene file ("" for the built-in scene)
  std::string shape;  // the first type's shape name or mesh file
  uint64_t objects = 0;
  double side = 0, density = 0;
  double voxel = 0;   // the first type's voxel
  uint64_t seed = 0;
  std::vector<std::shared_ptr<const ObjectType>> types;
  bool device_given = false;  // a whole configuration was asked for (SimulateRequest::device)
  DeviceConfig device;        // the configuration the run used
  std::string pruning, backend, mode;
  bool both_directions = false;
  int distance_bits = 0;  // 0: 2-bit voxmaps
  double band = 0, margin = 0;
  bool ccd = false;
  uint64_t frames = 0;
  DeviceClock clock;  // the clock of device_rate and where it comes from
  int lanes = 0;
  int ranks = 1;      // processes of a distributed run
  SimulationTotals totals;
  uint64_t state_hash = 0;  // Simulation::state_hash after the last frame

  double frame_rate() const;        // frames per second of the host (0 when no time was measured)
  double cycles_per_frame() const;  // mean device cycles
  double device_rate() const;       // frames per second the device's mean cycles allow at `clock` (0 without cycles)
  // The device's frame rate as printed: "4181 Hz at 93.6 MHz (OpenSTA, ...)", with "; 3 of 10 frames needed no device
  // cycles" when some did not, or "none: the frames needed no device cycles" when none did.
  std::string device_rate_text() const;
};

// A run as its request resolves: the scene made (types voxelised, bodies placed), the simulation's options, and
// the summary's description of the run (every field but the device's configuration, the totals and the state
// hash, which the run fills). SimulateOptionError for an option that cannot be used; SceneFileError,
// std::invalid_argument, MeshError, PlacementError ... from what it calls. A World can start from it (World::scene).
struct ResolvedRun {
  Scene scene;
  SimOptions options;
  SimulationSummary summary;
};
ResolvedRun resolve_run(const SimulateRequest& req);

// Resolves the request (resolve_run), makes the scene (make_scene of the file or of the SceneSpec) and runs it, calling
// progress(done, frames) after each frame when given. SimulateOptionError for an option that cannot be used;
// SceneFileError, std::invalid_argument, MeshError, PlacementError, DeviceError ... from what it calls.
SimulationSummary simulate(const SimulateRequest& req,
                           const std::function<void(uint64_t done, uint64_t frames)>& progress = {});

}  // namespace voxcd
