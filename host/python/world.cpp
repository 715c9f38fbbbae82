// voxcd.World and voxcd.BodyId (docs/python.md): the library's World, its bodies added with keyword arguments as a
// BodyDef's fields, named by BodyIds, their poses and velocities read and set, stepped by frames or seconds, and its
// contact events as dicts. A body's user data may be any Python object: the world keeps it, and the library holds a
// number that names it.
#include <cstring>
#include <unordered_map>
#include <vector>

#include "voxcd/host/api/access.h"
#include "voxcd/host/api/world.h"
#include "voxcd/host/python/bindings.h"
#include "voxcd/host/scene/run_config.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd::python {

namespace {

// A World and its bodies' user data: the library's user_data is a token (0: None) naming a Python object here.
// Objects of removed bodies stay until the step after the one whose end events name them.
struct PyWorld {
  explicit PyWorld(World w) : world(std::move(w)) {}
  World world;
  std::unordered_map<uint64_t, py::object> user;
  uint64_t next = 1;
  std::vector<uint64_t> retiring, retired;  // tokens of bodies removed before the last step, and before the one to come

  uint64_t token(const py::object& o) {
    if (o.is_none()) return 0;
    user[next] = o;
    return next++;
  }
  py::object object(uint64_t token) const {
    const auto it = user.find(token);
    return it == user.end() ? py::object(py::none()) : it->second;
  }
  // After a step: the objects of bodies removed before the step before it go.
  void retire() {
    for (const uint64_t t : retired) user.erase(t);
    retired = std::move(retiring);
    retiring.clear();
  }
};

using WorldClass = py::class_<PyWorld>;

const char* kind_name(BodyKind k) {
  return k == BodyKind::kStatic ? "static" : k == BodyKind::kKinematic ? "kinematic" : "dynamic";
}

BodyKind kind_arg(const std::string& k) {
  if (k == "dynamic") return BodyKind::kDynamic;
  if (k == "static") return BodyKind::kStatic;
  if (k == "kinematic") return BodyKind::kKinematic;
  value_error("kind: '" + k + "' is not dynamic, static or kinematic");
}

// A pose as a 4 x 4 homogeneous matrix (what pose arguments take back).
py::array pose_matrix(const Pose& p) {
  py::array_t<double> m({py::ssize_t(4), py::ssize_t(4)});
  double* d = m.mutable_data();
  const Eigen::Matrix3d R = p.rotation.toRotationMatrix();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) d[4 * i + j] = i < 3 ? (j < 3 ? R(i, j) : p.translation[i]) : (j == 3 ? 1.0 : 0.0);
  return m;
}

py::array vec3(const Eigen::Vector3d& v) {
  py::array_t<double> a(3);
  std::memcpy(a.mutable_data(), v.data(), 3 * sizeof(double));
  return a;
}

py::dict event_dict(const PyWorld& w, const ContactEvent& e) {
  return py::dict(py::arg("a") = e.a, py::arg("b") = e.b, py::arg("user_data_a") = w.object(e.user_data_a),
                  py::arg("user_data_b") = w.object(e.user_data_b));
}

py::dict touching_dict(const PyWorld& w, const ContactData& d) {
  py::dict out(py::arg("a") = d.a, py::arg("b") = d.b, py::arg("user_data_a") = w.object(d.user_data_a),
               py::arg("user_data_b") = w.object(d.user_data_b), py::arg("hits") = d.hits,
               py::arg("contacts") = d.contacts, py::arg("normal") = vec3(d.normal), py::arg("pair") = d.pair);
  out["deepest"] = d.contacts == 0 ? py::object(py::none())
                                   : py::object(py::dict(py::arg("position") = vec3(d.deepest.position),
                                                         py::arg("normal") = vec3(d.deepest.normal),
                                                         py::arg("depth") = d.deepest.depth,
                                                         py::arg("a_in_b") = d.deepest.a_in_b,
                                                         py::arg("point") = d.deepest.point));
  return out;
}

// A strided view of one vector field of every body (N x width doubles), kept alive by `owner`.
py::array body_view(const std::vector<Body>& bodies, const double* first, py::ssize_t width, py::handle owner) {
  const py::ssize_t n = py::ssize_t(bodies.size());
  return py::array(py::dtype::of<double>(), {n, width}, {py::ssize_t(sizeof(Body)), py::ssize_t(sizeof(double))},
                   n ? first : nullptr, owner);
}

// The getter of a property that views one vector field of every body, no copy: field(body) points at its first of
// `width` doubles.
template <class Field>
auto bodies_view(Field field, py::ssize_t width) {
  return [field, width](py::object self) {
    const auto& b = self.cast<const PyWorld&>().world.bodies();
    return body_view(b, b.empty() ? nullptr : field(b[0]), width, self);
  };
}

std::string hex(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%llx", static_cast<unsigned long long>(v));
  return b;
}

PyWorld* world_def(double side, bool walls, bool response, const std::optional<std::string>& broadphase,
                   const std::string& backend, int lanes, const std::string& mode, bool both_directions,
                   int distance_bits, double margin, bool ccd, unsigned threads,
                   const std::optional<std::string>& pruning, std::optional<bool> both) {
  WorldDef d;
  d.side = side;
  d.walls = walls;
  d.response = response;
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
  d.both_directions = both_directions_arg(both_directions, both);
  d.distance_bits = distance_bits;
  d.margin = margin;
  d.ccd = ccd;
  d.threads = threads;
  return new PyWorld(World(d));
}

// World.scene(): the scene `voxcd simulate` runs for the arguments, not yet stepped.
PyWorld* world_scene(const RunArgs& a) {
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
    return new PyWorld(ApiAccess::world_of(config));
  });
}

BodyId add_py(PyWorld& w, const py::object& obj, const py::object& pose, const py::object& velocity,
              const py::object& angular_velocity, const py::object& user_data, const std::string& kind, bool enabled) {
  BodyDef def(object_arg(obj));
  def.pose = pose_arg(pose, "pose");
  def.velocity = vec3_arg(velocity, "velocity");
  def.angular_velocity = vec3_arg(angular_velocity, "angular_velocity");
  def.kind = kind_arg(kind);
  def.enabled = enabled;
  def.user_data = w.token(user_data);
  try {
    return w.world.add(def);
  } catch (...) {
    w.user.erase(def.user_data);
    throw;
  }
}

py::list events_list(const PyWorld& w, const std::vector<ContactEvent>& events) {
  py::list out;
  for (const ContactEvent& e : events) out.append(event_dict(w, e));
  return out;
}

void bind_body_id(py::module_& m) {
  py::class_<BodyId>(m, "BodyId", R"(A body of a World: its slot (index) and the slot's generation. A removed body's
id is never valid again (World.is_valid); BodyId() is no body's.)")
      .def(py::init<>())
      .def(py::init([](uint32_t index, uint32_t generation) { return BodyId{index, generation}; }), py::arg("index"),
           py::arg("generation"))
      .def_readonly("index", &BodyId::index)
      .def_readonly("generation", &BodyId::generation)
      .def("__eq__", [](BodyId a, const py::object& b) { return py::isinstance<BodyId>(b) && a == b.cast<BodyId>(); })
      .def("__hash__", [](BodyId a) { return py::hash(py::make_tuple(a.index, a.generation)); })
      .def("__repr__", [](BodyId a) {
        return "BodyId(" + std::to_string(a.index) + ", " + std::to_string(a.generation) + ")";
      });
}

// World's construction and its bodies coming and going: add (and add_body, deprecated), remove, is_valid.
void bind_world_bodies(WorldClass& world) {
  world
      .def(py::init(&world_def), py::kw_only(), py::arg("side") = 100.0, py::arg("walls") = true,
           py::arg("response") = true, py::arg("broadphase") = py::none(), py::arg("backend") = "cpu",
           py::arg("lanes") = 4, py::arg("mode") = "ALL", py::arg("both_directions") = true,
           py::arg("distance_bits") = 0, py::arg("margin") = 0.0, py::arg("ccd") = false, py::arg("threads") = 0u,
           py::arg("pruning") = py::none(), py::arg("both") = py::none(),
           "An empty world (the library's WorldDef): both_directions (default True, as collide) also tests B's shell "
           "in A's voxmap (both: its deprecated spelling); broadphase one of broadphases(), by default grid (pruning: "
           "its deprecated spelling).")
      .def("add", &add_py, py::arg("object"), py::arg("pose") = py::none(), py::kw_only(),
           py::arg("velocity") = py::none(), py::arg("angular_velocity") = py::none(),
           py::arg("user_data") = py::none(), py::arg("kind") = "dynamic", py::arg("enabled") = true,
           "Adds a body of `object` at `pose` (any pose collide() takes: a row of World.poses goes back in), with velocity (world units) "
           "and angular_velocity (radians about the world axes) per second (per frame for step()), any user_data, "
           "kind 'dynamic', 'static' or 'kinematic'; returns its BodyId.")
      .def(
          "add_body",
          [](PyWorld& w, const py::object& obj, const py::object& pose, const py::object& velocity,
             const py::object& spin) {
            if (PyErr_WarnEx(PyExc_DeprecationWarning, "World.add_body is World.add, which returns a BodyId", 1) < 0)
              throw py::error_already_set();
            return add_py(w, obj, pose, velocity, spin, py::none(), "dynamic", true).index;
          },
          py::arg("object"), py::arg("pose") = py::none(), py::kw_only(), py::arg("velocity") = py::none(),
          py::arg("spin") = py::none(),
          "Deprecated: World.add. Adds a body moving by velocity and turning by spin per frame; returns its index.")
      .def("remove",
           [](PyWorld& w, BodyId id) {
             const uint64_t t = w.world.is_valid(id) ? w.world.user_data(id) : 0;
             w.world.remove(id);
             if (t) w.retiring.push_back(t);
           },
           py::arg("id"), "Removes the body; the pairs it touched end (end_events after the next step).")
      .def("is_valid", [](const PyWorld& w, BodyId id) { return w.world.is_valid(id); }, py::arg("id"));
}

// One body's state by its id: pose, velocities, user data, kind, enabled.
void bind_world_body_state(WorldClass& world) {
  world
      .def("pose", [](const PyWorld& w, BodyId id) { return pose_matrix(w.world.pose(id)); }, py::arg("id"),
           "The body's pose as a 4 x 4 matrix (as pose arguments take it).")
      .def("set_pose", [](PyWorld& w, BodyId id, const py::object& p) { w.world.set_pose(id, pose_arg(p, "pose")); },
           py::arg("id"), py::arg("pose"))
      .def("velocity", [](const PyWorld& w, BodyId id) { return vec3(w.world.velocity(id)); }, py::arg("id"))
      .def("set_velocity",
           [](PyWorld& w, BodyId id, const py::object& v) { w.world.set_velocity(id, vec3_arg(v, "velocity")); },
           py::arg("id"), py::arg("velocity"))
      .def("angular_velocity", [](const PyWorld& w, BodyId id) { return vec3(w.world.angular_velocity(id)); },
           py::arg("id"))
      .def("set_angular_velocity",
           [](PyWorld& w, BodyId id, const py::object& v) {
             w.world.set_angular_velocity(id, vec3_arg(v, "angular_velocity"));
           },
           py::arg("id"), py::arg("angular_velocity"))
      .def("user_data", [](const PyWorld& w, BodyId id) { return w.object(w.world.user_data(id)); }, py::arg("id"))
      .def("set_user_data",
           [](PyWorld& w, BodyId id, const py::object& o) {
             const uint64_t old = w.world.user_data(id);
             w.world.set_user_data(id, w.token(o));
             if (old) w.retiring.push_back(old);  // an end event to come may still name it
           },
           py::arg("id"), py::arg("user_data"))
      .def("kind", [](const PyWorld& w, BodyId id) { return kind_name(w.world.kind(id)); }, py::arg("id"))
      .def("is_enabled", [](const PyWorld& w, BodyId id) { return w.world.is_enabled(id); }, py::arg("id"))
      .def("set_enabled", [](PyWorld& w, BodyId id, bool on) { w.world.set_enabled(id, on); }, py::arg("id"),
           py::arg("enabled"));
}

// Every body at once: their count, ids, and the (N, k) arrays of positions, orientations, poses and velocities; the
// built-in scene's world.
void bind_world_arrays(WorldClass& world) {
  world
      .def("__len__", [](const PyWorld& w) { return w.world.size(); })
      .def_property_readonly("ids", [](const PyWorld& w) { return w.world.ids(); },
                             "The id of each row of positions, orientations and velocities.")
      .def_property_readonly("positions", bodies_view([](const Body& b) { return b.pose.translation.data(); }, 3),
                             "Every body's position, an (N, 3) float64 view of the world's own state (no copy; valid "
                             "until a body is added, removed, enabled or disabled).")
      .def_property_readonly("orientations",
                             bodies_view([](const Body& b) { return b.pose.rotation.coeffs().data(); }, 4),
                             "Every body's orientation as a unit quaternion (x, y, z, w: scalar last, as scipy's "
                             "Rotation.from_quat), an (N, 4) float64 view (no copy; valid as positions).")
      .def_property_readonly(
          "poses",
          [](const PyWorld& w) {
            const auto& b = w.world.bodies();
            py::array_t<double> a({py::ssize_t(b.size()), py::ssize_t(7)});
            auto r = a.mutable_unchecked<2>();
            for (size_t i = 0; i < b.size(); ++i) {
              const RigidPose& p = b[i].pose;
              const double v[7] = {p.translation.x(), p.translation.y(), p.translation.z(), p.rotation.w(),
                                   p.rotation.x(),    p.rotation.y(),    p.rotation.z()};
              for (py::ssize_t k = 0; k < 7; ++k) r(py::ssize_t(i), k) = v[k];
            }
            return a;
          },
          "Every body's pose as a new (N, 7) float64 array, tx, ty, tz, qw, qx, qy, qz: the 7-number form every pose "
          "argument takes (add(obj, world.poses[i]) puts a body where body i is).")
      .def_property_readonly("velocities", bodies_view([](const Body& b) { return b.velocity.data(); }, 3),
                             "Every body's velocity (world units per second, or per frame for step()), an (N, 3) "
                             "float64 view.");
  std::apply(
      [&](auto... args) {
        world.def_static("scene", run_function(&world_scene), args...,
                         "The scene `voxcd simulate` runs for the same options (simulate()'s; frames are the caller's "
                         "World.step()s).");
      },
      run_args());
}

// World's steps, what the last one found (pairs, contacts, events), the state hash and recording.
void bind_world_frames(WorldClass& world) {
  world
      .def(
          "step",
          [](PyWorld& w, std::optional<double> dt) {
            FrameStats st;
            {
              py::gil_scoped_release unlocked;
              st = dt ? w.world.step(*dt) : w.world.step();
            }
            w.retire();
            py::dict d = frame_counts(st);
            d["seconds"] = st.seconds();
            return d;
          },
          py::arg("dt") = py::none(),
          "One frame (velocities per frame), or with dt a step of dt seconds (velocities per second); returns its "
          "statistics as a dict (pairs, tested, touching, contacts, device_cycles, ...).")
      .def_property_readonly("frame", [](const PyWorld& w) { return w.world.frame(); }, "Steps taken.")
      .def_property_readonly("state_hash", [](const PyWorld& w) { return hex(w.world.state_hash()); },
                             "The hash of every body's state as a hex string: `voxcd simulate --json`'s state_hash "
                             "after as many frames of the same scene.")
      .def_property_readonly(
          "pairs",
          [](const PyWorld& w) {
            const auto& p = w.world.pairs();
            py::array_t<uint32_t> a({py::ssize_t(p.size()), py::ssize_t(2)});
            if (!p.empty()) std::memcpy(a.mutable_data(), p.data(), p.size() * 2 * sizeof(uint32_t));
            return a;
          },
          "The last step's pairs tested on the device, a (P, 2) uint32 array of rows of positions (ids gives their "
          "BodyIds); empty once a body was added, removed, enabled or disabled since.")
      .def_property_readonly(
          "contacts",
          [](const PyWorld& w) {
            py::list out;
            for (const Contacts& c : w.world.contacts()) out.append(contacts_dict(c, true));
            return out;
          },
          "The last step's contacts: per tested pair (in the order of pairs), the dict collide() returns.")
      .def_property_readonly("begin_events", [](const PyWorld& w) { return events_list(w, w.world.begin_events()); },
                             "The pairs that began touching in the last step: dicts of a, b (BodyIds) and "
                             "user_data_a, user_data_b.")
      .def_property_readonly("end_events", [](const PyWorld& w) { return events_list(w, w.world.end_events()); },
                             "The pairs that stopped touching in the last step (and those of bodies removed or "
                             "disabled before it), as begin_events.")
      .def_property_readonly(
          "touching",
          [](const PyWorld& w) {
            py::list out;
            for (const ContactData& d : w.world.touching()) out.append(touching_dict(w, d));
            return out;
          },
          "The pairs touching after the last step: begin_events' keys and hits, contacts (a count), normal (from a "
          "towards b, zero when the contacts give none), deepest (position, normal, depth, a_in_b, point; None "
          "without contacts) and pair (the index into pairs and contacts).")
      .def("record", [](PyWorld& w, const std::string& path) { w.world.record(path); }, py::arg("path"),
           "Records every frame from now on into `path` (docs/view.md; read_recording reads it, `voxcd view` replays "
           "it).")
      .def("stop_recording", [](PyWorld& w) { w.world.stop_recording(); }, "Closes the recording.");
}

}  // namespace

void bind_world(py::module_& m) {
  bind_body_id(m);
  WorldClass world(m, "World", R"(A world the caller steps (the library's World, docs/api.md): bodies of Objects
added with World.add and named by BodyIds, in the cube [0, side]^3 with walls (walls=False: open space), a
broadphase and pair tests on a device each step, the built-in response (response=False: contacts are reported
only), and contact events. World(...) is empty; World.scene(...) is the scene `voxcd simulate` runs for the same
options.)");
  bind_world_bodies(world);
  bind_world_body_state(world);
  bind_world_arrays(world);
  bind_world_frames(world);
}

}  // namespace voxcd::python
