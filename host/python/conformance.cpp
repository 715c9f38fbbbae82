// Conformance vectors: voxcd.generate_vectors (a file, as `voxcd conform --generate` writes it) and voxcd.conform
// (files run on a backend and compared with their expectations, as `voxcd conform` runs them).
#include <cstdint>
#include <stdexcept>

#include "voxcd/host/device/conform.h"
#include "voxcd/host/python/bindings.h"
#include "voxcd/ref/vectors.h"

namespace voxcd::python {

namespace {

py::dict generate(const py::object& path, uint64_t seed, int64_t jobs, int64_t cloud_points,
                  std::optional<int> lanes, std::optional<std::string> config) {
  const std::string out = path_arg(path, "path");
  if (jobs < 0) value_error("jobs: " + std::to_string(jobs) + " is negative");
  if (cloud_points < 0) value_error("cloud_points: " + std::to_string(cloud_points) + " is negative");
  GenerateOptions g;
  g.seed = seed;
  g.jobs = size_t(jobs);
  g.cloud_points = size_t(cloud_points);
  if (config) g.config = parse_config_pairs(*config, "config");
  if (lanes) g.config.LANES = *lanes;
  GeneratedFile w;
  try {
    py::gil_scoped_release unlocked;
    w = write_generated_vectors(out, g, config.value_or(""));
  } catch (const Error&) {
    throw;  // the library's own (a configuration, a vector): not the file system's
  } catch (const std::runtime_error& e) {
    PyErr_SetString(PyExc_OSError, e.what());  // the file could not be written whole
    throw py::error_already_set();
  }
  return py::dict(py::arg("file") = out, py::arg("jobs") = w.jobs, py::arg("shell_words") = w.shell_words,
                  py::arg("map_words") = w.map_words, py::arg("lookups") = w.lookups, py::arg("seed") = seed,
                  py::arg("config") = w.config.to_string());
}

py::dict conform(const py::object& files, const std::string& backend, std::optional<int> lanes, bool cycles) {
  std::vector<std::string> paths;
  if (py::isinstance<py::str>(files) || !py::isinstance<py::iterable>(files)) {
    paths.push_back(path_arg(files, "files"));
  } else {
    for (const py::handle h : files) paths.push_back(path_arg(h, "files"));
  }
  ConformOptions opt;
  opt.backend = backend;
  opt.lanes = lanes;
  opt.cycles = cycles;
  size_t passed = 0, failed = 0;
  py::list results;
  for (const std::string& p : paths) {
    ConformResult r;
    {
      py::gil_scoped_release unlocked;
      r = run_conformance(p, opt);
    }
    (r.ok() ? passed : failed) += 1;
    results.append(py::dict(py::arg("file") = r.file, py::arg("ok") = r.ok(), py::arg("error") = r.error,
                            py::arg("jobs") = r.jobs, py::arg("expected_records") = r.expected,
                            py::arg("records") = r.stream.size()));
  }
  return py::dict(py::arg("ok") = failed == 0, py::arg("passed") = passed, py::arg("failed") = failed,
                  py::arg("results") = results);
}

}  // namespace

void bind_conformance(py::module_& m) {
  m.def("generate_vectors", &generate, py::arg("path"), py::kw_only(), py::arg("seed") = 1, py::arg("jobs") = 200,
        py::arg("cloud_points") = 2000, py::arg("lanes") = py::none(), py::arg("config") = py::none(),
        R"(Writes random conformance vectors with expectations from ref/ to path, as `voxcd conform --generate -o
PATH` does (docs/conformance.md); config is a device configuration as NAME VALUE pairs. Returns what it wrote:
{'file', 'jobs', 'shell_words', 'map_words', 'lookups', 'seed', 'config'}. OSError when the file cannot be written
whole (nothing is left behind).)");
  m.def("conform", &conform, py::arg("files"), py::kw_only(), py::arg("backend") = "ref",
        py::arg("lanes") = py::none(), py::arg("cycles") = false,
        R"(Runs vector files (a path or a list of paths) on a backend and compares each stream with the file's
expectations, as `voxcd conform FILE...` does. Returns {'ok', 'passed', 'failed', 'results'}: per file, 'file',
'ok', 'error' (why it failed, the tool's FAIL line: a malformed or missing file, a backend that cannot run it, or
the first difference), 'jobs', 'expected_records' and 'records' (the backend's).)");
}

}  // namespace voxcd::python
