// The Python module (import voxcd): what its files share. Each file binds one part of the library (objects, pairs,
// scenes, conformance); docs/python.md documents the module.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <filesystem>
#include <string>
#include <system_error>

namespace voxcd::python {

namespace py = pybind11;

void bind_objects(py::module_& m);
void bind_pairs(py::module_& m);
void bind_scenes(py::module_& m);
void bind_conformance(py::module_& m);
void bind_record(py::module_& m);

// A path argument: a str or an os.PathLike giving one. TypeError naming `what` for anything else.
std::string path_arg(const py::handle& h, const char* what);

// Raises ValueError with the message: an argument the module refuses before calling the library.
[[noreturn]] void value_error(const std::string& message);

// The distance fields asked for (voxelize, Pair): ValueError naming the keyword for distance_bits other than 0 (no
// field), 4, 8 or 16, or a band that is not a positive finite number of voxels.
void check_distance_args(int distance_bits, double band);

// Runs f(); when it throws and the file `path` (not "") does not exist, raises FileNotFoundError carrying the
// library's message instead of the error it would map to (docs/python.md, "Errors").
template <class F>
auto with_file(const std::string& path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const py::error_already_set&) {
    throw;
  } catch (const std::exception& e) {
    std::error_code ec;
    if (path.empty() || std::filesystem::exists(path, ec) || ec) throw;
    PyErr_SetString(PyExc_FileNotFoundError, e.what());
    throw py::error_already_set();
  }
}

}  // namespace voxcd::python
