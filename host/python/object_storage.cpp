// voxcd.Object's storage: which of its voxmap, shell and distance field are sparse, the device memory each takes in
// the form stored and in the other form, and the sparse forms' bricks; the figures `voxcd info` prints
// (host/object/storage_figures.h, docs/python.md).
#include <numeric>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/storage_figures.h"
#include "voxcd/host/python/bindings.h"

namespace voxcd::python {

namespace {

const char* form(bool sparse) { return sparse ? "sparse" : "dense"; }

py::dict storage_dict(const ObjectFile& o) {
  const py::object distance = o.has_distance() ? py::str(form(o.distance_sparse())) : py::object(py::none());
  return py::dict(py::arg("voxmap") = form(o.voxmap_sparse()), py::arg("shell") = form(o.shell_sparse()),
                  py::arg("distance") = distance);
}

// {"stored": bytes of the stored form, "dense": ..., "sparse": ... (None when that form has no figure)}.
py::dict forms(bool sparse, uint64_t dense_bytes, const py::object& sparse_bytes) {
  return py::dict(py::arg("stored") = sparse ? sparse_bytes : py::int_(dense_bytes), py::arg("dense") = dense_bytes,
                  py::arg("sparse") = sparse_bytes);
}

py::object distance_memory_dict(const DistanceFigures& d) {
  if (!d.present) return py::none();
  return forms(d.sparse, d.dense.bytes, d.sparse ? py::object(py::int_(d.stored.bytes)) : py::object(py::none()));
}

py::dict memory_dict(const ObjectFile& o) {
  const StorageFigures f = storage_figures(o);
  const py::object sparse_shell = f.shell_has_sparse ? py::object(py::int_(f.sparse_shell)) : py::object(py::none());
  return py::dict(py::arg("voxmap") = forms(f.voxmap_sparse, f.dense_voxmap, py::int_(f.sparse_voxmap())),
                  py::arg("shell") = forms(f.shell_sparse, f.dense_shell, sparse_shell),
                  py::arg("distance") = distance_memory_dict(distance_figures(o)));
}

py::dict bricks_dict(const ObjectFile& o) {
  const StorageFigures f = storage_figures(o);
  const DistanceFigures d = distance_figures(o);
  py::object levels = py::none(), refined = py::none();
  if (d.sparse) {
    const auto& b = d.counts.bricks;
    levels = py::make_tuple(b[0], b[1], b[2], b[3]);
    refined = py::int_(std::accumulate(b.begin() + 1, b.end(), uint64_t{0}));
  }
  return py::dict(py::arg("voxmap") = f.cells[kCodeBrick],
                  py::arg("shell") = f.shell_has_sparse ? py::object(py::int_(f.shell_bricks)) : py::object(py::none()),
                  py::arg("distance") = levels, py::arg("distance_refined") = refined);
}

}  // namespace

void bind_object_storage(ObjectClass& cls) {
  cls.def_property_readonly("storage", &storage_dict,
                             "How the object is stored: {'voxmap': 'dense' or 'sparse', 'shell': ..., 'distance': "
                             "... (None without a field)}, as `voxcd info --json` gives storage.voxmap, "
                             "storage.shell and distance.storage.")
      .def_property_readonly("memory", &memory_dict,
                             "Device memory in bytes with the default widths, as `voxcd info` reports it: for "
                             "'voxmap', 'shell' and 'distance' (None without a field) a dict of 'stored' (the "
                             "form the object holds), 'dense' and 'sparse' (None where that form has no figure: a "
                             "shell on the surface has no sparse form, a dense field's sparse form needs the mesh).")
      .def_property_readonly("bricks", &bricks_dict,
                             "The sparse forms' bricks, as stored or as they would be: 'voxmap' (cells of 8^3 "
                             "voxels that are not all one state), 'shell' (4^3 shell bricks; None for a shell on "
                             "the surface), 'distance' (a sparse field's bricks at levels 0 to 3) and "
                             "'distance_refined' (those at levels 1 to 3); None for a field stored dense.");
}

}  // namespace voxcd::python
