// import voxcd: the module, its version, the library's lists (backends, shapes, broadphases) and how the library's
// errors reach Python (docs/python.md, "Errors").
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "voxcd/host/api/errors.h"
#include "voxcd/host/api/names.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/device/timing_table.h"
#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/python/bindings.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/energy_table.h"
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

void value_error(const std::string& message) { throw ArgumentError(message); }

void deprecation(const std::string& message) {
  if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 1) != 0) throw py::error_already_set();
}

namespace {

void warn_both() {
  deprecation("both is deprecated: use both_directions (the same keyword; docs/python.md, \"Deprecated spellings\")");
}

[[noreturn]] void both_differ(bool both) {
  value_error(std::string("both: is both_directions' deprecated spelling, and is ") + (both ? "True" : "False") +
              " where both_directions is " + (both ? "False" : "True"));
}

}  // namespace

bool both_directions_arg(bool both_directions, std::optional<bool> both, bool fallback) {
  if (!both) return both_directions;
  if (both_directions != fallback && both_directions != *both) both_differ(*both);
  warn_both();
  return *both;
}

std::optional<bool> both_directions_arg(std::optional<bool> both_directions, std::optional<bool> both) {
  if (!both) return both_directions;
  if (both_directions && *both_directions != *both) both_differ(*both);
  warn_both();
  return both;
}

void warn_notes(const RunConfig& c) {
  for (const std::string& note : c.notes) deprecation(note);
}

void check_distance_args(int distance_bits, double band) {
  if (distance_bits != 0 && !valid_distance_bits(distance_bits))
    value_error("distance_bits: " + std::to_string(distance_bits) + " is not " + distance_bits_text() +
                " (or 0 for no distance field)");
  if (!(std::isfinite(band) && band > 0))
    value_error("band: " + py::repr(py::float_(band)).cast<std::string>() + " is not a positive finite number of voxels");
}

namespace {

// The Python class of each library error: voxcd.Error (a RuntimeError) and one subclass of the same name per type,
// also a ValueError where it is bad input (the class such errors had before: `except ValueError` still works).
struct ErrorClass {
  const char* name;
  bool value_error;
  bool (*matches)(const Error&);
  PyObject* type = nullptr;
};

template <class T>
bool is(const Error& e) {
  return dynamic_cast<const T*>(&e) != nullptr;
}

// A setting the library refuses (OptionError) or a keyword argument the module refuses before calling it.
bool is_option(const Error& e) { return is<OptionError>(e) || is<ArgumentError>(e); }

// Most derived first: the first match names the class (every type derives from Error directly).
ErrorClass error_classes[] = {
    {"RangeError", true, is<RangeError>},         {"ConfigError", true, is<ConfigError>},
    {"JobError", false, is<JobError>},            {"VectorError", true, is<VectorError>},
    {"MeshError", true, is<MeshError>},           {"ObjectFileError", true, is<ObjectFileError>},
    {"CapacityError", true, is<CapacityError>},   {"DeviceError", false, is<DeviceError>},
    {"SceneFileError", true, is<SceneFileError>}, {"OptionError", true, is_option},
    {"PlacementError", true, is<PlacementError>}, {"RecordError", true, is<RecordError>},
    {"SizeError", true, is<SizeError>},           {"BodyError", true, is<BodyError>},
    {"TimingTableError", false, is<TimingTableError>},
    {"EnergyTableError", false, is<EnergyTableError>},
    {"Error", false, [](const Error&) { return true; }},
};

// The exception raised for e: its class's instance with the message as its argument, and `where` (and the fields
// some types carry: OptionError's options, BodyError's body and field, SizeError's constraint and factor).
void raise_as(const ErrorClass& c, const Error& e) {
  py::object exc = py::reinterpret_borrow<py::object>(c.type)(py::str(e.what()));
  exc.attr("where") = e.where();
  if (const auto* o = dynamic_cast<const OptionError*>(&e)) exc.attr("options") = o->options;
  if (is<ArgumentError>(e)) exc.attr("options") = e.where().empty() ? py::list() : py::list(py::make_tuple(e.where()));
  if (const auto* b = dynamic_cast<const BodyError*>(&e)) {
    exc.attr("body") = b->body;
    exc.attr("field") = b->field;
  }
  if (const auto* z = dynamic_cast<const SizeError*>(&e)) {
    exc.attr("constraint") = z->constraint;
    exc.attr("factor") = z->factor;
  }
  PyErr_SetObject(c.type, exc.ptr());
}

// The library's errors as their classes above; anything else goes on to pybind11's own translation (std::
// invalid_argument a ValueError, the rest a RuntimeError). The message is the library's.
void translate_error(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const Error& e) {
    for (const ErrorClass& c : error_classes)
      if (c.matches(e)) return raise_as(c, e);
  }
}

void bind_errors(py::module_& m) {
  PyObject* base = nullptr;
  for (auto it = std::rbegin(error_classes); it != std::rend(error_classes); ++it) {
    const std::string qualified = std::string("voxcd.") + it->name;
    py::tuple bases = !base            ? py::make_tuple(py::handle(PyExc_RuntimeError))
                      : it->value_error ? py::make_tuple(py::handle(base), py::handle(PyExc_ValueError))
                                        : py::make_tuple(py::handle(base));
    it->type = PyErr_NewException(qualified.c_str(), bases.ptr(), nullptr);
    if (!it->type) throw py::error_already_set();
    m.add_object(it->name, py::handle(it->type));
    if (!base) base = it->type;
  }
  py::register_exception_translator(&translate_error);
}

}  // namespace

}  // namespace voxcd::python

PYBIND11_MODULE(voxcd, m) {
  namespace py = pybind11;
  using namespace voxcd;
  m.doc() = "voxcd: voxel collision detection on a modelled point-lookup accelerator (docs/python.md)";
  m.attr("__version__") = VOXCD_VERSION;

  voxcd::python::bind_errors(m);

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
  m.def("broadphases", &broadphase_names,
        "The broadphases, by name (for simulate(broadphase=...), World(broadphase=...)).");
  m.attr("EMPTY") = int(kEmpty);
  m.attr("SURFACE") = int(kSurface);
  m.attr("INTERIOR") = int(kInterior);

  using namespace voxcd::python;
  for (const auto bind : {bind_objects, bind_pairs, bind_scenes, bind_conformance, bind_record, bind_api}) bind(m);
}
