#include "voxcd/host/scene/run_config.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <utility>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/device/device.h"

namespace voxcd {

namespace {

std::string joined(const std::vector<std::string>& names, const char* sep = ", ") {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : sep) + n;
  return s;
}

// Checks the settings of one RunConfig, naming each where it was given.
class Checker {
 public:
  explicit Checker(const RunConfig& c) : c_(c) {}

  bool given(const std::string& field) const { return c_.given.count(field) > 0; }
  bool from_file(const std::string& field) const {
    const auto it = c_.given.find(field);
    return it != c_.given.end() && !it->second.file.empty();
  }
  // Throws for `field`: "<file>: <JSON path>: <file_text>" for a scene file's key, OptionError with
  // option_text (file_text when empty) for an option, OptionError "<field>: <file_text>" for a value set in code.
  [[noreturn]] void fail(const std::string& field, const std::string& file_text,
                         const std::string& option_text = "") const {
    const auto it = c_.given.find(field);
    if (it == c_.given.end()) throw OptionError({field}, file_text);
    if (!it->second.file.empty()) throw SceneFileError(it->second.file + ": " + it->second.name + ": " + file_text);
    throw OptionError({it->second.name}, option_text.empty() ? file_text : option_text);
  }
  // A number in [lo, hi] (or (lo, hi] when lo_open).
  void number(const std::string& field, double v, double lo, double hi, bool lo_open,
              const std::string& option_text = "") const {
    if (std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi) return;
    fail(field,
         number_text(v) + " is outside " + (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + "]",
         option_text);
  }
  void integer(const std::string& field, uint64_t v, uint64_t lo, uint64_t hi) const {
    if (v < lo || v > hi) fail(field, outside(v, lo, hi));
  }
  void one_of(const std::string& field, const std::string& v, const std::vector<std::string>& names) const {
    if (std::find(names.begin(), names.end(), v) == names.end())
      fail(field, "'" + v + "' is not one of " + joined(names));
  }

 private:
  const RunConfig& c_;
};

void check_type(const Checker& k, const SceneTypeSpec& t) {
  const std::string p = t.key + ".";
  // A value set in code counts as given when it is not the "not given" 0.
  const auto set = [&](const char* f, double v) { return k.given(p + f) || v != 0; };
  k.integer(p + "count", t.count, 1, kMaxObjects);
  if (set("size", t.size)) k.number(p + "size", t.size, 0, kMaxLength, true);
  if (set("scale", t.scale)) k.number(p + "scale", t.scale, 0, kMaxLength, true);
  if (set("size", t.size) && set("scale", t.scale)) k.fail(t.key, "give \"size\" or \"scale\", not both");
  if (set("voxel", t.voxel) && set("resolution", t.resolution)) {
    if (k.given(p + "voxel") && !k.from_file(p + "voxel"))
      throw OptionError({"voxel", "resolution"},
                                "give the voxel size in world units (--voxel) or the voxels along an object's longest "
                                "side (--resolution), not both");
    k.fail(t.key, "give \"voxel\" (world units) or \"resolution\" (voxels along the longest side), not both");
  }
  if (set("voxel", t.voxel))
    k.number(p + "voxel", t.voxel, 0, kMaxLength, true,
             k.from_file(p + "voxel") ? "" : "must be a positive number of world units");
  if (set("resolution", t.resolution)) k.integer(p + "resolution", t.resolution, kMinVoxelsAcross, kMaxVoxelsAcross);
}

void check_scene(const Checker& k, const RunConfig& c) {
  for (const SceneTypeSpec& t : c.types) check_type(k, t);
  if (c.types.empty()) k.fail("types", "is empty: a scene needs at least one object type");
  k.number("side", c.side, 0, kMaxLength, true);
  k.number("density", c.density, 0, kMaxDensity, true);
  k.number("speed", c.speed, 0, kMaxMotion, false);
  k.number("spin", c.spin, 0, kMaxMotion, false);
  if (k.given("density") && std::none_of(c.types.begin(), c.types.end(), [](auto& t) { return t.auto_scaled(); }))
    k.fail("density", "sizes only the types with no \"size\" or \"scale\", and every type has one");
}

void check_device(const Checker& k, const RunConfig& c) {
  if (k.given("accuracy")) k.number("accuracy", c.accuracy, 0, kMaxLength, true);
  if (k.given("contact_accuracy")) k.number("contact_accuracy", c.contact_accuracy, 0, kMaxLength, true);
  k.number("rate", c.rate, 0, kMaxLength, true);
  if (c.clock) k.number("clock", c.clock->mhz, 0, kMaxClockMhz, true);
  k.integer("frames", c.frames, 1, kMaxFrames);
  if (c.device) c.device->validate();
}

void check_run(const Checker& k, const RunConfig& c) {
  // Names the file's only, for a broadphase or backend given otherwise is refused by make_broadphase or make_device.
  if (k.from_file("broadphase")) k.one_of("broadphase", c.broadphase, broadphase_names());
  if (k.from_file("backend")) k.one_of("backend", c.backend, backend_names());
  if (c.distance_bits != 0 || k.from_file("distance_bits"))
    if (!valid_distance_bits(c.distance_bits))
      k.fail("distance_bits", std::to_string(c.distance_bits) + " is not " + distance_bits_text());
  if (k.given("band")) {
    k.number("band", c.band, 0, kMaxBand, true, k.from_file("band") ? "" : "must be a positive number of voxels");
    // The file's band without the file's distance bits (an option may turn its fields off).
    if (k.from_file("band") && c.distance_bits == 0 && (!k.given("distance_bits") || k.from_file("distance_bits")))
      k.fail("band", "is the band of distance fields: it needs \"distance_bits\"");
  }
  if (!std::isfinite(c.margin)) k.fail("margin", "must be a finite number");
  if (c.ccd && c.device_distance_bits() == 0) {
    if (k.from_file("ccd") && !c.device && !(k.given("distance_bits") && !k.from_file("distance_bits")))
      k.fail("ccd", "continuous collision bounds each step by the distance fields: it needs \"distance_bits\"");
    k.fail("ccd", "continuous collision bounds each step by the distance fields: it needs distance voxmaps "
                  "(--distance-bits " + distance_bits_text() + ")");
  }
  if (c.ccd && !c.response)
    throw OptionError({"ccd", "response"}, "continuous collision ends each approach by the response at the time of "
                                           "impact: it needs the response on");
  if (!c.record.empty() && c.exchange)
    k.fail("record", "a distributed run cannot be recorded yet: record it in one process");
}

}  // namespace

OptionError::OptionError(std::vector<std::string> options_, const std::string& message_)
    : Error(joined(options_) + ": " + message_, joined(options_)), options(std::move(options_)), message(message_) {}

const std::vector<std::string>& mode_names() {
  static const std::vector<std::string> names = {"ALL", "FIRST", "COUNT"};
  return names;
}

Mode mode_option(const std::string& text) {
  const auto m = parse_mode(text);
  if (!m) {
    const auto& n = mode_names();
    throw OptionError({"mode"},
                              "'" + text + "' is not " + joined({n.begin(), n.end() - 1}) + " or " + n.back());
  }
  return *m;
}

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

std::string outside(uint64_t v, uint64_t lo, uint64_t hi) {
  return std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

uint64_t RunConfig::objects() const {
  uint64_t n = 0;
  for (const auto& t : types) n += t.count;
  return n;
}

double RunConfig::smallest_voxel() const {
  double v = 0;
  for (const auto& t : types) {
    const double tv = t.voxel > 0 ? t.voxel : 1.0;
    v = v == 0 ? tv : std::min(v, tv);
  }
  return v;
}

double RunConfig::accuracy_or_default() const { return accuracy > 0 ? accuracy : smallest_voxel() / 50; }

int RunConfig::device_distance_bits() const {
  if (device) return device->distance() ? device->SB : 0;
  return distance_bits;
}

DeviceClock run_clock(const RunConfig& c, const DeviceConfig& device) { return c.clock ? *c.clock : clock_for(device); }

void check(const RunConfig& c) {
  const Checker k(c);
  check_scene(k, c);
  check_device(k, c);
  check_run(k, c);
}

namespace {

using Copy = std::function<void(RunConfig&, const RunConfig&)>;

// How each option's setting replaces the file's (by RunConfig::given's field).
const std::map<std::string, Copy>& option_copies() {
  static const std::map<std::string, Copy> copies = {
      {"types[0].count", [](RunConfig& c, const RunConfig& o) { c.types[0].count = o.types[0].count; }},
      {"types[0].shape",
       [](RunConfig& c, const RunConfig& o) {
         c.types[0].shape = c.types[0].name = o.types[0].shape;
         c.types[0].mesh.clear();
       }},
      {"types[0].voxel",
       [](RunConfig& c, const RunConfig& o) {
         c.types[0].voxel = o.types[0].voxel, c.types[0].resolution = 0;
         c.given.erase("types[0].resolution");
       }},
      {"types[0].resolution",
       [](RunConfig& c, const RunConfig& o) {
         c.types[0].resolution = o.types[0].resolution, c.types[0].voxel = 0;
         c.given.erase("types[0].voxel");
       }},
      {"density", [](RunConfig& c, const RunConfig& o) { c.density = o.density; }},
      {"speed", [](RunConfig& c, const RunConfig& o) { c.speed = o.speed; }},
      {"seed", [](RunConfig& c, const RunConfig& o) { c.seed = o.seed; }},
      {"broadphase", [](RunConfig& c, const RunConfig& o) { c.broadphase = o.broadphase; }},
      {"backend", [](RunConfig& c, const RunConfig& o) { c.backend = o.backend; }},
      {"mode", [](RunConfig& c, const RunConfig& o) { c.mode = o.mode; }},
      {"both_directions", [](RunConfig& c, const RunConfig& o) { c.both_directions = o.both_directions; }},
      {"frames", [](RunConfig& c, const RunConfig& o) { c.frames = o.frames; }},
      {"clock", [](RunConfig& c, const RunConfig& o) { c.clock = o.clock; }},
      {"lanes", [](RunConfig& c, const RunConfig& o) { c.lanes = o.lanes; }},
      {"device", [](RunConfig& c, const RunConfig& o) { c.device = o.device; }},
      {"distance_bits", [](RunConfig& c, const RunConfig& o) { c.distance_bits = o.distance_bits; }},
      {"band", [](RunConfig& c, const RunConfig& o) { c.band = o.band; }},
      {"storage", [](RunConfig& c, const RunConfig& o) { c.storage = o.storage; }},
      {"margin", [](RunConfig& c, const RunConfig& o) { c.margin = o.margin; }},
      {"ccd", [](RunConfig& c, const RunConfig& o) { c.ccd = o.ccd; }},
  };
  return copies;
}

}  // namespace

RunConfig apply_options(RunConfig c, const RunConfig& o) {
  const bool type_option = o.given.count("types[0].count") || o.given.count("types[0].shape") ||
                           o.given.count("types[0].voxel") || o.given.count("types[0].resolution");
  if (o.given.count("types[0].voxel") && o.given.count("types[0].resolution")) check(o);  // names the conflict
  if (type_option && c.types.size() != 1)
    throw OptionError({"objects", "shape", "voxel", "resolution"},
                              "apply only to a scene file with one object type; " + c.where + " has " +
                                  std::to_string(c.types.size()));
  for (const auto& [field, source] : o.given) {
    const auto copy = option_copies().find(field);
    if (copy == option_copies().end()) throw std::logic_error("apply_options: no option sets " + field);
    copy->second(c, o);
    c.given[field] = source;
  }
  if (c.device) {
    c.device->validate();
    if (o.given.count("lanes")) c.device->LANES = o.lanes;
    c.lanes = c.device->LANES;
    // A whole distance configuration without distance bits of its own: the objects' fields take its SB.
    if (!o.given.count("distance_bits") && c.device->distance()) c.distance_bits = c.device->SB;
  }
  c.notes.insert(c.notes.end(), o.notes.begin(), o.notes.end());
  c.threads = o.threads;
  c.midphase = o.midphase;
  c.cull = o.cull;
  c.exchange = o.exchange;
  c.record = o.record;
  check(c);
  return c;
}

}  // namespace voxcd
