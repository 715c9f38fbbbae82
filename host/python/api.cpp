// The public API in Python (docs/api.md, docs/python.md): voxcd.collide(a, pose_a, b, pose_b) and voxcd.World, over
// the library's collide() and World; objects from arrays (numpy, or anything with .vertices and .faces).
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>

#include "voxcd/host/api/collide.h"
#include "voxcd/host/api/world.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/python/bindings.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd::python {

namespace {

// The library's form of a voxcd.Object, made once per Object (the last few kept: a query loads them once).
std::shared_ptr<const ObjectType> type_of(const std::shared_ptr<ObjectFile>& obj) {
  static std::mutex lock;
  static std::vector<std::pair<std::weak_ptr<ObjectFile>, std::shared_ptr<const ObjectType>>> cache;
  const std::lock_guard<std::mutex> hold(lock);
  for (auto& [w, t] : cache)
    if (w.lock() == obj) return t;
  auto t = std::make_shared<const ObjectType>(make_object_type(*obj, obj->source));
  if (cache.size() >= 8) cache.erase(cache.begin());
  cache.emplace_back(obj, t);
  return t;
}

// An object argument: a voxcd.Object, or anything voxelize takes (voxelised at 32 voxels along its longest side).
Object object_arg(const py::object& o) {
  if (py::isinstance<ObjectFile>(o)) return Object(type_of(o.cast<std::shared_ptr<ObjectFile>>()));
  py::object made = py::module_::import("voxcd").attr("voxelize")(o, py::arg("resolution") = 32);
  return Object(type_of(made.cast<std::shared_ptr<ObjectFile>>()));
}

py::dict collide_py(const py::object& a, const py::object& pose_a, const py::object& b, const py::object& pose_b,
                    const std::string& mode, bool both, double margin, const std::string& backend, int lanes,
                    unsigned threads) {
  const auto m = parse_mode(mode);
  if (!m) value_error("mode: '" + mode + "' is not ALL, FIRST or COUNT");
  if (!std::isfinite(margin)) value_error("margin: not a finite number");
  const Object oa = object_arg(a), ob = object_arg(b);
  const Pose pa = pose_arg(pose_a, "pose_a"), pb = pose_arg(pose_b, "pose_b");
  CollideOptions o;
  o.mode = *m;
  o.both_directions = both;
  o.margin = margin;
  o.backend = backend;
  o.lanes = lanes;
  o.threads = threads;
  Contacts c;
  {
    py::gil_scoped_release unlocked;
    c = collide(oa, pa, ob, pb, o);
  }
  return contacts_dict(c, true);
}

// A strided view of one vector field of every body (N x width doubles), kept alive by `owner`.
py::array body_view(const std::vector<Body>& bodies, const double* first, py::ssize_t width, py::handle owner) {
  const py::ssize_t n = py::ssize_t(bodies.size());
  return py::array(py::dtype::of<double>(), {n, width}, {py::ssize_t(sizeof(Body)), py::ssize_t(sizeof(double))},
                   n ? first : nullptr, owner);
}

World world_def(double side, const std::optional<std::string>& broadphase, const std::string& backend, int lanes,
                const std::string& mode, bool both, int distance_bits, double margin, bool ccd, unsigned threads,
                const std::optional<std::string>& pruning) {
  WorldDef d;
  d.side = side;
  if (broadphase) d.broadphase = *broadphase;
  if (pruning) {  // the keyword simulate() had before it was broadphase, as World's
    if (broadphase && *broadphase != *pruning)
      value_error("pruning: is broadphase's deprecated spelling, and names '" + *pruning +
                  "' where broadphase names '" + *broadphase + "'");
    deprecation("pruning is deprecated: use broadphase (the same keyword; docs/python.md, \"Deprecated spellings\")");
    d.broadphase = *pruning;
  }
  d.backend = backend;
  d.lanes = lanes;
  d.mode = mode_option(mode);
  d.both_directions = both;
  d.distance_bits = distance_bits;
  d.margin = margin;
  d.ccd = ccd;
  d.threads = threads;
  return World(d);
}

// World.scene(): the scene `voxcd simulate` runs for the arguments, not yet stepped.
World world_scene(const RunArgs& a) {
  if (!a.frames.is_none()) value_error("frames: a World is stepped by its caller (World.step())");
  std::optional<std::string> text;
  const RunConfig options = run_options(a, py::none(), text);
  return with_file(text ? "" : options.where, [&] {
    RunConfig config;
    {
      py::gil_scoped_release unlocked;
      config = run_config(options, text);
    }
    warn_notes(config);
    py::gil_scoped_release unlocked;
    return detail::world_of(config);
  });
}

// Three numbers (None: zeros); ValueError naming `what` for anything else.
Eigen::Vector3d vec3_arg(const py::object& v, const char* what) {
  if (v.is_none()) return Eigen::Vector3d::Zero();
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  if (!a || a.ndim() != 1 || a.shape(0) != 3) value_error(std::string(what) + ": give three numbers");
  return Eigen::Vector3d(a.data()[0], a.data()[1], a.data()[2]);
}

// The getter of a property that views one vector field of every body, no copy: field(body) points at its first of
// `width` doubles.
template <class Field>
auto bodies_view(Field field, py::ssize_t width) {
  return [field, width](py::object self) {
    const auto& b = self.cast<const World&>().bodies();
    return body_view(b, b.empty() ? nullptr : field(b[0]), width, self);
  };
}

std::string hex(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%llx", static_cast<unsigned long long>(v));
  return b;
}

using WorldClass = py::class_<World>;

// voxcd.collide: one pair query in one call.
void bind_collide(py::module_& m) {
  m.def("collide", &collide_py, py::arg("a"), py::arg("pose_a") = py::none(), py::arg("b"),
        py::arg("pose_b") = py::none(), py::kw_only(), py::arg("mode") = "ALL", py::arg("both") = true,
        py::arg("margin") = 0.0, py::arg("backend") = "cpu", py::arg("lanes") = 4, py::arg("threads") = 0u,
        R"(The contacts of b at pose_b against a at pose_a, in one call (the library's collide(), docs/api.md).
a and b: Objects, or anything voxelize() takes (a mesh file, a shape, (vertices, faces) arrays, an object with
.vertices and .faces such as a trimesh mesh), voxelised at 32 voxels along the longest side. Poses: None, 3, 6, 7,
12 or 16 numbers (tx, ty, tz; then rx, ry, rz in degrees, or qw, qx, qy, qz; or a 3 x 4 or 4 x 4 matrix, row-major),
a 3 x 4 or 4 x 4 matrix, (R, t), or the pose dict `voxcd pair --json` prints. mode ALL, FIRST or COUNT;
both (default True) also tests b's shell in a; margin: contacts within this distance outside (distance voxmaps, both objects with
fields). Returns the dict Pair.query returns: hits, lookups, device_cycles, and the contacts as arrays.)");
}

// World's construction, World.scene() and its bodies: adding them and viewing their state.
void bind_world_bodies(WorldClass& world) {
  world
      .def(py::init(&world_def), py::kw_only(), py::arg("side") = 100.0, py::arg("broadphase") = py::none(),
           py::arg("backend") = "cpu", py::arg("lanes") = 4, py::arg("mode") = "ALL", py::arg("both") = true,
           py::arg("distance_bits") = 0, py::arg("margin") = 0.0, py::arg("ccd") = false, py::arg("threads") = 0u,
           py::arg("pruning") = py::none(),
           "An empty world (the library's WorldDef): both (default True, as collide) also tests B's shell in A's "
           "voxmap; broadphase one of broadphases(), by default grid (pruning: its deprecated spelling).")
      .def(
          "add_body",
          [](World& w, const py::object& obj, const py::object& pose, const py::object& velocity,
             const py::object& spin) {
            return w.add_body(object_arg(obj), pose_arg(pose, "pose"), vec3_arg(velocity, "velocity"),
                              vec3_arg(spin, "spin"));
          },
          py::arg("object"), py::arg("pose") = py::none(), py::kw_only(), py::arg("velocity") = py::none(),
          py::arg("spin") = py::none(),
          "Adds a body of `object` at `pose` (any pose collide() takes: a row of World.poses goes back in) moving by "
          "velocity (world units) and turning by spin (radians about the world axes) per frame; returns its index.")
      .def("__len__", &World::size)
      .def_property_readonly("positions", bodies_view([](const Body& b) { return b.pose.translation.data(); }, 3),
                             "Every body's position, an (N, 3) float64 view of the world's own state (no copy; valid "
                             "until a body is added).")
      .def_property_readonly("orientations",
                             bodies_view([](const Body& b) { return b.pose.rotation.coeffs().data(); }, 4),
                             "Every body's orientation as a unit quaternion (x, y, z, w: scalar last, as scipy's "
                             "Rotation.from_quat), an (N, 4) float64 view (no copy; valid until a body is added).")
      .def_property_readonly(
          "poses",
          [](const World& w) {
            const auto& b = w.bodies();
            py::array_t<double> a({py::ssize_t(b.size()), py::ssize_t(7)});
            auto r = a.mutable_unchecked<2>();
            for (size_t i = 0; i < b.size(); ++i) {
              const Pose& p = b[i].pose;
              const double v[7] = {p.translation.x(), p.translation.y(), p.translation.z(), p.rotation.w(),
                                   p.rotation.x(),    p.rotation.y(),    p.rotation.z()};
              for (py::ssize_t k = 0; k < 7; ++k) r(py::ssize_t(i), k) = v[k];
            }
            return a;
          },
          "Every body's pose as a new (N, 7) float64 array, tx, ty, tz, qw, qx, qy, qz: the 7-number form every pose "
          "argument takes (add_body(obj, world.poses[i]) puts a body where body i is).")
      .def_property_readonly("velocities", bodies_view([](const Body& b) { return b.velocity.data(); }, 3),
                             "Every body's velocity (world units per frame), an (N, 3) float64 view.");
  std::apply(
      [&](auto... args) {
        world.def_static("scene", run_function(&world_scene), args...,
                         "The scene `voxcd simulate` runs for the same options (simulate()'s; frames are the caller's "
                         "World.step()s).");
      },
      run_args());
}

// World's frames: stepping, what the last frame found, the state hash and recording.
void bind_world_frames(WorldClass& world) {
  world
      .def(
          "step",
          [](World& w) {
            FrameStats st;
            {
              py::gil_scoped_release unlocked;
              st = w.step();
            }
            py::dict d = frame_counts(st);
            d["seconds"] = st.seconds();
            return d;
          },
          "One frame; returns its statistics as a dict (pairs, tested, touching, contacts, device_cycles, ...).")
      .def_property_readonly("frame", &World::frame, "Frames stepped.")
      .def_property_readonly("state_hash", [](const World& w) { return hex(w.state_hash()); },
                             "The hash of every body's state as a hex string: `voxcd simulate --json`'s state_hash "
                             "after as many frames of the same scene.")
      .def_property_readonly(
          "pairs",
          [](const World& w) {
            const auto& p = w.pairs();
            py::array_t<uint32_t> a({py::ssize_t(p.size()), py::ssize_t(2)});
            if (!p.empty()) std::memcpy(a.mutable_data(), p.data(), p.size() * 2 * sizeof(uint32_t));
            return a;
          },
          "The last frame's pairs tested on the device, a (P, 2) uint32 array of body indices.")
      .def_property_readonly(
          "contacts",
          [](const World& w) {
            py::list out;
            for (const Contacts& c : w.contacts()) out.append(contacts_dict(c, true));
            return out;
          },
          "The last frame's contacts: per tested pair (in the order of pairs), the dict collide() returns.")
      .def("record", &World::record, py::arg("path"),
           "Records every frame from now on into `path` (docs/view.md; read_recording reads it, `voxcd view` replays "
           "it).")
      .def("stop_recording", &World::stop_recording, "Closes the recording.");
}

}  // namespace

void bind_api(py::module_& m) {
  bind_collide(m);
  WorldClass world(m, "World", R"(A world the caller steps (the library's World, docs/api.md): bodies of Objects
in the cube [0, side]^3 with walls, a broadphase and pair tests on a device each frame, a response. World(...) is
empty; World.scene(...) is the scene `voxcd simulate` runs for the same options.)");
  bind_world_bodies(world);
  bind_world_frames(world);
}

}  // namespace voxcd::python
