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

}  // namespace

// An object argument: a voxcd.Object, or anything voxelize takes (voxelised at 32 voxels along its longest side).
Object object_arg(const py::object& o) {
  if (py::isinstance<ObjectFile>(o)) return ApiAccess::object_of(type_of(o.cast<std::shared_ptr<ObjectFile>>()));
  py::object made = py::module_::import("voxcd").attr("voxelize")(o, py::arg("resolution") = 32);
  return ApiAccess::object_of(type_of(made.cast<std::shared_ptr<ObjectFile>>()));
}

// Three numbers (None: zeros); ValueError naming `what` for anything else.
Eigen::Vector3d vec3_arg(const py::object& v, const char* what) {
  if (v.is_none()) return Eigen::Vector3d::Zero();
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
  if (!a || a.ndim() != 1 || a.shape(0) != 3) value_error(std::string(what) + ": give three numbers");
  return Eigen::Vector3d(a.data()[0], a.data()[1], a.data()[2]);
}

namespace {

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

}  // namespace

void bind_api(py::module_& m) {
  bind_collide(m);
  bind_world(m);
}

}  // namespace voxcd::python
