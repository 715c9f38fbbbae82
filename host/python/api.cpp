// The public API in Python (docs/api.md, docs/python.md): voxcd.collide(a, pose_a, b, pose_b) over the library's
// collide(), and the arguments the API's bindings share (objects, poses, vectors); voxcd.World is world.cpp's.
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

#include "voxcd/host/api/access.h"
#include "voxcd/host/api/collide.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/python/bindings.h"

namespace voxcd::python {

namespace {

// Where a voxcd.Object lives: its object file's form and, once a query has asked for it, the library's form of it,
// kept with the object and freed with it. Found from the object through its deleter (std::get_deleter), which every
// shared_ptr the module gives Python carries.
struct Home {
  ObjectFile file;
  std::shared_ptr<const ObjectType> type;
  std::mutex lock;
};
struct HomeDeleter {
  Home* home = nullptr;
  void operator()(Home* h) const { delete h; }
};

std::shared_ptr<Home> new_home() {
  Home* h = new Home;
  return std::shared_ptr<Home>(h, HomeDeleter{h});
}

}  // namespace

std::shared_ptr<ObjectFile> python_object(ObjectFile obj) {
  const std::shared_ptr<Home> h = new_home();
  h->file = std::move(obj);
  return std::shared_ptr<ObjectFile>(h, &h->file);
}

std::shared_ptr<ObjectFile> python_object(const Object& object) {
  const std::shared_ptr<Home> h = new_home();
  h->type = ApiAccess::type_of(object);
  // The module's Object class reads its object and never writes it.
  return std::shared_ptr<ObjectFile>(h, const_cast<ObjectFile*>(&h->type->object));
}

Object library_object(const std::shared_ptr<ObjectFile>& obj) {
  const HomeDeleter* d = std::get_deleter<HomeDeleter>(obj);
  if (!d) return ApiAccess::object_of(std::make_shared<const ObjectType>(make_object_type(*obj, obj->source)));
  Home& h = *d->home;
  const std::lock_guard<std::mutex> hold(h.lock);
  if (!h.type) h.type = std::make_shared<const ObjectType>(make_object_type(h.file, h.file.source));
  return ApiAccess::object_of(h.type);
}

// An object argument: a voxcd.Object, or anything voxelize takes (voxelised at 32 voxels along its longest side).
Object object_arg(const py::object& o) {
  if (py::isinstance<ObjectFile>(o)) return library_object(o.cast<std::shared_ptr<ObjectFile>>());
  py::object made = py::module_::import("voxcd").attr("voxelize")(o, py::arg("resolution") = 32);
  return library_object(made.cast<std::shared_ptr<ObjectFile>>());
}

// Three numbers (None: zeros); ValueError naming `what` for anything else.
Eigen::Vector3d vec3_arg(const py::object& v, const char* what) {
  if (v.is_none()) return Eigen::Vector3d::Zero();
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  if (!a || a.ndim() != 1 || a.shape(0) != 3) value_error(std::string(what) + ": give three numbers");
  return Eigen::Vector3d(a.data()[0], a.data()[1], a.data()[2]);
}

namespace {

// CollideOptions from collide()'s and Collider()'s keywords, checked.
CollideOptions collide_options(const std::string& mode, bool both_directions, double margin, const std::string& backend,
                               int lanes, unsigned threads, std::optional<bool> both) {
  const auto m = parse_mode(mode);
  if (!m) value_error("mode: '" + mode + "' is not ALL, FIRST or COUNT");
  if (!std::isfinite(margin)) value_error("margin: not a finite number");
  CollideOptions o;
  o.mode = *m;
  o.both_directions = both_directions_arg(both_directions, both);
  o.margin = margin;
  o.backend = backend;
  o.lanes = lanes;
  o.threads = threads;
  return o;
}

// A batch's poses: an (N, 2, k) array (or a list of N (pose_a, pose_b) pairs) of any pose form, as (pose of a, pose
// of b) pairs.
std::vector<std::pair<Pose, Pose>> pose_pairs(const py::object& poses) {
  std::vector<std::pair<Pose, Pose>> out;
  if (!py::isinstance<py::iterable>(poses) || py::isinstance<py::str>(poses) || py::isinstance<py::dict>(poses))
    value_error("poses: give a sequence of (pose_a, pose_b) pairs");
  size_t i = 0;
  for (const py::handle h : poses) {
    const std::string at = "poses[" + std::to_string(i++) + "]";
    if (!py::isinstance<py::iterable>(h) || py::len(h) != 2) value_error(at + ": give a (pose_a, pose_b) pair");
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(h);
    out.emplace_back(pose_arg(pair[0], at + "[0]"), pose_arg(pair[1], at + "[1]"));
  }
  return out;
}

py::list contacts_list(const std::vector<Contacts>& many) {
  py::list out;
  for (const Contacts& c : many) out.append(contacts_dict(c, true));
  return out;
}

py::dict collide_py(const py::object& a, const py::object& pose_a, const py::object& b, const py::object& pose_b,
                    const std::string& mode, bool both_directions, double margin, const std::string& backend,
                    int lanes, unsigned threads, std::optional<bool> both) {
  const CollideOptions o = collide_options(mode, both_directions, margin, backend, lanes, threads, both);
  const Object oa = object_arg(a), ob = object_arg(b);
  const Pose pa = pose_arg(pose_a, "pose_a"), pb = pose_arg(pose_b, "pose_b");
  Contacts c;
  {
    py::gil_scoped_release unlocked;
    c = collide(oa, pa, ob, pb, o);
  }
  return contacts_dict(c, true);
}

py::list collide_many_py(const py::object& a, const py::object& b, const py::object& poses, const std::string& mode,
                         bool both_directions, double margin, const std::string& backend, int lanes, unsigned threads,
                         std::optional<bool> both) {
  const CollideOptions o = collide_options(mode, both_directions, margin, backend, lanes, threads, both);
  const Object oa = object_arg(a), ob = object_arg(b);
  const auto p = pose_pairs(poses);
  std::vector<Contacts> c;
  {
    py::gil_scoped_release unlocked;
    c = collide(oa, ob, p, o);
  }
  return contacts_list(c);
}

// The options' keywords after the objects and poses, as collide() and Collider() take them.
auto option_args() {
  return std::make_tuple(py::kw_only(), py::arg("mode") = "ALL", py::arg("both_directions") = true,
                         py::arg("margin") = 0.0, py::arg("backend") = "cpu", py::arg("lanes") = 4,
                         py::arg("threads") = 0u, py::arg("both") = py::none());
}

const char* const kCollideDoc = R"(The contacts of b at pose_b against a at pose_a, in one call (the library's
collide(), docs/api.md). a and b: Objects, or anything voxelize() takes (a mesh file, a shape, (vertices, faces) arrays, an object with
.vertices and .faces such as a trimesh mesh), voxelised at 32 voxels along the longest side. Poses: None, 3, 6, 7,
12 or 16 numbers (tx, ty, tz; then rx, ry, rz in degrees, or qw, qx, qy, qz; or a 3 x 4 or 4 x 4 matrix, row-major),
a 3 x 4 or 4 x 4 matrix, (R, t), or the pose dict `voxcd pair --json` prints. mode ALL, FIRST or COUNT;
both_directions (default True, as C++ CollideOptions) also tests b's shell in a (both: its deprecated spelling);
margin: contacts within this distance outside (distance voxmaps, both objects with fields). Returns the dict
Pair.query returns: hits, lookups, device_cycles, and the contacts as arrays. collide(a, b, poses) is the same at
many (pose_a, pose_b) pairs in one batch: a list of such dicts, in order.)";

// voxcd.collide: one pair query in one call, or a batch of poses.
void bind_collide(py::module_& m) {
  std::apply(
      [&](auto... opts) {
        m.def("collide", &collide_py, py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"), opts...,
              kCollideDoc);
        m.def("collide", &collide_many_py, py::arg("a"), py::arg("b"), py::arg("poses"), opts..., kCollideDoc);
      },
      option_args());
}

// voxcd.Collider: the C++ Collider, one query at a time (its own lock; the GIL is released while it works).
struct PyCollider {
  explicit PyCollider(const CollideOptions& o) : collider(o) {}
  Collider collider;
  std::mutex busy;
};

void bind_collider(py::module_& m) {
  py::class_<PyCollider> cls(m, "Collider", R"(Repeated pair queries (the C++ Collider, docs/api.md): made once
with collide()'s options, it keeps the device of its last two objects loaded (and, with threads other than 1, a pool
of worker threads of its own) until it is freed; its results equal collide()'s. Queries from several threads take
turns on it.)");
  std::apply(
      [&](auto... opts) {
        cls.def(py::init([](const std::string& mode, bool both_directions, double margin, const std::string& backend,
                            int lanes, unsigned threads, std::optional<bool> both) {
                  return std::make_unique<PyCollider>(
                      collide_options(mode, both_directions, margin, backend, lanes, threads, both));
                }),
                opts..., "A Collider with collide()'s options (the C++ CollideOptions' names and defaults).");
      },
      option_args());
  cls.def(
         "collide",
         [](PyCollider& c, const py::object& a, const py::object& pose_a, const py::object& b,
            const py::object& pose_b) {
           const Object oa = object_arg(a), ob = object_arg(b);
           const Pose pa = pose_arg(pose_a, "pose_a"), pb = pose_arg(pose_b, "pose_b");
           Contacts out;
           {
             py::gil_scoped_release unlocked;
             const std::lock_guard<std::mutex> one_at_a_time(c.busy);
             out = c.collider.collide(oa, pa, ob, pb);
           }
           return contacts_dict(out, true);
         },
         py::arg("a"), py::arg("pose_a"), py::arg("b"), py::arg("pose_b"),
         "collide(a, pose_a, b, pose_b) with this Collider's options and device; collide(a, b, poses) a batch.")
      .def(
          "collide",
          [](PyCollider& c, const py::object& a, const py::object& b, const py::object& poses) {
            const Object oa = object_arg(a), ob = object_arg(b);
            const auto p = pose_pairs(poses);
            std::vector<Contacts> out;
            {
              py::gil_scoped_release unlocked;
              const std::lock_guard<std::mutex> one_at_a_time(c.busy);
              out = c.collider.collide(oa, ob, p);
            }
            return contacts_list(out);
          },
          py::arg("a"), py::arg("b"), py::arg("poses"),
          "collide(a, pose_a, b, pose_b) with this Collider's options and device; collide(a, b, poses) a batch.")
      .def_property_readonly(
          "options",
          [](const PyCollider& c) {
            const CollideOptions& o = c.collider.options();
            return py::dict(py::arg("mode") = mode_name(o.mode), py::arg("both_directions") = o.both_directions,
                            py::arg("margin") = o.margin, py::arg("backend") = o.backend, py::arg("lanes") = o.lanes,
                            py::arg("threads") = o.threads);
          },
          "Its options as a dict of collide()'s keywords.")
      .def_property_readonly(
          "worker_threads", [](PyCollider& c) {
            const std::lock_guard<std::mutex> one_at_a_time(c.busy);
            return c.collider.worker_threads();
          },
          "Worker threads it holds now, besides the calling thread (0 before its first query, on one thread, or off "
          "cpu).");
}

}  // namespace

void bind_api(py::module_& m) {
  bind_collide(m);
  bind_collider(m);
  bind_world(m);
}

}  // namespace voxcd::python
