// Poses as the module takes them, through the library's one pose parser (host/pairs/pose_text.h): numbers in its
// five forms, matrices, (R, t) and the pose dict `voxcd pair --json` prints; one pose or an array of them.
#include <string>
#include <vector>

#include "voxcd/host/pairs/pose_text.h"
#include "voxcd/host/python/bindings.h"

namespace voxcd::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The array of `o`, or an empty one when it is not numbers.
Array numbers(const py::handle& o) {
  try {
    return Array::ensure(o);
  } catch (const py::error_already_set&) {
    return {};
  }
}

std::string shape_text(const py::array& a) {
  std::string shape;
  for (py::ssize_t i = 0; i < a.ndim(); ++i) shape += (i ? ", " : "") + std::to_string(a.shape(i));
  return "(" + shape + ")";
}

// The library's parser on n numbers, its message behind `what`.
RigidPose pose_of(const double* v, size_t n, const std::string& what) {
  try {
    return pose_from_numbers(v, n);
  } catch (const std::invalid_argument& e) {
    value_error(what + ": " + e.what());
  }
}

bool pose_width(py::ssize_t w) { return w == 3 || w == 6 || w == 7 || w == 12 || w == 16; }

// (R, t): a 3 x 3 rotation and a translation, as the 12 numbers of [R | t]; false when `o` is not a pair of that shape.
bool rotation_translation(const py::handle& o, std::vector<double>& v) {
  if (!(py::isinstance<py::tuple>(o) || py::isinstance<py::list>(o)) || py::len(o) != 2) return false;
  const py::sequence s = py::reinterpret_borrow<py::sequence>(o);
  const Array R = numbers(s[0]), t = numbers(s[1]);
  if (!R || !t || R.ndim() != 2 || R.shape(0) != 3 || R.shape(1) != 3 || t.ndim() != 1 || t.shape(0) != 3) return false;
  v.clear();
  for (int i = 0; i < 3; ++i) v.insert(v.end(), {R.at(i, 0), R.at(i, 1), R.at(i, 2), t.at(i)});
  return true;
}

// {"translation": [3], "rotation_wxyz": [4]}, the pose `voxcd pair --json` prints (the rotation optional).
RigidPose dict_pose(const py::dict& d, const std::string& what) {
  std::vector<double> v;
  for (const auto& [key, value] : d) {
    const std::string k = py::str(key);
    if (k != "translation" && k != "rotation_wxyz")
      value_error(what + ": " + k + ": unknown key (known: translation, rotation_wxyz)");
  }
  for (const char* key : {"translation", "rotation_wxyz"}) {
    if (!d.contains(key)) {
      if (key[0] == 't') value_error(what + ": translation: missing");
      continue;
    }
    const Array a = numbers(d[key]);
    const py::ssize_t n = key[0] == 't' ? 3 : 4;
    if (!a || a.ndim() != 1 || a.shape(0) != n)
      value_error(what + ": " + key + " must be " + std::to_string(n) + " numbers");
    v.insert(v.end(), a.data(), a.data() + n);
  }
  return pose_of(v.data(), v.size(), what);
}

[[noreturn]] void shape_error(const std::string& what, const std::string& got, bool many) {
  value_error(what + ": give 3 (tx, ty, tz), 6 (tx, ty, tz, rx, ry, rz in degrees), 7 (tx, ty, tz, qw, qx, qy, qz), 12 "
                     "or 16 numbers (a 3 x 4 or 4 x 4 matrix, row-major), a 3 x 4 or 4 x 4 matrix, (R, t) or a "
                     "{'translation', 'rotation_wxyz'} dict" +
              std::string(many ? ", or an (N, 3), (N, 6), (N, 7), (N, 12), (N, 16), (N, 3, 4) or (N, 4, 4) array of "
                                 "them"
                               : "") +
              "; got " + got);
}

}  // namespace

std::vector<RigidPose> poses_arg(const py::object& pose, const std::string& what, bool& many) {
  many = false;
  if (pose.is_none()) return {RigidPose{}};
  if (py::isinstance<py::dict>(pose)) return {dict_pose(pose.cast<py::dict>(), what)};
  std::vector<double> rt;
  if (rotation_translation(pose, rt)) return {pose_of(rt.data(), rt.size(), what)};
  const Array a = numbers(pose);
  if (!a) value_error(what + ": not numbers: " + py::repr(pose).cast<std::string>());
  const double* v = a.data();
  if (a.ndim() == 1) {
    if (!pose_width(a.shape(0))) shape_error(what, "shape " + shape_text(a), true);
    return {pose_of(v, size_t(a.shape(0)), what)};
  }
  // A matrix is one pose; (N, k) and (N, 3 or 4, 4) arrays are N. (3, 4) and (4, 4) cannot be rows of poses: no pose
  // has 4 numbers.
  const bool matrix = a.ndim() == 2 && a.shape(1) == 4 && (a.shape(0) == 3 || a.shape(0) == 4);
  if (matrix) return {pose_of(v, size_t(a.size()), what)};
  const bool rows = a.ndim() == 2 && pose_width(a.shape(1));
  const bool matrices = a.ndim() == 3 && a.shape(2) == 4 && (a.shape(1) == 3 || a.shape(1) == 4);
  if (!rows && !matrices) shape_error(what, "shape " + shape_text(a), true);
  const size_t w = size_t(a.size() / std::max<py::ssize_t>(a.shape(0), 1));
  many = true;
  std::vector<RigidPose> out;
  for (py::ssize_t k = 0; k < a.shape(0); ++k, v += w)
    out.push_back(pose_of(v, w, what + "[" + std::to_string(k) + "]"));
  return out;
}

RigidPose pose_arg(const py::object& pose, const std::string& what) {
  bool many = false;
  const std::vector<RigidPose> p = poses_arg(pose, what, many);
  if (many) shape_error(what, "an array of " + std::to_string(p.size()) + " poses (one pose here)", false);
  return p.at(0);
}

}  // namespace voxcd::python
