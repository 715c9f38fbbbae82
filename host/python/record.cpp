// Recordings: voxcd.read_recording (a recording as numpy arrays, docs/view.md); voxcd.simulate(record=...) writes one.
#include <cstring>

#include "voxcd/host/python/bindings.h"
#include "voxcd/host/scene/record.h"

namespace voxcd::python {

namespace {

// An (n, k) array of T copied from n items of k values each.
template <class T, class Item>
py::array_t<T> rows(const std::vector<Item>& v, size_t k) {
  py::array_t<T> a({v.size(), k});
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * k * sizeof(T));
  return a;
}

py::dict type_dict(const RecordedType& t) {
  py::dict d;
  d["name"] = t.name;
  d["voxel"] = t.voxel;
  d["origin"] = py::make_tuple(t.origin[0], t.origin[1], t.origin[2]);
  d["dims"] = py::make_tuple(t.dims[0], t.dims[1], t.dims[2]);
  d["centre"] = py::make_tuple(t.centre[0], t.centre[1], t.centre[2]);
  d["radius"] = t.radius;
  d["from_mesh"] = t.from_mesh;
  d["vertices"] = rows<float>(t.vertices, 3);
  d["triangles"] = rows<uint32_t>(t.triangles, 3);
  d["shell_points"] = rows<float>(t.shell_points, 3);
  d["shell_normals"] = rows<float>(t.shell_normals, 3);
  return d;
}

// A recorded frame's statistics: its counters, those of continuous collision and the seconds of each stage.
py::dict stats_dict(const FrameStats& s) {
  py::dict d = frame_counts(s);
  for (const auto& [k, v] : {std::pair{"ccd_iterations", s.ccd_iterations}, {"ccd_queries", s.ccd_queries},
                             {"ccd_limited", s.ccd_limited}, {"ccd_toi", s.ccd_toi}, {"ccd_dropped", s.ccd_dropped},
                             {"ccd_lookups", s.ccd_lookups}})
    d[k] = v;
  for (const auto& [k, v] : {std::pair{"t_integrate", s.t_integrate}, {"t_bounds", s.t_bounds},
                             {"t_broadphase", s.t_broadphase}, {"t_narrow", s.t_narrow}, {"t_response", s.t_response}})
    d[k] = v;
  return d;
}

py::dict frame_dict(const RecordedFrame& f) {
  py::dict d;
  d["stats"] = stats_dict(f.stats);
  d["positions"] = rows<float>(f.positions, 3);
  d["rotations"] = rows<float>(f.rotations, 4);
  std::vector<std::array<uint32_t, 2>> pairs;
  for (const BodyPair& p : f.pairs) pairs.push_back({p.first, p.second});
  d["pairs"] = rows<uint32_t>(pairs, 2);
  d["pair_flags"] = py::array_t<uint8_t>(py::ssize_t(f.pair_flags.size()), f.pair_flags.data());
  const size_t n = f.contacts.size();
  const py::ssize_t len = py::ssize_t(n);
  py::array_t<uint32_t> pair(len), point(len);
  py::array_t<bool> a_in_b(len);
  py::array_t<float> position({n, size_t(3)}), normal({n, size_t(3)}), depth(len);
  for (size_t i = 0; i < n; ++i) {
    const RecordedContact& c = f.contacts[i];
    pair.mutable_at(i) = c.pair;
    point.mutable_at(i) = c.point;
    a_in_b.mutable_at(i) = c.a_in_b;
    depth.mutable_at(i) = c.depth;
    for (size_t k = 0; k < 3; ++k) position.mutable_at(i, k) = c.position[k], normal.mutable_at(i, k) = c.normal[k];
  }
  d["contacts"] = py::dict(py::arg("pair") = pair, py::arg("a_in_b") = a_in_b, py::arg("point") = point,
                           py::arg("position") = position, py::arg("normal") = normal, py::arg("depth") = depth);
  return d;
}

py::dict read_recording_py(const py::object& path) {
  const std::string file = path_arg(path, "path");
  Recording r;
  with_file(file, [&] {
    py::gil_scoped_release unlocked;
    r = read_recording(file);
  });
  py::dict d;
  d["version"] = r.version;
  d["run"] = py::module_::import("json").attr("loads")(r.run);
  py::list types, frames;
  for (const RecordedType& t : r.types) types.append(type_dict(t));
  for (const RecordedFrame& f : r.frames) frames.append(frame_dict(f));
  d["types"] = types;
  d["body_types"] = py::array_t<uint32_t>(py::ssize_t(r.body_types.size()), r.body_types.data());
  d["frames"] = frames;
  d["truncated"] = r.truncated;
  d["note"] = r.note;
  return d;
}

}  // namespace

py::dict frame_counts(const FrameStats& s) {
  py::dict d;
  for (const auto& [k, v] : {std::pair{"frame", s.frame}, {"pairs", s.pairs}, {"tested", s.tested},
                             {"touching", s.touching}, {"responses", s.responses}, {"wall_hits", s.wall_hits},
                             {"lookups", s.lookups}, {"hits", s.hits}, {"contacts", s.contacts},
                             {"device_cycles", s.device_cycles}})
    d[k] = v;
  return d;
}

void bind_record(py::module_& m) {
  m.def("read_recording", &read_recording_py, py::arg("path"),
        R"(A recording (simulate(record=...), `voxcd simulate --record`; docs/view.md) as a dict: version, run (the
run's settings), types (name, voxel, dims, centre, radius, vertices, triangles, shell_points, shell_normals as numpy
arrays), body_types, frames (each: stats, positions (n, 3), rotations (n, 4) as w, x, y, z, pairs (p, 2),
pair_flags (1 tested, 2 touching), contacts: pair, a_in_b, point, position, normal, depth), truncated and note
(where a file still being written, or cut short, ends: its whole frames are read). ValueError for a file that is not
a recording, of another format version, or damaged.)");
}

}  // namespace voxcd::python
