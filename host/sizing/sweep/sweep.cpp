#include "voxcd/host/sizing/sweep/sweep.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "voxcd/host/detail/cross_product.h"
#include "voxcd/host/detail/text_file.h"
#include "voxcd/host/device/clock.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/sizing/contact_bound.h"
#include "voxcd/host/sizing/sweep/contact_measure.h"
#include "voxcd/host/sizing/depth.h"
#include "voxcd/host/sizing/digits.h"

// A point's yosys cost in a results row: an object of its numbers, or null when not synthesised.
namespace nlohmann {
template <>
struct adl_serializer<std::optional<voxcd::YosysCost>> {
  template <class Json>
  static void to_json(Json& j, const std::optional<voxcd::YosysCost>& c) {
    if (c)
      j = {{"luts", c->luts}, {"ffs", c->ffs}, {"dsps", c->dsps}, {"brams", c->brams}, {"seconds", c->seconds}};
    else
      j = nullptr;
  }
  template <class Json>
  static void from_json(const Json& j, std::optional<voxcd::YosysCost>& c) {
    c.reset();
    if (j.is_null()) return;
    voxcd::YosysCost y;
    y.luts = j.at("luts").template get<uint64_t>();
    y.ffs = j.at("ffs").template get<uint64_t>();
    y.dsps = j.at("dsps").template get<uint64_t>();
    y.brams = j.at("brams").template get<double>();
    y.seconds = j.at("seconds").template get<double>();
    c = y;
  }
};
}  // namespace nlohmann

namespace voxcd {

namespace {

std::string num(double v) { return detail::digits_text(v, 6); }

bool power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

using json = nlohmann::ordered_json;

}  // namespace

std::string SweepPoint::text() const {
  return "lanes " + std::to_string(lanes) + ", depth " + std::to_string(depth) + ", voxel x" + num(voxel_scale) +
         ", distance bits " +
         std::to_string(distance_bits) + ", accuracy " + num(accuracy);
}

SweepPoint point_at(const SweepSpec& s, uint64_t index) {
  if (index >= s.points())
    throw std::out_of_range("point " + std::to_string(index) + " of a sweep of " + std::to_string(s.points()));
  SweepPoint p;
  p.index = index;
  const auto d = detail::cross_product_digits(
      index, {s.accuracies.size(), s.distance_bits.size(), s.voxel_scales.size(), s.depths.size(), s.lanes.size()});
  p.accuracy = s.accuracies[d[0]];
  p.distance_bits = s.distance_bits[d[1]];
  p.voxel_scale = s.voxel_scales[d[2]];
  p.depth = s.depths[d[3]];
  p.lanes = s.lanes[d[4]];
  return p;
}

std::vector<double> parse_number_list(const std::string& text, const std::string& what) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size())
      throw SweepError(what + ": '" + item + "' is not a number (expected a comma-separated list such as 1,2,4)");
    v.push_back(x);
  }
  if (v.empty() || (!text.empty() && text.back() == ','))
    throw SweepError(what + ": '" + text + "' is not a comma-separated list of numbers");
  return v;
}

void check_sweep(const SweepSpec& s, const std::string& where) {
  auto fail = [&](const std::string& key, const std::string& what) { return SweepError(where + ": " + key + ": " + what); };
  if (s.lanes.empty()) throw fail("lanes", "is empty");
  if (s.depths.empty()) throw fail("depth", "is empty");
  if (s.voxel_scales.empty()) throw fail("voxel_scale", "is empty");
  if (s.distance_bits.empty()) throw fail("distance_bits", "is empty");
  if (s.accuracies.empty()) throw fail("accuracy", "is empty");
  for (size_t i = 0; i < s.lanes.size(); ++i)
    if (!power_of_two(s.lanes[i]) || s.lanes[i] > 64)
      throw fail("lanes[" + std::to_string(i) + "]", std::to_string(s.lanes[i]) +
                                                         " is not a power of two from 1 to 64 (the RTL's lanes)");
  for (size_t i = 0; i < s.depths.size(); ++i) {
    try {
      at_depth(DeviceConfig{}, s.depths[i]);
    } catch (const ConfigError& e) {
      throw fail("depth[" + std::to_string(i) + "]", e.what());
    }
  }
  for (size_t i = 0; i < s.voxel_scales.size(); ++i)
    if (!(s.voxel_scales[i] > 0) || !std::isfinite(s.voxel_scales[i]))
      throw fail("voxel_scale[" + std::to_string(i) + "]", num(s.voxel_scales[i]) + " is not a positive number");
  for (size_t i = 0; i < s.distance_bits.size(); ++i) {
    const int b = s.distance_bits[i];
    if (b != 0 && !valid_distance_bits(b))
      throw fail("distance_bits[" + std::to_string(i) + "]",
                 std::to_string(b) + " is not 0 (2-bit states), " + distance_bits_text());
  }
  for (size_t i = 0; i < s.accuracies.size(); ++i)
    if (!(s.accuracies[i] > 0) || !std::isfinite(s.accuracies[i]))
      throw fail("accuracy[" + std::to_string(i) + "]", num(s.accuracies[i]) + " is not a positive number of world "
                                                                               "units");
  if (!(s.clock >= 0) || !std::isfinite(s.clock)) throw fail("clock", num(s.clock) + " is not a positive number of MHz");
  if (s.frames > kMaxFrames) throw fail("frames", std::to_string(s.frames) + " is above " + std::to_string(kMaxFrames));
  if (s.frames > 0 && s.sample_frames > s.frames)
    throw fail("sample_frames", std::to_string(s.sample_frames) + " is more than the " + std::to_string(s.frames) +
                                    " frames measured");
}

namespace {

// A JSON value as a list of numbers (a single number is a list of one); SweepError naming the key otherwise.
std::vector<double> number_list(const json& v, const std::string& where, const std::string& key) {
  std::vector<double> out;
  if (v.is_number()) return {v.get<double>()};
  if (!v.is_array()) throw SweepError(where + ": " + key + ": expected a list of numbers, got " + v.dump());
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number())
      throw SweepError(where + ": " + key + "[" + std::to_string(i) + "]: expected a number, got " + v[i].dump());
    out.push_back(v[i].get<double>());
  }
  return out;
}

std::vector<int> int_list(const json& v, const std::string& where, const std::string& key) {
  std::vector<int> out;
  const std::vector<double> d = number_list(v, where, key);
  for (size_t i = 0; i < d.size(); ++i) {
    if (d[i] != std::floor(d[i]) || std::abs(d[i]) > 1e6)
      throw SweepError(where + ": " + key + "[" + std::to_string(i) + "]: " + num(d[i]) + " is not a whole number");
    out.push_back(int(d[i]));
  }
  return out;
}

uint64_t count_of(const json& v, const std::string& where, const std::string& key) {
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
    throw SweepError(where + ": " + key + ": expected a whole number of frames, got " + v.dump());
  return v.get<uint64_t>();
}

}  // namespace

SweepSpec parse_sweep_file(const std::string& text, const std::string& where, SweepSpec s) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw SweepError(where + ": not JSON: " + e.what());
  }
  if (!j.is_object()) throw SweepError(where + ": expected a JSON object of sweep keys, got " + j.dump());
  for (const auto& [key, v] : j.items()) {
    if (key == "lanes") s.lanes = int_list(v, where, key);
    else if (key == "depth") s.depths = int_list(v, where, key);
    else if (key == "voxel_scale") s.voxel_scales = number_list(v, where, key);
    else if (key == "distance_bits") s.distance_bits = int_list(v, where, key);
    else if (key == "accuracy") s.accuracies = number_list(v, where, key);
    else if (key == "frames") s.frames = count_of(v, where, key);
    else if (key == "sample_frames") s.sample_frames = count_of(v, where, key);
    else if (key == "clock") {
      if (!v.is_number() || !(v.get<double>() > 0))
        throw SweepError(where + ": clock: expected a positive number of MHz, got " + v.dump());
      const DeviceClock c = given_clock(v.get<double>(), where + "'s \"clock\"");
      s.clock = c.mhz;
      s.clock_source = c.source;
    } else if (key == "cost") {
      if (!v.is_boolean()) throw SweepError(where + ": cost: expected true or false, got " + v.dump());
      s.cost = v.get<bool>();
    } else {
      throw SweepError(where + ": " + key + ": unknown key (the keys: lanes, depth, voxel_scale, distance_bits, "
                                            "accuracy, frames, sample_frames, clock, cost)");
    }
  }
  return s;
}

SweepSpec read_sweep_file(const std::string& path, SweepSpec base) {
  const std::optional<std::string> text = detail::read_text_file(path);
  if (!text) throw SweepError(path + ": cannot read the sweep file");
  return parse_sweep_file(*text, path, std::move(base));
}

namespace {

// A key of the sweep's JSON and the member it holds; `optional`: a file written before the key existed may leave it
// out, and the member keeps its default.
template <class S, class T>
struct Field {
  const char* key;
  T S::*member;
  bool optional;
};
template <class S, class T>
constexpr Field<S, T> field(const char* key, T S::*member, bool optional = false) {
  return {key, member, optional};
}

// The keys in the order they are written: the sweep (results files before depths: {0}), a point and the rest of a
// row (rows before depths: 0; before conservative cells: none of those, and before latency: 0).
constexpr auto kSpecFields = std::make_tuple(
    field("scene", &SweepSpec::scene), field("lanes", &SweepSpec::lanes), field("depth", &SweepSpec::depths, true),
    field("voxel_scale", &SweepSpec::voxel_scales), field("distance_bits", &SweepSpec::distance_bits),
    field("accuracy", &SweepSpec::accuracies), field("frames", &SweepSpec::frames),
    field("sample_frames", &SweepSpec::sample_frames), field("clock", &SweepSpec::clock),
    field("clock_source", &SweepSpec::clock_source), field("cost", &SweepSpec::cost),
    field("rtl_dir", &SweepSpec::rtl_dir));
constexpr auto kPointFields = std::make_tuple(
    field("point", &SweepPoint::index), field("lanes", &SweepPoint::lanes), field("depth", &SweepPoint::depth, true),
    field("voxel_scale", &SweepPoint::voxel_scale), field("distance_bits", &SweepPoint::distance_bits),
    field("accuracy", &SweepPoint::accuracy));
constexpr auto kRowFields = std::make_tuple(
    field("status", &SweepRow::status), field("config", &SweepRow::config),
    field("error_bound", &SweepRow::error_bound), field("contact_bound", &SweepRow::contact_bound),
    field("contact_measured", &SweepRow::contact_measured), field("contacts_checked", &SweepRow::contacts_checked),
    field("contacts_conservative", &SweepRow::contacts_conservative, true),
    field("contact_measured_conservative", &SweepRow::contact_measured_conservative, true),
    field("contact_bound_conservative", &SweepRow::contact_bound_conservative, true),
    field("latency", &SweepRow::latency, true), field("max_cycles", &SweepRow::max_cycles),
    field("mean_cycles", &SweepRow::mean_cycles), field("rate", &SweepRow::rate),
    field("clock_mhz", &SweepRow::clock_mhz, true), field("clock_source", &SweepRow::clock_source, true),
    field("clock_estimate", &SweepRow::clock_estimate, true),
    field("shell_bits", &SweepRow::shell_bits), field("map_bits", &SweepRow::map_bits),
    field("cost", &SweepRow::cost), field("rank", &SweepRow::rank), field("seconds", &SweepRow::seconds));

// j[key] = s.*member for every field of the table, in its order.
template <class S, class Table>
void put_fields(json& j, const S& s, const Table& table) {
  std::apply([&](const auto&... f) { ((j[f.key] = s.*(f.member)), ...); }, table);
}

template <class S, class T>
void get_field(const json& j, S& s, const Field<S, T>& f) {
  if (f.optional && !j.contains(f.key)) return;
  s.*(f.member) = j.at(f.key).template get<T>();
}

// s.*member = j[key] for every field of the table (json::exception for a missing key or a wrong type).
template <class S, class Table>
void get_fields(const json& j, S& s, const Table& table) {
  std::apply([&](const auto&... f) { (get_field(j, s, f), ...); }, table);
}

}  // namespace

std::string sweep_json(const SweepSpec& s) {
  json j;
  put_fields(j, s, kSpecFields);
  return j.dump();
}

SweepSpec sweep_from_json(const std::string& text, const std::string& where) {
  try {
    SweepSpec s;
    get_fields(json::parse(text), s, kSpecFields);
    return s;
  } catch (const json::exception& e) {
    throw SweepError(where + ": not a sweep: " + e.what());
  }
}

std::string sweep_row_line(const SweepRow& r) {
  json j;
  put_fields(j, r.point, kPointFields);
  put_fields(j, r, kRowFields);
  return j.dump();
}

SweepRow parse_sweep_row(const std::string& line, const std::string& where) {
  try {
    const json j = json::parse(line);
    SweepRow r;
    get_fields(j, r.point, kPointFields);
    get_fields(j, r, kRowFields);
    return r;
  } catch (const json::exception& e) {
    throw SweepError(where + ": not a sweep row: " + e.what());
  }
}

SweepRunner::SweepRunner(const SweepSpec& s) : spec_(s) {
  file_ = read_scene_file(s.scene);
  const Scene base = make_scene(file_);
  for (const auto& t : base.types) voxels_.push_back(t->voxmap().voxel());
  convex_ = types_convex(file_);
  meshes_ = scene_meshes(file_);
  if (!(spec_.clock > 0) && file_.clock) spec_.clock = file_.clock->mhz, spec_.clock_source = file_.clock->source;
  frames_ = s.frames > 0 ? s.frames : file_.frames;
}

DeviceClock SweepRunner::clock_of(const DeviceConfig& cfg) const {
  return spec_.clock > 0 ? DeviceClock{spec_.clock, spec_.clock_source, false} : clock_for(cfg);
}

const Scene& SweepRunner::scene_for(const RunConfig& f, double scale, int bits) {
  auto& slot = scenes_[{scale, bits}];
  if (!slot) slot = std::make_shared<const Scene>(make_scene(f));
  return *slot;
}

namespace {
// The row of a point no device meets: its status says why, every number is 0.
SweepRow infeasible(const SweepPoint& p, const std::string& why) {
  SweepRow r;
  r.point = p;
  r.status = "infeasible: " + why;
  return r;
}
}  // namespace

SweepRow SweepRunner::run(uint64_t index) {
  const auto t0 = std::chrono::steady_clock::now();
  SweepRow r;
  r.point = point_at(spec_, index);
  const SweepPoint p = r.point;
  // The scene file of the point: every type's voxel scaled, the voxmap kind set.
  RunConfig f = file_;
  for (size_t i = 0; i < f.types.size(); ++i) {
    f.types[i].voxel = voxels_[i] * p.voxel_scale;
    f.types[i].resolution = 0;
    f.given.erase(f.types[i].key + ".resolution");
  }
  f.distance_bits = p.distance_bits;
  try {
    const Scene& scene = scene_for(f, p.voxel_scale, p.distance_bits);
    const VoxmapKind kind = p.distance_bits ? VoxmapKind{p.distance_bits, DeviceConfig{}.WB, f.band} : VoxmapKind{};
    const SceneExtents e = scene_extents(scene);
    DeviceConfig base;
    base.SB = kind.SB;
    base.WB = kind.WB;
    base.LANES = p.lanes;
    base = at_depth(base, p.depth);
    DeviceConfig cfg = derive_widths(e, p.accuracy, base, kind.distance() ? kind.WB : 0);
    cfg = derive_memory(cfg, scene);
    cfg.validate();
    r.config = cfg.to_string();
    r.latency = latency_cycles(cfg);
    r.error_bound = size_error_bound(cfg, e);
    r.contact_bound = contact_error_bound(cfg, e, kind, convex_);
    const LaneMeasure m = measure_frames(scene, f, cfg, frames_);
    r.max_cycles = m.max_cycles;
    r.mean_cycles = m.mean_cycles;
    const DeviceClock clock = clock_of(cfg);
    r.clock_mhz = clock.mhz, r.clock_source = clock.source, r.clock_estimate = clock.estimate;
    r.rate = clock.rate(double(m.max_cycles));
    const ContactMeasure c = measure_contacts(scene, f, cfg, meshes_, frames_, spec_.sample_frames);
    r.contact_measured = c.worst_outside;
    r.contacts_checked = c.contacts;
    if (kind.distance()) {
      r.contacts_conservative = c.conservative;
      r.contact_measured_conservative = c.worst_outside_conservative;
      r.contact_bound_conservative = contact_error_bound(cfg, e, VoxmapKind{}, convex_);
    }
    r.shell_bits = shell_memory_bits(cfg);
    r.map_bits = map_memory_bits(cfg);
    if (spec_.cost) r.cost = yosys_cost(cfg, spec_.rtl_dir);
  } catch (const SizeError& e) {
    r = infeasible(p, e.what());
  } catch (const SceneFileError& e) {
    r = infeasible(p, e.what());
  } catch (const CapacityError& e) {
    r = infeasible(p, e.what());
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace voxcd
