#include "voxcd/host/scene/scene_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/device/device.h"

namespace voxcd {

namespace {

using json = nlohmann::json;

// Reads one JSON object's keys with their types, naming the file and the JSON path in every error, and notes each
// key read in the configuration's `given` (by its field) so that check() names it.
class Reader {
 public:
  Reader(const json& j, std::string path, const std::string& where, RunConfig& c)
      : j_(j), path_(std::move(path)), where_(where), c_(c) {
    if (!j_.is_object()) fail(path_, std::string("must be an object, not ") + j_.type_name());
  }

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw SceneFileError(where_ + ": " + (path.empty() ? std::string("(top level)") : path) + ": " + what);
  }
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) const { return j_.contains(key); }
  const json& at(const std::string& key) const { return j_.at(key); }

  // Every key of the object must be one of `known`.
  void only(std::initializer_list<const char*> known) const {
    for (const auto& [k, v] : j_.items()) {
      if (std::none_of(known.begin(), known.end(), [&key = k](const char* n) { return key == n; })) {
        std::string list;
        for (const char* n : known) list += (list.empty() ? "" : ", ") + std::string(n);
        fail(key_path(k), "unknown key (known here: " + list + ")");
      }
    }
  }

  // A value of JSON type `T` (is(v) says whether v is one, `must` what it must be); false when the key is absent.
  template <class T, class Is>
  bool typed(const std::string& key, T& out, const std::string& field, Is is, const char* must) const {
    if (!has(key)) return false;
    const json& v = at(key);
    if (!is(v)) fail(key_path(key), std::string("must be ") + must + ", not " + v.type_name());
    out = v.get<T>();
    note(key, field);
    return true;
  }
  // A number; false when the key is absent. `field` is its RunConfig::given key (by default the key).
  bool number(const std::string& key, double& out, const std::string& field = "") const {
    return typed(key, out, field, [](const json& v) { return v.is_number(); }, "a number");
  }
  // A whole number. [lo, hi] is the setting's range (check()'s), named here only for a value the field cannot hold
  // (negative, or too large): check() refuses the others.
  template <class T>
  bool integer(const std::string& key, T& out, uint64_t lo, uint64_t hi, const std::string& field = "") const {
    if (!has(key)) return false;
    const json& v = at(key);
    if (!v.is_number_integer() && !(v.is_number_float() && std::floor(v.get<double>()) == v.get<double>()))
      fail(key_path(key), std::string("must be an integer, not ") + (v.is_number() ? v.dump() : v.type_name()));
    const double d = v.get<double>();
    if ((v.is_number_integer() && !v.is_number_unsigned() && v.get<int64_t>() < 0) || d < 0 ||
        d >= double(std::numeric_limits<T>::max()) + 1.0)
      fail(key_path(key), v.dump() + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    out = v.is_number_unsigned() ? T(v.get<uint64_t>()) : T(d);
    note(key, field);
    return true;
  }
  // A string, not empty.
  bool string(const std::string& key, std::string& out, const std::string& field = "") const {
    if (!typed(key, out, field, [](const json& v) { return v.is_string(); }, "a string")) return false;
    if (out.empty()) fail(key_path(key), "must not be empty");
    return true;
  }
  bool boolean(const std::string& key, bool& out, const std::string& field = "") const {
    return typed(key, out, field, [](const json& v) { return v.is_boolean(); }, "true or false");
  }
  void one_of(const std::string& key, const std::string& value, const std::vector<std::string>& names) const {
    if (std::find(names.begin(), names.end(), value) != names.end()) return;
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    fail(key_path(key), "'" + value + "' is not one of " + list);
  }

 private:
  void note(const std::string& key, const std::string& field) const {
    c_.given[field.empty() ? key_path(key) : field] = SettingSource{where_, key_path(key)};
  }
  const json& j_;
  std::string path_;
  const std::string& where_;
  RunConfig& c_;
};

// A key given twice in one object (JSON leaves it to the reader; nlohmann keeps the last one, which would silently
// drop the first): found while parsing, with the path of the key in the same form as Reader's errors.
class DuplicateKeys {
 public:
  explicit DuplicateKeys(const std::string& where) : where_(where) {}
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: stack_.push_back({false, 0, {}, {}}); break;
      case json::parse_event_t::array_start: stack_.push_back({true, 0, {}, {}}); break;
      case json::parse_event_t::key: {
        Frame& f = stack_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second) throw SceneFileError(where_ + ": " + path() + ": appears twice in one object");
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack_.pop_back();
        if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
        break;
      case json::parse_event_t::value:
        if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool array;
    size_t index;
    std::string key;
    std::set<std::string> keys;
  };
  std::string path() const {
    std::string p;
    for (const Frame& f : stack_) {
      if (f.array) p += "[" + std::to_string(f.index) + "]";
      else p += (p.empty() ? "" : ".") + f.key;
    }
    return p;
  }
  const std::string& where_;
  std::vector<Frame> stack_;
};

}  // namespace

double accuracy_or_default(const RunConfig& c, const Scene& scene) {
  if (c.accuracy > 0) return c.accuracy;
  double v = 0;
  for (const auto& t : scene.types) v = v == 0 ? t->voxmap().voxel() : std::min(v, t->voxmap().voxel());
  return v > 0 ? v / 50 : c.accuracy_or_default();
}

namespace {

void parse_types(const Reader& top, const std::string& where, RunConfig& f) {
  if (!top.has("types")) top.fail("types", "missing: a scene needs at least one object type");
  const json& types = top.at("types");
  if (!types.is_array()) top.fail("types", std::string("must be an array of object types, not ") + types.type_name());
  if (types.empty()) top.fail("types", "is empty: a scene needs at least one object type");
  const std::filesystem::path dir = std::filesystem::path(where).parent_path();
  f.types.clear();
  for (size_t i = 0; i < types.size(); ++i) {
    SceneTypeSpec t;
    t.key = "types[" + std::to_string(i) + "]";
    t.name = t.shape = "";
    t.count = 1;
    f.given[t.key] = SettingSource{where, t.key};
    const Reader r(types[i], t.key, where, f);
    r.only({"name", "shape", "mesh", "size", "scale", "voxel", "resolution", "count"});
    const bool has_shape = r.string("shape", t.shape), has_mesh = r.string("mesh", t.mesh);
    if (has_shape == has_mesh) r.fail(t.key, "needs exactly one of \"shape\" (a built-in name) and \"mesh\" (a file)");
    if (has_shape) r.one_of("shape", t.shape, shape_names());
    if (has_mesh) {
      t.name = std::filesystem::path(t.mesh).filename().string();
      if (std::filesystem::path(t.mesh).is_relative()) t.mesh = (dir / t.mesh).lexically_normal().string();
    } else {
      t.name = t.shape;
    }
    r.string("name", t.name);
    r.number("size", t.size);
    r.number("scale", t.scale);
    r.number("voxel", t.voxel);
    r.integer("resolution", t.resolution, kMinVoxelsAcross, kMaxVoxelsAcross);
    r.integer("count", t.count, 1, kMaxObjects);
    f.types.push_back(t);
  }
}

// "broadphase", or its deprecated spelling "pruning" (the tool's old option's name) with a note; both must agree.
void parse_broadphase(const Reader& top, const std::string& where, RunConfig& f) {
  std::string pruning;
  const bool old = top.string("pruning", pruning, "broadphase");
  if (old) {
    f.broadphase = pruning;
    f.notes.push_back(where + ": pruning is deprecated: use \"broadphase\" (the same key; docs/scenes.md, "
                              "\"Deprecated spellings\")");
  }
  if (top.string("broadphase", f.broadphase) && old && f.broadphase != pruning)
    top.fail("pruning", "is \"broadphase\"'s deprecated spelling, and names '" + pruning +
                            "' where \"broadphase\" names '" + f.broadphase + "'");
  if (old || top.has("broadphase"))
    top.one_of(top.has("broadphase") ? "broadphase" : "pruning", f.broadphase, broadphase_names());
}

void parse_run(const Reader& top, const std::string& where, RunConfig& f) {
  top.number("accuracy", f.accuracy);
  top.number("contact_accuracy", f.contact_accuracy);
  top.number("rate", f.rate);
  double mhz = 0;
  if (top.number("clock", mhz)) f.clock = DeviceClock{mhz, "given by " + where + "'s \"clock\"", false};
  top.integer("frames", f.frames, 1, kMaxFrames);
  parse_broadphase(top, where, f);
  if (top.string("backend", f.backend)) top.one_of("backend", f.backend, backend_names());
  std::string mode;
  if (top.string("mode", mode)) {
    top.one_of("mode", mode, mode_names());
    f.mode = *parse_mode(mode);
  }
  top.boolean("both_directions", f.both_directions);
  top.integer("distance_bits", f.distance_bits, uint64_t(kDistanceBits.front()), uint64_t(kDistanceBits.back()));
  top.number("band", f.band);
  top.boolean("ccd", f.ccd);
  std::string storage;
  if (top.string("storage", storage)) {
    top.one_of("storage", storage, {"auto", "dense", "sparse"});
    f.storage = *parse_storage(storage);
  }
}

}  // namespace

RunConfig parse_scene_file(std::string_view text, const std::string& where) {
  json j;
  try {
    j = json::parse(text.begin(), text.end(), DuplicateKeys(where));
  } catch (const json::exception& e) {
    // nlohmann's message: "[json.exception.parse_error.101] parse error at line 3, column 5: ..."; a number too
    // large for a double is an out_of_range.406 ("number overflow parsing '1e999'"), not a parse_error.
    std::string what = e.what();
    const auto p = what.find("] ");
    throw SceneFileError(where + ": not valid JSON: " + (p == std::string::npos ? what : what.substr(p + 2)));
  }
  RunConfig f;
  f.where = where;
  f.frames = 100;
  f.both_directions = WorldDef{}.both_directions;  // a world's default; the built-in scene's is the paper's (one)
  const Reader top(j, "", where, f);
  top.only({"types", "environment", "accuracy", "contact_accuracy", "rate", "clock", "frames", "broadphase",
            "backend", "mode", "both_directions", "distance_bits", "band", "ccd", "storage", "pruning"});
  parse_types(top, where, f);
  if (top.has("environment")) {
    const Reader e(top.at("environment"), "environment", where, f);
    e.only({"side", "density", "speed", "spin", "seed"});
    e.number("side", f.side, "side");
    e.number("density", f.density, "density");
    e.number("speed", f.speed, "speed");
    e.number("spin", f.spin, "spin");
    e.integer("seed", f.seed, 0, ~uint64_t{0}, "seed");
  }
  parse_run(top, where, f);
  check(f);
  return f;
}

RunConfig read_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneFileError(path + ": cannot open the scene file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw SceneFileError(path + ": cannot read the scene file");
  return parse_scene_file(s.str(), path);
}

namespace {

// A type's mesh as the scene uses it, and what its scale came from.
struct LoadedType {
  Mesh mesh;  // centred on its box's centre; scaled by s once load_types returns
  std::string source;
  uint64_t hash = 0;
  double extent = 0, volume = 0, s = 0;  // extent and volume before scaling
};
struct LoadedTypes {
  std::vector<LoadedType> types;
  double fixed_volume = 0;  // of the types with a size or scale
  uint64_t auto_count = 0;  // instances of the types without
};

// The scene file's meshes, centred and scaled as make_scene places them in their types' frames; SceneFileError
// naming the key for a missing or unreadable mesh or a fill that does not fit the cube.
LoadedTypes load_types(const RunConfig& f) {
  auto fail = [&](const std::string& path, const std::string& what) -> SceneFileError {
    return SceneFileError(f.where + ": " + path + ": " + what);
  };
  if (f.types.empty()) throw fail("types", "is empty: a scene needs at least one object type");
  const double cube = f.side * f.side * f.side;
  LoadedTypes lt;
  std::vector<LoadedType>& loaded = lt.types;
  loaded.resize(f.types.size());
  double& fixed_volume = lt.fixed_volume;
  uint64_t& auto_count = lt.auto_count;
  for (size_t i = 0; i < f.types.size(); ++i) {
    const SceneTypeSpec& t = f.types[i];
    LoadedType& l = loaded[i];
    if (!t.mesh.empty()) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(t.mesh, ec))
        throw fail(t.key + ".mesh", "'" + t.mesh + "' is not a readable file");
    }
    try {
      l.mesh = t.mesh.empty() ? load_source(t.shape, &l.source, &l.hash) : load_mesh(t.mesh);
      if (!t.mesh.empty()) {
        l.source = t.mesh;
        l.hash = hash_file(t.mesh);
      }
    } catch (const std::exception& e) {
      throw fail(t.key + (t.mesh.empty() ? ".shape" : ".mesh"), e.what());
    }
    Eigen::Vector3d lo, hi;
    l.mesh.bounds(lo, hi);
    const Eigen::Vector3d mid = 0.5 * (lo + hi);
    for (auto& v : l.mesh.vertices) v -= mid;
    l.extent = (hi - lo).maxCoeff();
    l.volume = l.mesh.volume();
    if (t.size > 0) l.s = t.size / l.extent;
    if (t.scale > 0) l.s = t.scale;
    if (l.s > 0)
      fixed_volume += double(t.count) * l.volume * l.s * l.s * l.s;
    else
      auto_count += t.count;
  }
  if (auto_count > 0) {
    // Evaluated as make_scene does, so that one auto-scaled type gets exactly its scale.
    const double left = f.density * f.side * f.side * f.side - fixed_volume;
    if (!(left > 0))
      throw fail("environment.density", number_text(f.density) + " of the cube is " + number_text(f.density * cube) +
                                            ", and the types with a size or scale already fill " +
                                            number_text(fixed_volume));
    for (size_t i = 0; i < f.types.size(); ++i)
      if (f.types[i].auto_scaled()) loaded[i].s = std::cbrt(left / double(auto_count) / loaded[i].volume);
  } else if (fixed_volume > kMaxDensity * cube) {
    throw fail("types", "the objects fill " + number_text(fixed_volume / cube) + " of the cube, above " +
                            number_text(kMaxDensity));
  }
  for (LoadedType& l : loaded)
    for (auto& v : l.mesh.vertices) v *= l.s;
  return lt;
}

}  // namespace

std::vector<Mesh> scene_meshes(const RunConfig& f) {
  std::vector<Mesh> meshes;
  for (LoadedType& l : load_types(f).types) meshes.push_back(std::move(l.mesh));
  return meshes;
}

namespace {

// Each type's voxel: given, from its resolution, or the default (the built-in scene's rule, evaluated alike so that
// one auto-scaled type gets exactly the built-in scene's voxel); SceneFileError naming the key at fault for a voxel
// that makes an object too large or too small for a voxmap.
std::vector<double> type_voxels(const RunConfig& f, const LoadedTypes& lt) {
  auto fail = [&](const std::string& path, const std::string& what) -> SceneFileError {
    return SceneFileError(f.where + ": " + path + ": " + what);
  };
  const std::vector<LoadedType>& loaded = lt.types;
  std::vector<double> voxel(f.types.size());
  for (size_t i = 0; i < f.types.size(); ++i) {
    const SceneTypeSpec& t = f.types[i];
    const LoadedType& l = loaded[i];
    const double extent = l.extent * l.s;
    const double one = t.auto_scaled()
                           ? (f.density * f.side * f.side * f.side - lt.fixed_volume) / double(lt.auto_count)
                           : l.volume * l.s * l.s * l.s;
    try {
      voxel[i] = t.voxel > 0 ? t.voxel : t.resolution > 0 ? voxel_for_resolution(l.mesh, t.resolution)
                                                          : default_voxel(one, extent);
    } catch (const std::exception& e) {
      throw fail(t.key + ".resolution", e.what());
    }
    // The key at fault, and what it asked.
    const std::string key = t.key + (t.voxel > 0 ? ".voxel" : t.resolution > 0 ? ".resolution" : "");
    const std::string what = t.voxel > 0        ? number_text(t.voxel)
                              : t.resolution > 0 ? "resolution " + std::to_string(t.resolution) + " (voxel " +
                                                       number_text(voxel[i]) + ")"
                                                 : "the default voxel " + number_text(voxel[i]);
    if (extent / voxel[i] > kMaxVoxelsAcross)
      throw fail(key, what + " makes the object " + number_text(std::ceil(extent / voxel[i])) + " voxels across (" +
                          number_text(extent) + " world units), above 2^10");
    if (extent / voxel[i] < 2)
      throw fail(key, what + " is larger than half the object (" + number_text(extent) +
                          " across); it would be a voxel or two");
    if (extent / voxel[i] < kMinVoxelsAcross)
      throw fail(key, what + " leaves " + number_text(extent / voxel[i]) + " voxels along the object's longest side (" +
                          number_text(extent) + " world units); at least " + std::to_string(kMinVoxelsAcross) +
                          " are needed: a voxel of at most " + number_text(extent / kMinVoxelsAcross) +
                          ", or a \"resolution\"");
  }
  return voxel;
}

}  // namespace

Scene make_file_scene(const RunConfig& f) {
  auto fail = [&](const std::string& path, const std::string& what) -> SceneFileError {
    return SceneFileError(f.where + ": " + path + ": " + what);
  };
  LoadedTypes lt = load_types(f);
  const std::vector<LoadedType>& loaded = lt.types;
  const uint64_t auto_count = lt.auto_count;
  const std::vector<double> voxel = type_voxels(f, lt);
  // Every shell is fine enough for the smallest voxmap of the scene (the paper's sqrt(2) rule against it).
  const double vmin = *std::min_element(voxel.begin(), voxel.end());
  Scene scene;
  scene.side = f.side;
  for (size_t i = 0; i < f.types.size(); ++i) {
    const SceneTypeSpec& t = f.types[i];
    const LoadedType& l = loaded[i];
    ObjectOptions oo;
    oo.voxel = voxel[i];
    oo.shell_ratio = std::sqrt(2.0) * (voxel[i] / vmin);
    oo.distance_bits = f.distance_bits;
    oo.band = f.band;
    set_storage(oo, f.storage);
    try {
      auto type = std::make_shared<ObjectType>(make_object_type(make_object(l.mesh, l.source, l.hash, oo), t.name));
      type->mesh = std::make_shared<const Mesh>(l.mesh);
      scene.types.push_back(std::move(type));
    } catch (const std::exception& e) {
      throw fail(t.key, e.what());
    }
    if (2 * scene.types.back()->radius >= f.side)
      throw fail(t.key, "the object (radius " + number_text(scene.types.back()->radius) +
                            ") does not fit the cube of side " + number_text(f.side));
  }
  // With one type, the same draws as the built-in scene, so the same bodies.
  std::vector<uint64_t> counts;
  for (const auto& t : f.types) counts.push_back(t.count);
  try {
    place_bodies(scene, counts, f.speed, f.spin, f.seed);
  } catch (const PlacementError& e) {
    const auto& t = f.types[e.type];
    throw fail(t.key + ".count", "could not place instance " + std::to_string(e.instance) + " of " +
                                     std::to_string(t.count) + " without overlapping another (the cube is too full): " +
                                     "even packed on a lattice, bounding spheres of radius " + number_text(e.radius) +
                                     " (the scene's largest) fit at most " + std::to_string(e.capacity) + " of the " +
                                     std::to_string(f.objects()) + " objects" +
                                     (auto_count > 0 ? "; lower environment.density (" + number_text(f.density) +
                                                           ") or the counts"
                                                     : "; lower the counts or sizes"));
  }
  return scene;
}

}  // namespace voxcd
