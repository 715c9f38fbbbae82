// One run's configuration: the scene (the built-in scene or a scene file's object types and environment), what is
// asked of the device, and how the run goes (broadphase, backend, lanes, distance voxmaps, ccd, threads, frames).
// Read from a scene file (scene_file.h), overridden by the options given (apply_options: file < options), checked
// in one place (check), then passed down unchanged to make_scene, Simulation, simulate and World. Every limit and
// list of allowed values a run's settings have is named here (or, for an object's, in host/object) and used by every
// layer: the command line's checks, the scene file reader, Python and the library. docs/scenes.md lists them.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/api/world_def.h"
#include "voxcd/host/device/clock.h"
#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/storage.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/scene/body.h"
#include "voxcd/host/scene/errors.h"
#include "voxcd/ref/config.h"

namespace voxcd {

class FrameExchange;

// The limits of a run's settings (objects' voxels: kMinVoxelsAcross, kMaxVoxelsAcross; distance bits:
// kDistanceBits, in host/object).
constexpr uint64_t kMaxObjects = uint64_t{1} << 20;  // instances in one scene
constexpr double kMaxDensity = 0.3;                  // the fraction of the cube the objects may fill
constexpr uint64_t kMaxFrames = 1000000;             // frames of a run (a scene file's "frames", --frames)
constexpr double kMaxLength = 1e12;                  // side, size, scale, voxel, accuracy, rate: world units or Hz
constexpr double kMaxBand = 1e6;                     // voxels
constexpr double kMaxMotion = 1e6;                   // speed (of the radius) and spin (radians) per frame
constexpr double kMaxClockMhz = 1e6;                 // the device clock
// The device's job modes by name (ref/types.h parse_mode); broadphases: broadphase_names(); backends:
// backend_names().
const std::vector<std::string>& mode_names();  // ALL, FIRST, COUNT
// The mode of an option's text; OptionError "mode: 'X' is not ALL, FIRST or COUNT" for another.
Mode mode_option(const std::string& text);
// "3 is outside [4, 1020]": an integer setting out of its range, as every layer says it.
std::string outside(uint64_t v, uint64_t lo, uint64_t hi);
// A number as the messages about settings print it (up to 10 significant digits: "1e+12", "0.025").
std::string number_text(double v);

// One object type of a scene and its instance count.
struct SceneTypeSpec {
  std::string key = "types[0]";  // its JSON path, for messages and RunConfig::given
  std::string name = "polytope36";   // label (default: the shape name, or the mesh file's name)
  std::string shape = "polytope36";  // a built-in shape name (or, in the built-in scene, a mesh file), or
  std::string mesh;     // a mesh file, resolved against the scene file's directory
  double size = 0;      // largest extent of the object's box, world units (0: not given)
  double scale = 0;     // factor on the mesh's coordinates (0: not given)
  double voxel = 0;     // voxmap voxel size, world units (0: not given)
  uint32_t resolution = 0;  // or voxels along the object's longest side (0: not given); neither: default_voxel
  uint64_t count = 64;  // instances
  bool auto_scaled() const { return size == 0 && scale == 0; }
};

// Where a setting was given: a scene file's key (`file` the file, `name` the JSON path: "types[0].voxel",
// "environment.density") or an option (`file` empty, `name` the option as OptionError names it: "voxel").
struct SettingSource {
  std::string file;
  std::string name;
};

// A run. The defaults are the paper's scene (64 polytopes filling 2.5% of a cube of side 100, voxel 1) run for 1000
// frames on the cpu backend; WorldDef's fields are how the world runs (broadphase, backend, lanes, mode, both
// directions, distance bits, margin, ccd, threads, the cube's side).
struct RunConfig : WorldDef {
  // The paper's scene tests one direction, A's shell in B's voxmap: the built-in scene keeps it, so `voxcd simulate`
  // runs (and their state hashes) stay the paper's. A world and a scene file test both directions (WorldDef's
  // default; parse_scene_file), unless they say otherwise.
  RunConfig() { both_directions = false; }

  // The scene: the built-in scene when `where` is empty (one type, `shape` a built-in name or a mesh file, scaled so
  // that its objects fill `density` of the cube), else a scene file's types.
  std::string where;  // the scene file, for messages and the summary ("" for the built-in scene)
  std::vector<SceneTypeSpec> types = {SceneTypeSpec{}};
  double density = 0.025;  // fill of the types without a size or scale
  double speed = 0.1;      // largest initial speed per frame, as a fraction of an object's radius
  double spin = 0.02;      // largest initial spin, radians per frame
  uint64_t seed = 1;
  double band = 4.0;       // the distance fields' band, voxels (with distance_bits)
  // How the types' voxmaps, shells and fields are kept (docs/objects.md, "Sparse objects"); sparse types run on a
  // sparse device (device_config_for). Contacts do not depend on it for 2-bit voxmaps; device cycles do.
  ObjectStorage storage = ObjectStorage::kDense;
  // What is asked of the device (voxcd size).
  double accuracy = 0;          // world units; 0: not given (accuracy_or_default)
  double contact_accuracy = 0;  // world units: how far outside the other surface a contact may lie; 0: not given
  double rate = 1000;           // frames per second
  // The device clock of the modelled frame rates when one is given (--clock, the scene file's "clock", Python's
  // clock=), with where; unset: the clock of the run's device configuration, once it is known (run_clock).
  std::optional<DeviceClock> clock;
  uint64_t frames = 1000;  // frames simulated (a scene file's default: 100)
  // How it runs, besides WorldDef.
  // The device's whole configuration (e.g. one `voxcd size` derived); it replaces `lanes` and the memories grown to
  // fit, and its SB decides the distance device. Unset: the default widths with `lanes` and distance_bits.
  std::optional<DeviceConfig> device;
  // Continuous collision: advancement steps per frame; at the cap the bodies still limited keep their place for the
  // rest of the frame (counted in FrameStats::ccd_dropped).
  uint32_t ccd_max_iterations = 64;
  // Before the device, drop broadphase pairs whose oriented boxes (each type's contact bounds grown by one voxel)
  // are disjoint: such a pair has no hit, so results never depend on it.
  bool midphase = true;
  // Submit only the shell points whose clusters can land in the other object's voxmap (PairOptions::cull): results
  // never depend on it, lookups and device cycles do.
  bool cull = true;
  // A distributed run (host/scene/exchange.h, docs/scale.md): this process is one rank; its broadphase and device take
  // only the pairs of its slab, and the exchange gives it every rank's outcomes. Results never depend on the ranks.
  std::shared_ptr<FrameExchange> exchange;
  std::string record;  // a file to record the run to as it goes (host/scene/record.h); "" records nothing
  // The settings given (by the scene file's keys or options; the others have their defaults), keyed by their field:
  // "types[0].voxel", "density", "distance_bits", ... Errors name the source.
  std::map<std::string, SettingSource> given;
  // Deprecated spellings the scene file or the options used, one line each ("s.json: pruning is deprecated: use
  // \"broadphase\" ..."), for the caller to show: the tool on stderr, Python as DeprecationWarnings.
  std::vector<std::string> notes;

  bool builtin() const { return where.empty(); }
  uint64_t objects() const;  // instances of every type
  // The requested accuracy, or by default 1/50 of the smallest voxel of the scene's types (1 where a type gives
  // none: the paper's).
  double accuracy_or_default() const;
  double smallest_voxel() const;
  // The distance bits of the run's device: the whole configuration's SB (0 for 2-bit states), else distance_bits.
  int device_distance_bits() const;
};

// Throws for the first setting that cannot be used, naming it where it was given (SceneFileError for a scene file's
// key, OptionError for an option or for a value set in code, "<field>: ..."): each limit
// above and in host/object, the allowed names (mode, broadphase, backend), settings given together that exclude each
// other (voxel and resolution, size and scale) or need another (band and ccd need distance bits; record is not for
// a distributed run), and a whole device configuration (DeviceConfig::validate).
void check(const RunConfig& c);

// The clock of a run on `device` (its whole configuration, as the run makes it): c.clock when given, else
// clock_for(device), the clock measured for that configuration or an estimate that says so (device/clock.h).
DeviceClock run_clock(const RunConfig& c, const DeviceConfig& device);

// `base` with every setting `options` gives (options.given) in its place: the options override the scene file.
// objects, shape, voxel and resolution apply to the only type (OptionError for a scene file of several);
// voxel replaces resolution and the other way round; a whole device configuration brings its SB as distance_bits
// unless distance_bits is given, and lanes overrides its LANES; threads, midphase, cull, exchange and record always
// come from `options`. The result is checked (check).
RunConfig apply_options(RunConfig base, const RunConfig& options);

}  // namespace voxcd
