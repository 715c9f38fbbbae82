// Objects: voxcd.voxelize (a mesh file or a built-in shape, as `voxcd voxelize`), voxcd.read_object and the
// voxcd.Object they give: the voxmap's states, its grid, the point shell and the repair report as numpy arrays and
// dicts, and save(path) (an object file).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "voxcd/host/api/object.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/python/bindings.h"
#include "voxcd/host/report/object_report.h"

namespace voxcd::python {

namespace {

using ObjectPtr = std::shared_ptr<ObjectFile>;

py::array_t<double> vec3(const Eigen::Vector3d& v) {
  py::array_t<double> a(3);
  auto w = a.mutable_unchecked<1>();
  for (int i = 0; i < 3; ++i) w(i) = v[i];
  return a;
}

py::tuple dims3(const std::array<uint32_t, 3>& d) { return py::make_tuple(d[0], d[1], d[2]); }

// A read-only (N, 3) numpy view of `rows`, N items of three T each, kept alive by the Python object `owner`: no copy.
template <class T, class Item>
py::array rows_view(const std::vector<Item>& rows, const py::handle& owner) {
  static_assert(sizeof(Item) == 3 * sizeof(T), "an item is three values, unpadded");
  py::array a(py::dtype::of<T>(), {py::ssize_t(rows.size()), py::ssize_t(3)},
              {py::ssize_t(sizeof(Item)), py::ssize_t(sizeof(T))}, rows.empty() ? nullptr : rows.front().data(), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// The voxmap's states indexed [x, y, z]: Fortran order, so that element (x, y, z) sits at the voxmap's linear
// index x + nx * (y + ny * z).
py::array_t<uint8_t> states(const Voxmap& vm) {
  const auto& d = vm.dims();
  const py::ssize_t nx = d[0], ny = d[1], nz = d[2];
  py::array_t<uint8_t, py::array::f_style> a({nx, ny, nz});
  uint8_t* out = a.mutable_data();
  for (uint64_t i = 0; i < vm.size(); ++i) out[i] = uint8_t(vm.at(i));
  return a;
}

// The distance field's node values indexed [X, Y, Z] (Fortran order, as `states`).
py::array_t<int16_t, py::array::f_style> node_array(const DistanceField& f) {
  const py::ssize_t nx = f.dims[0] + 1, ny = f.dims[1] + 1, nz = f.dims[2] + 1;
  py::array_t<int16_t, py::array::f_style> a({nx, ny, nz});
  std::copy(f.q.begin(), f.q.end(), a.mutable_data());
  return a;
}

// The field as a dense array: the dense field, or a sparse one's level-0 nodes where its grid fits a dense field
// (ValueError saying why not); None without a field.
py::object distance(const ObjectFile& o) {
  if (!o.has_distance()) return py::none();
  if (!o.distance_sparse()) return node_array(o.distance);
  const auto& d = o.sparse_distance.dims();
  if (std::max({d[0], d[1], d[2]}) > kMaxDenseDim)
    value_error("the object's distance field is stored sparse on a grid of " + std::to_string(d[0]) + "x" +
                std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels, larger than a dense field's " +
                std::to_string(kMaxDenseDim) + " per axis: it has no dense array (memory and bricks describe it)");
  return node_array(dense_from_sparse(o.sparse_distance));
}

// What loading, repair and voxelising found: `voxcd info --json`'s "repair", made by the same function (None for an
// object file of version 1).
py::object repair_dict(const ObjectFile& obj) {
  return py::module_::import("json").attr("loads")(report::repair_json(obj).dump());
}

// A mesh given as arrays: a (vertices, faces) pair, or an object with .vertices and .faces (trimesh) or
// .vertices and .triangles (Open3D); vertices (V, 3) numbers, faces (F, 3) non-negative integers. None for anything
// else (a path). ValueError naming the array for a wrong shape or an index that is negative or does not fit.
std::optional<Mesh> mesh_arg(const py::object& source) {
  py::object v, f;
  if (py::isinstance<py::tuple>(source) || py::isinstance<py::list>(source)) {
    const py::sequence seq = source;
    if (py::len(seq) != 2) value_error("source: give (vertices, faces), a mesh file, a shape or an object with "
                                       ".vertices and .faces");
    v = seq[0], f = seq[1];
  } else if (py::hasattr(source, "vertices") && (py::hasattr(source, "faces") || py::hasattr(source, "triangles"))) {
    v = source.attr("vertices");
    f = py::hasattr(source, "faces") ? source.attr("faces") : source.attr("triangles");
  } else {
    return std::nullopt;
  }
  const auto np = py::module_::import("numpy");
  const py::array_t<double, py::array::c_style | py::array::forcecast> va = np.attr("asarray")(v, "float64");
  const py::array fa = np.attr("asarray")(f);
  if (va.ndim() != 2 || va.shape(1) != 3) value_error("vertices: give a (V, 3) array of numbers");
  if (fa.ndim() != 2 || fa.shape(1) != 3 || !(fa.dtype().kind() == 'i' || fa.dtype().kind() == 'u'))
    value_error("faces: give an (F, 3) array of integer vertex indices");
  const py::array_t<int64_t, py::array::c_style | py::array::forcecast> fi = fa;
  Mesh m;
  m.name = py::hasattr(source, "metadata") ? "mesh" : "arrays";
  for (py::ssize_t i = 0; i < va.shape(0); ++i)
    m.vertices.emplace_back(va.at(i, 0), va.at(i, 1), va.at(i, 2));
  for (py::ssize_t t = 0; t < fi.shape(0); ++t) {
    std::array<uint32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const int64_t x = fi.at(t, k);
      if (x < 0 || x > int64_t(UINT32_MAX))
        value_error("faces: face " + std::to_string(t) + " has vertex index " + std::to_string(x) +
                    (x < 0 ? " (negative)" : " (too large)"));
      tri[size_t(k)] = uint32_t(x);
    }
    m.triangles.push_back(tri);
  }
  return m;
}

ObjectPtr voxelize_source(const py::object& source, std::optional<double> voxel, std::optional<int64_t> resolution,
                          double shell_ratio, bool strict, unsigned threads, int distance_bits, double band,
                          const std::string& storage) {
  std::optional<Mesh> given = mesh_arg(source);
  const std::string input = given ? std::string() : path_arg(source, "source");
  if (voxel.has_value() == resolution.has_value())
    value_error("give voxel (the voxel edge in mesh units) or resolution (voxels along the longest side), " +
                std::string(voxel ? "not both" : "one of them"));
  if (resolution && (*resolution < 1 || *resolution > int64_t(UINT32_MAX)))
    value_error("resolution: " + std::to_string(*resolution) + " is not a positive count of voxels");
  if (!(std::isfinite(shell_ratio) && shell_ratio > 0))
    value_error("shell_ratio: " + std::to_string(shell_ratio) + " is not a positive finite number");
  check_distance_args(distance_bits, band);
  const std::optional<ObjectStorage> kind = parse_storage(storage);
  if (!kind) value_error("storage: '" + storage + "' is not 'auto', 'dense' or 'sparse'");
  ObjectOptions opt;
  opt.distance_bits = distance_bits;
  opt.band = band;
  opt.voxel = voxel.value_or(0);
  opt.resolution = uint32_t(resolution.value_or(0));
  opt.shell_ratio = shell_ratio;
  opt.threads = threads;
  set_storage(opt, *kind);
  py::gil_scoped_release unlocked;
  // The arrays below read the dense forms: made of a sparse object's where they fit.
  auto made = [](ObjectFile obj) {
    add_dense_forms(obj);
    return python_object(std::move(obj));
  };
  std::string src;
  uint64_t hash = 0;
  MeshReport report;
  if (given) {
    // Repaired (or checked) as a file's mesh is; named "arrays".
    report = strict ? prepare(*given) : repair(*given);
    src = given->name;
    std::string bytes;
    for (const auto& p : given->vertices) bytes.append(reinterpret_cast<const char*>(p.data()), 3 * sizeof(double));
    hash = hash_bytes(bytes);
    return made(make_object(*given, src, hash, opt, &report));
  }
  const Mesh mesh = load_source(input, &src, &hash, &report, LoadOptions{strict});
  return made(make_object(mesh, src, hash, opt, &report));
}

// Object.load's and Object.from_arrays' keywords as the C++ ObjectDef; OptionError naming a keyword it cannot take.
ObjectDef object_def(double voxel, int64_t resolution, int distance_bits, double band, const std::string& storage,
                     bool strict, unsigned threads) {
  if (!(voxel >= 0 && std::isfinite(voxel)))
    value_error("voxel: " + py::repr(py::float_(voxel)).cast<std::string>() + " is not 0 or a positive number");
  if (resolution < 1 || resolution > int64_t(UINT32_MAX))
    value_error("resolution: " + std::to_string(resolution) + " is not a positive count of voxels");
  check_distance_args(distance_bits, band);
  const std::optional<ObjectStorage> kind = parse_storage(storage);
  if (!kind) value_error("storage: '" + storage + "' is not 'auto', 'dense' or 'sparse'");
  ObjectDef def;
  def.voxel = voxel;
  def.resolution = uint32_t(resolution);
  def.distance_bits = distance_bits;
  def.band = band;
  def.storage = *kind;
  def.strict = strict;
  def.threads = threads;
  return def;
}

// Object.load: the C++ Object::load, its ObjectDef's fields as keywords.
ObjectPtr load_object(const py::object& source, double voxel, int64_t resolution, int distance_bits, double band,
                      const std::string& storage, bool strict, unsigned threads) {
  const ObjectDef def = object_def(voxel, resolution, distance_bits, band, storage, strict, threads);
  const std::string path = path_arg(source, "file_or_shape");
  return with_file(is_object_file(path) ? path : "", [&] {
    py::gil_scoped_release unlocked;
    return python_object(Object::load(path, def));
  });
}

// Object.from_arrays: the C++ Object::from_arrays, given the arrays' own memory where they are C-contiguous float64
// vertices and uint32 triangles (other layouts and dtypes are converted first).
ObjectPtr from_arrays(const py::object& vertices, const py::object& triangles, double voxel, int64_t resolution,
                      int distance_bits, double band, const std::string& storage, bool strict, unsigned threads) {
  const ObjectDef def = object_def(voxel, resolution, distance_bits, band, storage, strict, threads);
  const auto np = py::module_::import("numpy");
  using Vertices = py::array_t<double, py::array::c_style | py::array::forcecast>;
  using Triangles = py::array_t<uint32_t, py::array::c_style | py::array::forcecast>;
  const Vertices v = Vertices::ensure(vertices);
  if (!v || v.ndim() != 2 || v.shape(1) != 3) value_error("vertices: give a (V, 3) array of numbers");
  const py::array t = np.attr("asarray")(triangles);
  const char kind = t.dtype().kind();
  if (t.ndim() != 2 || t.shape(1) != 3 || !(kind == 'i' || kind == 'u'))
    value_error("triangles: give an (F, 3) array of integer vertex indices");
  if (t.size() > 0 && (t.attr("min")().cast<int64_t>() < 0 || t.attr("max")().cast<uint64_t>() > UINT32_MAX))
    value_error("triangles: a vertex index is negative or beyond 2^32 - 1");
  const Triangles f = Triangles::ensure(t);
  py::gil_scoped_release unlocked;
  return python_object(Object::from_arrays(v.data(), size_t(v.shape(0)), f.data(), size_t(f.shape(0)), def));
}

}  // namespace

namespace {

// The dense forms the arrays read; ValueError for a sparse object too large for them.
const Voxmap& dense_voxmap(const ObjectFile& o) {
  if (!o.has_dense_voxmap())
    value_error("the object's voxmap is stored sparse and is larger than " + std::to_string(kMaxDenseDim) +
                " voxels per axis: it has no dense states");
  return o.voxmap;
}
const PointShell& dense_shell(const ObjectFile& o) {
  if (o.shell.size() != o.shell_count())
    value_error("the object's shell is stored sparse on a grid too large for its dense form");
  return o.shell;
}

// Object's voxmap: its source, grid and states.
void bind_voxmap(ObjectClass& cls) {
  cls.def_readonly("source", &ObjectFile::source, "The mesh file as given, or 'shape:NAME' for a built-in shape.")
      .def_readonly("source_hash", &ObjectFile::source_hash, "FNV-1a 64 of the source file's bytes (of the shape's name).")
      .def_property_readonly("voxel", [](const ObjectFile& o) { return o.voxmap_grid().voxel; }, "Voxel edge, mesh units.")
      .def_property_readonly("origin", [](const ObjectFile& o) { return vec3(o.voxmap_grid().origin); },
                             "Corner of voxel (0, 0, 0) in the object's frame: voxel (x, y, z) covers origin + "
                             "voxel * ([x, x+1] x [y, y+1] x [z, z+1]).")
      .def_property_readonly("dims", [](const ObjectFile& o) { return dims3(o.voxmap_grid().dims); },
                             "Voxels along x, y and z.")
      .def_property_readonly("states", [](const ObjectFile& o) { return states(dense_voxmap(o)); },
                             "The voxmap's states as a new uint8 array of shape dims, indexed [x, y, z]: EMPTY (0), "
                             "SURFACE (1) or INTERIOR (2).")
      .def_property_readonly(
          "counts",
          [](const ObjectFile& o) {
            const auto c = o.voxmap_counts();
            return py::dict(py::arg("empty") = c[kEmpty], py::arg("surface") = c[kSurface],
                            py::arg("interior") = c[kInterior]);
          },
          "Voxels in each state: {'empty': ..., 'surface': ..., 'interior': ...}.");
}

// Object's point shell.
void bind_shell(ObjectClass& cls) {
  // Views of the shell's arrays, kept alive by the voxcd.Object (self).
  auto shell = [](const py::object& self) -> const PointShell& { return dense_shell(self.cast<const ObjectFile&>()); };
  cls.def_property_readonly(
         "shell_points", [shell](const py::object& self) { return rows_view<double>(shell(self).points, self); },
         "The point shell in the object's frame, an (N, 3) float64 array (shell_count rows): a read-only view of the "
         "object's own (no copy).")
      .def_property_readonly("shell_count", &ObjectFile::shell_count,
                             "The number of shell points (as `voxcd info`'s shell_count; C++ Object::shell_count()).")
      .def_property_readonly(
          "shell_normals", [shell](const py::object& self) { return rows_view<double>(shell(self).normals, self); },
          "Each shell point's outward unit normal, an (N, 3) float64 array: a read-only view (no copy).")
      .def_property_readonly(
          "shell_cells", [shell](const py::object& self) { return rows_view<uint32_t>(shell(self).cells, self); },
          "Each shell point's cell of the shell grid, an (N, 3) uint32 array (a read-only view, no copy): the point is "
          "the cell's centre, or, when shell_on_surface, a point of the cell's closed cube.")
      .def_property_readonly("shell_on_surface", [](const ObjectFile& o) { return o.shell.on_surface; },
                             "True when the shell's points lie on the surface (objects with a distance field): "
                             "each is the closest point of the mesh to a surface cell's centre, rounded to 1/256 of "
                             "the spacing.");
}

// Object's distance field.
void bind_distance(ObjectClass& cls) {
  cls.def_property_readonly("distance_bits", [](const ObjectFile& o) { return o.distance_bits(); },
                             "Bits of the distance field's node values (4, 8 or 16); 0 for an object without one.")
      .def_property_readonly("distance_step", [](const ObjectFile& o) { return o.distance_step(); },
                             "Voxels per unit of a node value (band / 2^(bits-1)); 0 without a field.")
      .def_property_readonly("distance", &distance,
                             "The signed distance field's node values as a new int16 array of shape (nx+1, ny+1, "
                             "nz+1), indexed [X, Y, Z] (node X, Y, Z at origin + voxel * (X, Y, Z)), negative "
                             "inside; times distance_step it is voxels, clamped to the band. A field stored sparse "
                             "gives its level-0 nodes (a refined brick's nodes at those places; ValueError for a "
                             "grid larger than 1024 voxels per axis). None without a field.");
}

// ", 8-bit distance field" for an object with one; "; sparse: voxmap, shell, distance" naming the parts stored
// sparse, "" when none is.
std::string repr_storage(const ObjectFile& o) {
  std::string t = o.has_distance() ? ", " + std::to_string(o.distance_bits()) + "-bit distance field" : "";
  std::string sparse;
  for (const auto& [is, name] : {std::pair{o.voxmap_sparse(), "voxmap"}, std::pair{o.shell_sparse(), "shell"},
                                 std::pair{o.distance_sparse(), "distance"}})
    if (is) sparse += (sparse.empty() ? "; sparse: " : ", ") + std::string(name);
  return t + sparse;
}

std::string object_repr(const ObjectFile& o) {
  const auto& d = o.voxmap_grid().dims;
  return "<voxcd.Object " + o.source + ": " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
         std::to_string(d[2]) + " voxels of " + py::repr(py::float_(o.voxmap_grid().voxel)).cast<std::string>() +
         ", " + std::to_string(o.shell_count()) + " shell points" + repr_storage(o) + ">";
}

// Object's shell grid, report, save() and repr.
void bind_rest(ObjectClass& cls) {
  cls.def_property_readonly("shell_spacing", [](const ObjectFile& o) { return o.shell_grid().voxel; },
                             "The shell grid's spacing: voxel / shell_ratio.")
      .def_property_readonly("shell_origin", [](const ObjectFile& o) { return vec3(o.shell_grid().origin); },
                             "Corner of the shell grid's cell (0, 0, 0) in the object's frame.")
      .def_property_readonly("shell_dims", [](const ObjectFile& o) { return dims3(o.shell_grid().dims); },
                             "Cells of the shell grid along x, y and z.")
      .def_readonly("shell_ratio", &ObjectFile::shell_ratio, "Voxel / shell spacing the shell was built with.")
      .def_property_readonly("report", &repair_dict,
                             "What loading, repair and voxelising found (C++ Object::report()), as `voxcd info --json` "
                             "gives it under 'repair'; None for an object file of version 1.")
      .def_property_readonly(
          "repair",
          [](const ObjectFile& o) {
            deprecation("Object.repair is deprecated: use Object.report (the same dict; docs/python.md, "
                        "\"Deprecated spellings\")");
            return repair_dict(o);
          },
          "Deprecated: Object.report's old name (the same dict, with a DeprecationWarning).")
      .def(
          "save",
          [](const ObjectFile& o, const py::object& path) {
            const std::string p = path_arg(path, "path");
            try {
              py::gil_scoped_release unlocked;
              write_object(p, o);
            } catch (const ObjectFileError& e) {
              PyErr_SetString(PyExc_OSError, e.what());  // the file could not be written
              throw py::error_already_set();
            }
          },
          py::arg("path"), "Writes the object file (as `voxcd voxelize -o`), atomically. OSError when it cannot.")
      .def("__repr__", &object_repr);
}

}  // namespace

void bind_objects(py::module_& m) {
  ObjectClass c(m, "Object", R"(An object: a voxmap (2-bit states on a regular grid) and a point
shell, as `voxcd voxelize` writes them to an object file (docs/objects.md). Made by voxelize() or read_object().)");
  bind_voxmap(c);
  bind_shell(c);
  bind_distance(c);
  bind_object_storage(c);
  bind_rest(c);
  c.def_static("load", &load_object, py::arg("file_or_shape"), py::kw_only(), py::arg("voxel") = 0.0,
               py::arg("resolution") = 32, py::arg("distance_bits") = 0, py::arg("band") = 4.0,
               py::arg("storage") = "dense", py::arg("strict") = false, py::arg("threads") = 0u,
               R"(The C++ Object::load with an ObjectDef's fields and defaults: a mesh file, a built-in shape or an
object file (which brings its own voxel; with distance_bits it must carry a field of that many bits), voxelised at
`voxel` (mesh units) or, when voxel is 0, at `resolution` voxels along its longest side (32).)");
  c.def_static(
      "from_arrays", &from_arrays,
      py::arg("vertices"), py::arg("triangles"), py::kw_only(), py::arg("voxel") = 0.0, py::arg("resolution") = 32,
      py::arg("distance_bits") = 0, py::arg("band") = 4.0, py::arg("storage") = "dense", py::arg("strict") = false,
      py::arg("threads") = 0u,
      R"(The C++ Object::from_arrays: a mesh as a (V, 3) array of vertices and an (F, 3) array of vertex indices,
repaired as a file is (unless strict), with Object.load's keywords and defaults.)");

  m.def("voxelize", &voxelize_source, py::arg("source"), py::kw_only(), py::arg("voxel") = py::none(),
        py::arg("resolution") = py::none(), py::arg("shell_ratio") = std::sqrt(2.0), py::arg("strict") = false,
        py::arg("threads") = 0u, py::arg("distance_bits") = 0, py::arg("band") = 4.0, py::arg("storage") = "auto",
        R"(Voxelises a mesh file (any format `voxcd voxelize` reads; repaired unless strict), a built-in shape
(voxcd.shapes()), or a mesh as arrays: (vertices, faces), or any object with .vertices and .faces (a trimesh mesh;
.triangles for Open3D), vertices (V, 3) numbers and faces (F, 3) integer indices, repaired as a file is; at `voxel`
(mesh units) or at `resolution` voxels along its longest side: exactly one of the two.
distance_bits (4, 8 or 16) also stores the signed distance field over a band of +-band voxels, with the shell on
the surface. storage ('auto', 'dense' or 'sparse') chooses how the voxmap and the shell are kept and saved, as the
tool's --storage (docs/objects.md, "Sparse objects"); the arrays below need the dense forms (ValueError for an object
too large for them). Returns an Object, the same as `voxcd voxelize SOURCE --voxel V | --resolution R
[--distance-bits B --band K] [--storage S]` writes.)");
  m.def(
      "read_object",
      [](const py::object& path) {
        const std::string p = path_arg(path, "path");
        return with_file(p, [&] {
          py::gil_scoped_release unlocked;
          return python_object(read_object(p));
        });
      },
      py::arg("path"), "Reads an object file (written by `voxcd voxelize` or Object.save). ValueError naming the "
                       "problem for a file that is not one; FileNotFoundError when there is none.");
}

}  // namespace voxcd::python
