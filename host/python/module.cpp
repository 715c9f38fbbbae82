// import voxcd: the module, its version, the library's lists (backends, shapes, broadphases) and how the library's
// errors reach Python (docs/python.md, "Errors").
#include <cmath>
#include <stdexcept>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/object/mesh.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/python/bindings.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/vectors.h"
#include "voxcd/version.h"

namespace voxcd::python {

std::string path_arg(const py::handle& h, const char* what) {
  if (py::isinstance<py::str>(h)) return h.cast<std::string>();
  const py::object os = py::module_::import("os");
  if (py::isinstance(h, os.attr("PathLike"))) {
    const py::object p = os.attr("fspath")(h);
    if (py::isinstance<py::str>(p)) return p.cast<std::string>();
  }
  throw py::type_error(std::string(what) + " must be a str or an os.PathLike naming a file, not " +
                       py::str(py::type::handle_of(h).attr("__name__")).cast<std::string>());
}

void value_error(const std::string& message) { throw py::value_error(message); }

void check_distance_args(int distance_bits, double band) {
  if (distance_bits != 0 && !valid_distance_bits(distance_bits))
    value_error("distance_bits: " + std::to_string(distance_bits) + " is not " + distance_bits_text() +
                " (or 0 for no distance field)");
  if (!(std::isfinite(band) && band > 0))
    value_error("band: " + py::repr(py::float_(band)).cast<std::string>() + " is not a positive finite number of voxels");
}

namespace {

// True when e is one of the exception types Bad.
template <class... Bad>
bool is_one_of(const std::exception& e) {
  return (... || (dynamic_cast<const Bad*>(&e) != nullptr));
}

// A backend that cannot run is a RuntimeError; bad input (the values given, or the files they name) a ValueError;
// anything else goes on to pybind11's own translation (a RuntimeError). The message is the library's.
void translate_error(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const DeviceError& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
  } catch (const std::exception& e) {
    if (!is_one_of<MeshError, ObjectFileError, SceneFileError, VectorError, RangeError, CapacityError,
                   PlacementError, RecordError>(e))
      throw;
    PyErr_SetString(PyExc_ValueError, e.what());
  }
}

}  // namespace

}  // namespace voxcd::python

PYBIND11_MODULE(voxcd, m) {
  namespace py = pybind11;
  using namespace voxcd;
  m.doc() = "voxcd: voxel collision detection on a modelled point-lookup accelerator (docs/python.md)";
  m.attr("__version__") = VOXCD_VERSION;

  py::register_exception_translator(&voxcd::python::translate_error);

  m.def("backends", &device_backends, "The device backends that can run here, by name (for backend=...).");
  m.def(
      "backend_status",
      [] {
        py::list out;
        for (const BackendStatus& b : backend_status())
          out.append(py::dict(py::arg("name") = b.name, py::arg("ready") = b.ready, py::arg("why_not") = b.why_not));
        return out;
      },
      "Every backend as {name, ready, why_not}: rtl and sysc-* need the device models (cmake --build build "
      "--target voxcd_models), which why_not names when they are not built.");
  m.def("shapes", &shape_names, "The built-in shapes, by name (for voxelize, pair and simulate).");
  m.def("broadphases", &broadphase_names, "The broadphases, by name (for simulate(pruning=...)).");
  m.attr("EMPTY") = int(kEmpty);
  m.attr("SURFACE") = int(kSurface);
  m.attr("INTERIOR") = int(kInterior);

  using namespace voxcd::python;
  for (const auto bind : {bind_objects, bind_pairs, bind_scenes, bind_conformance, bind_record, bind_api}) bind(m);
}
