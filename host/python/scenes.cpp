// Scenes: voxcd.simulate (the built-in scene, a scene file or a scene as a dict, run as `voxcd simulate` runs it,
// with the same summary) and voxcd.size (the smallest device for a scene, the report of `voxcd size --json`).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <utility>

#include "voxcd/host/python/bindings.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/vectors.h"

namespace voxcd::python {

namespace {

// Adds the keyword arguments' names and values (py::arg("key") = value, ...) to d, in their order.
template <class... Items>
void put(py::dict& d, Items&&... items) {
  for (const auto& [key, value] : py::dict(std::forward<Items>(items)...)) d[key] = value;
}

// An optional non-negative integer argument (a Python int or anything with __index__).
std::optional<uint64_t> count_arg(const py::object& o, const char* name) {
  if (o.is_none()) return std::nullopt;
  if (py::isinstance<py::bool_>(o) || !PyIndex_Check(o.ptr()))
    throw py::type_error(std::string(name) + " must be an int, not " +
                         py::str(py::type::handle_of(o).attr("__name__")).cast<std::string>());
  const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(o.ptr()));
  const unsigned long long v = PyLong_AsUnsignedLongLong(i.ptr());
  if (PyErr_Occurred()) {
    PyErr_Clear();
    value_error(std::string(name) + ": " + py::repr(i).cast<std::string>() + " is not an integer in [0, 2^64)");
  }
  return uint64_t(v);
}

// A scene argument: a scene file (path), or a dict with a scene file's keys (docs/scenes.md), named "scene" in
// messages and with mesh paths relative to the working directory. Sets `file` and, for a dict, `text`.
void scene_arg(const py::object& scene, std::string& file, std::optional<std::string>& text) {
  if (py::isinstance<py::dict>(scene)) {
    file = "scene";
    text = py::module_::import("json").attr("dumps")(scene).cast<std::string>();
  } else {
    file = path_arg(scene, "scene");
  }
}

// The clock argument (MHz), its source "given by the clock argument"; ValueError "clock: ..." for zero, negative,
// NaN or infinity.
DeviceClock clock_arg(double mhz) {
  const std::string problem = clock_problem(mhz);
  if (!problem.empty()) value_error("clock: " + problem);
  return given_clock(mhz, "the clock argument");
}

// The scene file's object types, as `voxcd simulate --json` lists them.
py::list types_list(const SimulationSummary& s) {
  py::list types;
  for (const auto& ty : s.types)
    types.append(py::dict(py::arg("name") = ty->name, py::arg("voxel") = ty->voxmap().voxel(),
                          py::arg("shell_count") = ty->shell().size(),
                          py::arg("shell_points") = ty->shell().size()));
  return types;
}

// The summary's configuration: the scene and how it ran, in the order of `voxcd simulate --json`.
void put_config(py::dict& r, const SimulationSummary& s) {
  const RunConfig& c = s.config;
  const ObjectType& type = *s.types[0];
  const auto& d = type.voxmap().dims();
  if (!c.builtin()) put(r, py::arg("scene") = c.where, py::arg("types") = types_list(s));
  put(r, py::arg("device") = s.device.to_string(), py::arg("shape") = s.shape(), py::arg("objects") = c.objects(),
      py::arg("voxel") = s.voxel(), py::arg("shell_count") = type.shell().size(),
      py::arg("shell_points") = type.shell().size(), py::arg("voxmap") = py::make_tuple(d[0], d[1], d[2]),
      py::arg("broadphase") = c.broadphase, py::arg("pruning") = c.broadphase,
      py::arg("backend") = c.backend, py::arg("mode") = mode_name(c.mode), py::arg("both_directions") = c.both_directions);
  if (s.distance_bits())
    put(r, py::arg("distance_bits") = s.distance_bits(), py::arg("band") = c.band, py::arg("margin") = c.margin,
        py::arg("ccd") = c.ccd);
  put(r, py::arg("frames") = c.frames, py::arg("seed") = c.seed);
}

// The run's totals: counters, then the seconds of each stage and, with ccd, the counters of no_tunnelling.
void put_totals(py::dict& r, const SimulationSummary& s) {
  const SimulationTotals& t = s.totals;
  put(r, py::arg("seconds") = t.seconds(), py::arg("frame_rate_hz") = s.frame_rate(),
      py::arg("broadphase_pairs") = t.pairs, py::arg("pairs_tested") = t.tested, py::arg("touching_pairs") = t.touching,
      py::arg("responses") = t.responses, py::arg("wall_bounces") = t.wall_hits, py::arg("lookups") = t.lookups,
      py::arg("hits") = t.hits, py::arg("contacts") = t.contacts);
  r["stage_seconds"] = py::dict(py::arg("integrate") = t.t_integrate, py::arg("bounds") = t.t_bounds,
                                py::arg("broadphase") = t.t_broadphase, py::arg("narrow") = t.t_narrow,
                                py::arg("response") = t.t_response);
  if (s.config.ccd)
    r["no_tunnelling"] = py::dict(py::arg("iterations") = t.ccd_iterations, py::arg("queries") = t.ccd_queries,
                                  py::arg("pairs_limited") = t.ccd_limited, py::arg("time_of_impact_events") = t.ccd_toi,
                                  py::arg("bodies_dropped") = t.ccd_dropped, py::arg("lookups") = t.ccd_lookups);
}

// The summary as a dict with the keys and numbers of `voxcd simulate --json` (the state hash as a hex string).
py::dict summary_dict(const SimulationSummary& s) {
  const RunConfig& c = s.config;
  const SimulationTotals& t = s.totals;
  py::dict r;
  put_config(r, s);
  put_totals(r, s);
  char hash[24];
  std::snprintf(hash, sizeof hash, "%llx", static_cast<unsigned long long>(s.state_hash));
  // No device cycles: no device rate (None), as `voxcd simulate --json` gives null.
  put(r, py::arg("lanes") = c.lanes, py::arg("device_cycles") = t.cycles,
      py::arg("device_cycles_per_frame") = s.cycles_per_frame(), py::arg("device_cycles_max_frame") = t.max_cycles,
      py::arg("device_idle_frames") = t.idle_frames, py::arg("clock_mhz") = s.clock.mhz,
      py::arg("clock_source") = s.clock.source, py::arg("clock_estimate") = s.clock.estimate,
      py::arg("device_frame_rate_hz") = t.cycles ? py::object(py::float_(s.device_rate())) : py::object(py::none()),
      py::arg("state_hash") = std::string(hash));
  return r;
}

}  // namespace

RunConfig run_options(const RunArgs& a, const py::object& record, std::optional<std::string>& text) {
  RunConfig o;
  SceneTypeSpec& t = o.types[0];
  // Notes a keyword given: the setting's field and the keyword that names it in messages.
  auto give = [&](const char* field, const char* keyword) { o.given[field] = SettingSource{"", keyword}; };
  if (!a.scene.is_none()) scene_arg(a.scene, o.where, text);
  if (const auto f = count_arg(a.frames, "frames")) o.frames = *f, give("frames", "frames");
  if (const auto n = count_arg(a.objects, "objects")) t.count = *n, give("types[0].count", "objects");
  if (a.shape) t.shape = *a.shape, give("types[0].shape", "shape");
  if (a.voxel) t.voxel = *a.voxel, give("types[0].voxel", "voxel");
  if (const auto r = count_arg(a.resolution, "resolution")) {
    if (*r > UINT32_MAX) value_error("resolution: " + outside(*r, kMinVoxelsAcross, kMaxVoxelsAcross));
    t.resolution = uint32_t(*r), give("types[0].resolution", "resolution");
  }
  if (a.density) o.density = *a.density, give("density", "density");
  if (a.speed) o.speed = *a.speed, give("speed", "speed");
  if (const auto sd = count_arg(a.seed, "seed")) o.seed = *sd, give("seed", "seed");
  if (a.broadphase) o.broadphase = *a.broadphase, give("broadphase", "broadphase");
  if (a.pruning) {
    if (a.broadphase && *a.broadphase != *a.pruning)
      value_error("pruning: is broadphase's deprecated spelling, and names '" + *a.pruning + "' where broadphase "
                  "names '" + *a.broadphase + "'");
    deprecation("pruning is deprecated: use broadphase (the same keyword; docs/python.md, \"Deprecated spellings\")");
    o.broadphase = *a.pruning, give("broadphase", "broadphase");
  }
  if (a.backend) o.backend = *a.backend, give("backend", "backend");
  if (a.lanes) o.lanes = *a.lanes, give("lanes", "lanes");
  if (a.mode) o.mode = mode_option(*a.mode), give("mode", "mode");
  if (const auto b = both_directions_arg(a.both_directions, a.both))
    o.both_directions = *b, give("both_directions", a.both ? "both" : "both_directions");
  if (a.clock) o.clock = clock_arg(*a.clock), give("clock", "clock");
  if (a.distance_bits) o.distance_bits = *a.distance_bits, give("distance_bits", "distance_bits");
  if (a.band) o.band = *a.band, give("band", "band");
  if (a.margin) o.margin = *a.margin, give("margin", "margin");
  if (a.ccd) o.ccd = *a.ccd, give("ccd", "ccd");
  if (a.config) o.device = parse_config_pairs(*a.config, "config"), give("device", "config");
  o.threads = a.threads;
  o.midphase = a.midphase;
  o.cull = a.cull;
  if (!record.is_none()) o.record = path_arg(record, "record");
  return o;
}

namespace {

// simulate(): the run the arguments ask for, its summary as a dict.
py::dict simulate_scene(const RunArgs& a, const py::object& record) {
  std::optional<std::string> text;
  const RunConfig options = run_options(a, record, text);
  return with_file(text ? "" : options.where, [&] {
    RunConfig config;
    {
      py::gil_scoped_release unlocked;
      config = run_config(options, text);
    }
    warn_notes(config);
    SimulationSummary s;
    {
      py::gil_scoped_release unlocked;
      s = simulate(config);
    }
    return summary_dict(s);
  });
}

py::object size_scene(const py::object& scene, std::optional<double> accuracy, std::optional<double> contact_accuracy,
                      std::optional<double> rate, std::optional<double> clock, const py::object& frames, bool cost,
                      const std::optional<py::object>& rtl, const std::optional<std::string>& target) {
  std::string file;
  std::optional<std::string> text;
  scene_arg(scene, file, text);
  SizeRequest req;
  for (const auto& [v, name] : {std::pair{accuracy, "accuracy"}, {contact_accuracy, "contact_accuracy"},
                                {rate, "rate"}})
    if (v && !(*v > 0)) value_error(std::string(name) + ": " + py::repr(py::float_(*v)).cast<std::string>() +
                                    " is not a positive number");
  req.accuracy = accuracy.value_or(0);
  req.contact_accuracy = contact_accuracy.value_or(0);
  req.rate = rate.value_or(0);
  if (clock) req.clock = clock_arg(*clock);
  if (const auto f = count_arg(frames, "frames")) {
    if (*f < 1 || *f > kMaxFrames) value_error("frames: " + outside(*f, 1, kMaxFrames));
    req.frames = *f;
  }
  req.cost = cost;
  if (rtl && !rtl->is_none()) req.rtl_dir = path_arg(*rtl, "rtl");
  if (target) {
    const auto& targets = timing_targets();
    if (std::find(targets.begin(), targets.end(), *target) == targets.end()) {
      std::string list;
      for (const std::string& t : targets) list += (list.empty() ? "" : ", ") + t;
      value_error("target: '" + *target + "' is not one of " + list);
    }
    req.target = *target;
  }
  std::string json;
  with_file(text ? "" : file, [&] {
    RunConfig f;
    {
      py::gil_scoped_release unlocked;
      f = text ? parse_scene_file(*text, file) : read_scene_file(file);
    }
    warn_notes(f);
    py::gil_scoped_release unlocked;
    const Scene sc = make_scene(f);
    try {
      json = size_json(derive_size(f, sc, req));
    } catch (const SizeError& e) {
      throw e.prefixed(file + ": cannot be met: ");
    }
  });
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

const char* const kSimulateDoc = R"(Runs a scene as `voxcd simulate` does and returns its summary as a dict, with the keys and numbers of
`voxcd simulate --json` (the state hash as a hex string). scene: None (the paper's built-in scene), a scene file,
or a dict with a scene file's keys (docs/scenes.md). Each option given (not None) overrides the scene file, as the
tool's option of the same name does (both_directions: --both or --no-both, both its deprecated spelling; broadphase: --broadphase, whose deprecated
spelling pruning still works with a DeprecationWarning); config is a whole device configuration as NAME VALUE pairs.
distance_bits (4, 8 or 16), band (voxels), margin (world units) and ccd (continuous collision, which needs distance voxmaps) are
--distance-bits, --band, --margin and --ccd (ccd=False also turns off a scene file's "ccd"); with distance voxmaps
the summary has distance_bits, band, margin and ccd, and with ccd the counters of no_tunnelling. clock (MHz) is the
device clock of device_frame_rate_hz (default: the scene file's "clock", or the clock OpenSTA measured at 0.18 um for
the run's device configuration, else an estimate from the nearest configuration measured, with clock_estimate True:
docs/hardware.md, "The default clock"); clock_mhz, clock_source and clock_estimate say which, and
device_frame_rate_hz is None when no frame needed device cycles. record (a path) records the run as it goes
(docs/view.md; read_recording reads it, `voxcd view` replays it).)";

void bind_scenes(py::module_& m) {
  std::apply(
      [&](auto... args) { m.def("simulate", run_function<const py::object&>(&simulate_scene), args..., kSimulateDoc); },
      std::tuple_cat(run_args(), std::make_tuple(py::arg("record") = py::none())));
  m.def("size", &size_scene, py::arg("scene"), py::kw_only(), py::arg("accuracy") = py::none(),
        py::arg("contact_accuracy") = py::none(),
        py::arg("rate") = py::none(), py::arg("clock") = py::none(), py::arg("frames") = py::none(),
        py::arg("cost") = false, py::arg("rtl") = py::none(), py::arg("target") = py::none(),
        R"(The smallest device for a scene file (or a dict with a scene file's keys), as `voxcd size --json` reports
it, as a dict. The options override the file's accuracy (world units), contact_accuracy (world units: chooses the
voxmaps, docs/size.md), rate (Hz), clock (MHz; default: the scene file's "clock", or the derived configuration's,
measured or an estimate: clock_source and clock_estimate in the dict say which) and frames; cost
also synthesises the configuration with yosys (about 10 s each; rtl: the directory of the RTL's voxcd.f). target
("asic-osu018", "ice40-hx8k", "ice40-up5k" or "xilinx-7") chooses the pipeline depth for the clock from the measured
timing table, as --target does (depth_choice in the dict). ValueError '<scene>: cannot be met: ...' when no device
meets the request (or no depth meets the clock).)");
}

}  // namespace voxcd::python
