// The Python module (import voxcd): what its files share. Each file binds one part of the library (objects, pairs,
// scenes, conformance, recordings, the public API); docs/python.md documents the module.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <exception>
#include <memory>
#include <optional>
#include <tuple>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "voxcd/ref/error.h"

namespace voxcd {
struct FrameStats;
class Object;
struct ObjectFile;
struct ObjectType;
struct Contacts;
using PairResult = Contacts;
struct Pose;
using RigidPose = Pose;
struct RunConfig;
}  // namespace voxcd

namespace voxcd::python {

namespace py = pybind11;

// module.cpp: the module, and what every part uses. Each bind_* below binds one part of the library into it.

// A path argument: a str or an os.PathLike giving one. TypeError naming `what` for anything else.
std::string path_arg(const py::handle& h, const char* what);

// A keyword argument the module refuses before calling the library: raised as voxcd.OptionError (a ValueError),
// `where` the message's leading place (the keyword).
struct ArgumentError : Error {
  using Error::Error;
};
// Throws ArgumentError with the message.
[[noreturn]] void value_error(const std::string& message);

// Emits a DeprecationWarning with the message (a deprecated spelling used; docs/python.md, "Deprecated spellings");
// raises it when the warning filters make it an error.
void deprecation(const std::string& message);

// The both-directions option of a call that takes `both_directions` and `both`, its deprecated spelling (None: not
// given): `both` when given, with a DeprecationWarning; OptionError when the two are given and differ (`both_directions`
// counts as given when it is not its default, `fallback`).
bool both_directions_arg(bool both_directions, std::optional<bool> both, bool fallback = true);
std::optional<bool> both_directions_arg(std::optional<bool> both_directions, std::optional<bool> both);

// poses.cpp: poses as every function takes them (through host/pairs/pose_text.h's parser). One pose: None (the
// identity), 3, 6, 7, 12 or 16 numbers (translation; then degrees about x, y, z; or a quaternion w, x, y, z; or a
// 3 x 4 or 4 x 4 matrix, row-major), a 3 x 4 or 4 x 4 matrix, (R, t), or the dict `voxcd pair --json` prints for a
// pose. ValueError "WHAT: ..." for anything else, a number that is not finite or a rotation that is not one.
RigidPose pose_arg(const py::object& pose, const std::string& what);
// One pose as above, or an array of them ((N, k) for k of those counts, (N, 3, 4), (N, 4, 4)): `many` says which.
std::vector<RigidPose> poses_arg(const py::object& pose, const std::string& what, bool& many);

// The distance fields asked for (voxelize, Pair): ValueError naming the keyword for distance_bits other than 0 (no
// field), 4, 8 or 16, or a band that is not a positive finite number of voxels.
void check_distance_args(int distance_bits, double band);

// objects.cpp: voxcd.voxelize, voxcd.read_object and voxcd.Object.
void bind_objects(py::module_& m);

// object_storage.cpp: Object.storage, Object.memory and Object.bricks (which parts are sparse, their device memory
// in both forms, the sparse forms' bricks).
using ObjectClass = py::class_<ObjectFile, std::shared_ptr<ObjectFile>>;
void bind_object_storage(ObjectClass& cls);

// pairs.cpp: voxcd.Pair and voxcd.pair.
void bind_pairs(py::module_& m);

// A pair's result as the module gives it: hits, lookups, device_cycles (None without cycles) and the contacts as
// numpy arrays.
py::dict contacts_dict(const PairResult& r, bool cycles);

// scenes.cpp: voxcd.simulate and voxcd.size.
void bind_scenes(py::module_& m);

// The arguments of a run after `scene` (keyword-only), as simulate() and World.scene() take them.
inline auto run_args() {
  return std::make_tuple(
      py::arg("scene") = py::none(), py::kw_only(), py::arg("frames") = py::none(), py::arg("objects") = py::none(),
      py::arg("shape") = py::none(), py::arg("voxel") = py::none(), py::arg("resolution") = py::none(),
      py::arg("density") = py::none(), py::arg("speed") = py::none(), py::arg("seed") = py::none(),
      py::arg("broadphase") = py::none(), py::arg("backend") = py::none(), py::arg("lanes") = py::none(),
      py::arg("mode") = py::none(), py::arg("both_directions") = py::none(), py::arg("clock") = py::none(),
      py::arg("config") = py::none(), py::arg("threads") = 0u, py::arg("midphase") = true, py::arg("cull") = true,
      py::arg("distance_bits") = py::none(), py::arg("band") = py::none(), py::arg("margin") = py::none(),
      py::arg("ccd") = py::none(), py::arg("pruning") = py::none(), py::arg("both") = py::none());
}

// The values of run_args(), None where not given.
struct RunArgs {
  py::object scene, frames, objects;
  std::optional<std::string> shape;
  std::optional<double> voxel;
  py::object resolution;
  std::optional<double> density, speed;
  py::object seed;
  std::optional<std::string> broadphase, backend;
  std::optional<int> lanes;
  std::optional<std::string> mode;
  std::optional<bool> both_directions;
  std::optional<double> clock;
  std::optional<std::string> config;
  unsigned threads = 0;
  bool midphase = true, cull = true;
  std::optional<int> distance_bits;
  std::optional<double> band, margin;
  std::optional<bool> ccd;
  std::optional<std::string> pruning;  // broadphase's deprecated spelling
  std::optional<bool> both;            // both_directions' deprecated spelling
};

// A function of run_args()'s arguments, then `Extra` ones, that returns finish(RunArgs, extra...): the one parameter
// list of simulate() and World.scene().
template <class... Extra, class F>
auto run_function(F finish) {
  return [finish](const py::object& scene, const py::object& frames, const py::object& objects,
                  std::optional<std::string> shape, std::optional<double> voxel, const py::object& resolution,
                  std::optional<double> density, std::optional<double> speed, const py::object& seed,
                  std::optional<std::string> broadphase, std::optional<std::string> backend, std::optional<int> lanes,
                  std::optional<std::string> mode, std::optional<bool> both_directions, std::optional<double> clock,
                  std::optional<std::string> config, unsigned threads, bool midphase, bool cull,
                  std::optional<int> distance_bits, std::optional<double> band, std::optional<double> margin,
                  std::optional<bool> ccd, std::optional<std::string> pruning, std::optional<bool> both,
                  Extra... extra) {
    return finish(RunArgs{scene, frames, objects, std::move(shape), voxel, resolution, density, speed, seed,
                          std::move(broadphase), std::move(backend), lanes, std::move(mode), both_directions, clock,
                          std::move(config), threads, midphase, cull, distance_bits, band, margin, ccd,
                          std::move(pruning), both},
                  extra...);
  };
}

// Those arguments (and `record`) as the settings they give over the scene file (RunConfig::given; run_config applies
// them); `text` is set to a dict scene's JSON. ValueError or TypeError naming the keyword for a value it cannot take.
RunConfig run_options(const RunArgs& a, const py::object& record, std::optional<std::string>& text);
// A DeprecationWarning for each deprecated spelling a run's scene file or options used (RunConfig::notes).
void warn_notes(const RunConfig& c);

// conformance.cpp: voxcd.generate_vectors and voxcd.conform.
void bind_conformance(py::module_& m);

// record.cpp: voxcd.read_recording.
void bind_record(py::module_& m);

// A frame's counters as a dict: frame, pairs, tested, touching, responses, wall_hits, lookups, hits, contacts,
// device_cycles (World.step() and a recording's frames add more).
py::dict frame_counts(const FrameStats& s);

// api.cpp: voxcd.collide, and the public API's arguments.
void bind_api(py::module_& m);

// A voxcd.Object of an object file's form; the library's Object of it is made at its first query and kept with it.
std::shared_ptr<ObjectFile> python_object(ObjectFile obj);
// The voxcd.Object of a C++ Object (Object.load, Object.from_arrays, Pair.a), which it keeps: no copy.
std::shared_ptr<ObjectFile> python_object(const Object& object);
// The library's Object of a voxcd.Object (made once per object; MeshError for one that cannot be queried).
Object library_object(const std::shared_ptr<ObjectFile>& obj);
// An object argument: a voxcd.Object, or anything voxelize takes (voxelised at 32 voxels along its longest side).
Object object_arg(const py::object& o);
// Three numbers (None: zeros); ValueError naming `what` for anything else.
Eigen::Vector3d vec3_arg(const py::object& v, const char* what);

// world.cpp: voxcd.World and voxcd.BodyId.
void bind_world(py::module_& m);

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
