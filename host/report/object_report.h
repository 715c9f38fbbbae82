// Shared by `voxcd voxelize`, `voxcd info` and the Python module (an object's `repair`): the description of an object
// file (text or JSON) and its picture.
#pragma once

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

#include "voxcd/host/report/json_text.h"
#include "voxcd/host/report/storage_report.h"

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/png.h"
#include "voxcd/ref/config.h"

namespace voxcd::report {

inline std::string hex64(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

// What loading and repair did, as JSON (null for a version 1 object file, which has no report).
inline Json repair_json(const ObjectFile& obj) {
  if (!obj.has_report) return nullptr;
  const MeshReport& r = obj.mesh_report;
  const VoxelizeReport& v = obj.voxelize_report;
  return Json{{"closed", r.closed}, {"surface_only", r.surface_only}, {"points_only", r.points_only},
              {"flipped", r.flipped}, {"input_vertices", r.input_vertices}, {"input_triangles", r.input_triangles},
              {"vertices", r.vertices}, {"triangles", r.triangles}, {"welded", r.welded},
              {"welded_near", r.welded_near}, {"weld_tolerance", r.weld_tolerance},
              {"dropped", {{"nonfinite", r.dropped_nonfinite}, {"repeated_vertex", r.dropped_repeated},
                           {"collinear", r.dropped_collinear}, {"duplicate", r.dropped_duplicate},
                           {"internal", r.dropped_internal}}},
              {"reoriented", r.reoriented}, {"open_edges", r.open_edges}, {"nonmanifold_edges", r.nonmanifold_edges},
              {"nonmanifold_parts", r.nonmanifold_parts}, {"fin_triangles", r.fin_triangles},
              {"inconsistent_edges", r.inconsistent_edges}, {"components", r.components},
              {"closed_components", r.closed_components}, {"sheet_components", r.sheet_components},
              {"uncertain_voxels", v.uncertain}, {"evaluated_voxels", v.evaluated}, {"conservative_cells", v.conservative}};
}

// The same as lines of text: what was found, what was done, how certain the result is.
inline std::string repair_text(const ObjectFile& obj) {
  if (!obj.has_report) return "  repair   not recorded (object file version 1)\n";
  const MeshReport& r = obj.mesh_report;
  std::ostringstream t;
  t << "  input    " << r.input_triangles << " triangles, " << r.input_vertices << " vertices; ";
  if (r.points_only)
    t << "a point cloud (no triangles): surface only, no interior\n";
  else if (r.closed)
    t << "closed, manifold and consistently oriented" << (r.flipped ? " (inside out: reversed)" : "") << "\n";
  else
    t << "not closed: " << r.open_edges << " open edges, " << r.nonmanifold_edges << " non-manifold edges, "
      << r.inconsistent_edges << " inconsistently oriented edges after repair\n";
  t << "  repair   welded " << r.welded << " vertices (" << r.welded_near << " within " << r.weld_tolerance
    << ", the rest exactly equal); dropped " << r.dropped_nonfinite << " non-finite, " << r.dropped_repeated
    << " with a repeated vertex, " << r.dropped_collinear << " collinear, " << r.dropped_duplicate
    << " duplicate triangles; reoriented " << r.reoriented << " triangles" << (r.flipped ? "; reversed the whole mesh" : "")
    << "\n";
  if (r.nonmanifold_parts)
    t << "  nonmanifold " << r.nonmanifold_edges << " edges of three triangles or more in " << r.nonmanifold_parts
      << " parts, decided by the cells they bound: dropped " << r.dropped_internal
      << " internal triangles (solid on both sides), kept " << r.fin_triangles << " fin triangles as sheets\n";
  if (!r.points_only)
    t << "  parts    " << r.components << " components, " << r.closed_components << " closed, " << r.sheet_components
      << " sheets (surface only)" << (r.surface_only ? "; nothing encloses a volume: no interior" : "") << "\n";
  t << "  solid    " << obj.voxelize_report.uncertain << " uncertain voxels (winding number in [" << kUncertainLow << ", "
    << kUncertainHigh << "]), " << obj.voxelize_report.evaluated << " evaluated one by one\n";
  if (!obj.distance.empty())
    t << "  distance " << obj.voxelize_report.conservative
      << " conservative cells (a surface the nodes do not resolve: every point in them is a hit)\n";
  if (obj.distance_sparse())
    t << "  distance " << obj.voxelize_report.conservative
      << " conservative sub-cells (a surface even level-3 bricks do not resolve: every point in them is a hit)\n";
  return t.str();
}

// A sparse field's keys: its cells per kind, its bricks per level, the conservative sub-cells left, and its device
// memory beside a dense map's.
inline Json sparse_distance_json(const ObjectFile& obj) {
  const SparseDistanceField& f = obj.sparse_distance;
  const SparseFieldCounts c = f.counts();
  const DistanceMemory dm = sparse_distance_memory(obj);
  const DistanceMemory dense = dense_distance_memory(f.bits(), f.dims());
  const auto [lo, hi] = std::minmax_element(f.nodes().begin(), f.nodes().end());
  return Json{{"storage", "sparse"}, {"bits", f.bits()}, {"step", f.step()}, {"band", f.band()},
              {"nodes", dm.nodes}, {"cells", {f.cells()[0], f.cells()[1], f.cells()[2]}},
              {"far_cells", c.far}, {"deep_cells", c.deep}, {"bricks_per_level", c.bricks},
              {"conservative_subcells", c.conservative},
              {"min", f.nodes().empty() ? f.qmax() : *lo}, {"max", f.nodes().empty() ? f.qmax() : *hi},
              {"memory_words", dm.words}, {"memory_bytes", dm.bytes}, {"memory_config", dm.cfg.to_string()},
              {"dense_memory_words", dense.words}, {"dense_memory_bytes", dense.bytes}};
}

// The distance field's keys of object_json (objects of file version 3): null when the object has none.
inline Json distance_json(const ObjectFile& obj) {
  if (obj.distance_sparse()) return sparse_distance_json(obj);
  if (obj.distance.empty()) return nullptr;
  const DistanceField& f = obj.distance;
  const DistanceMemory dm = distance_memory(obj);
  return Json{{"storage", "dense"}, {"bits", f.bits}, {"step", f.step}, {"band", f.band()}, {"nodes", dm.nodes},
              {"node_dims", {f.dims[0] + 1, f.dims[1] + 1, f.dims[2] + 1}},
              {"min", *std::min_element(f.q.begin(), f.q.end())}, {"max", *std::max_element(f.q.begin(), f.q.end())},
              {"memory_words", dm.words}, {"memory_bytes", dm.bytes}, {"memory_config", dm.cfg.to_string()}};
}

// The object's description as JSON, one key a line (docs/objects.md lists the keys).
inline std::string object_json(const std::string& path, const ObjectFile& obj) {
  const GridPlacement& g = obj.voxmap_grid();
  const auto counts = obj.voxmap_counts();
  const ObjectMemory mem = object_memory(obj);
  const GridPlacement& sg = obj.shell_grid();
  const auto& sd = sg.dims;
  Json j = {{"file", path}, {"source", obj.source}, {"source_hash", hex64(obj.source_hash)},
            {"dims", {g.dims[0], g.dims[1], g.dims[2]}}, {"voxel_size", g.voxel},
            {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}}, {"voxels", g.size()},
            {"empty", counts[kEmpty]}, {"surface", counts[kSurface]}, {"interior", counts[kInterior]},
            // shell_points: shell_count's deprecated spelling, kept for one release (docs/objects.md).
            {"shell_count", obj.shell_count()}, {"shell_points", obj.shell_count()},
            {"shell_spacing", sg.voxel},
            {"shell_ratio", obj.shell_ratio}, {"shell_dims", {sd[0], sd[1], sd[2]}},
            {"voxmap_bytes", mem.voxmap_bytes}, {"shell_bytes", mem.shell_bytes},
            {"memory_bytes", mem.voxmap_bytes + mem.shell_bytes}, {"memory_config", DeviceConfig{}.to_string()},
            {"storage", storage_json(storage_figures(obj))}, {"repair", repair_json(obj)}};
  // Objects with a distance field (file version 3) have two more keys; the others print exactly as before.
  if (obj.has_distance() || obj.shell.on_surface) {
    j["shell_on_surface"] = obj.shell.on_surface;
    j["distance"] = distance_json(obj);
  }
  return json_text(j, true) + "\n";
}

// A sparse field's line: its values, cells, bricks per level, and device memory beside a dense field's.
inline std::string sparse_distance_text(const ObjectFile& obj) {
  const SparseDistanceField& f = obj.sparse_distance;
  const SparseFieldCounts c = f.counts();
  const DistanceMemory dm = sparse_distance_memory(obj);
  std::ostringstream t;
  t << "  distance " << f.bits() << "-bit node values, step " << f.step() << " voxels, band +-" << f.band()
    << " voxels, stored sparse: " << f.cells()[0] << " x " << f.cells()[1] << " x " << f.cells()[2] << " cells of 8^3, "
    << c.far << " far outside, " << c.deep << " far inside, bricks of level 0/1/2/3: " << c.bricks[0] << "/"
    << c.bricks[1] << "/" << c.bricks[2] << "/" << c.bricks[3] << " (" << c.nodes << " nodes); device memory "
    << dm.words << " words (" << dm.bytes << " bytes, " << dm.cfg.to_string().substr(dm.cfg.to_string().find("SB"))
    << "), dense " << dense_distance_memory(f.bits(), f.dims()).words << " words\n";
  return t.str();
}

inline std::string object_text(const std::string& path, const ObjectFile& obj) {
  const GridPlacement& g = obj.voxmap_grid();
  const auto c = obj.voxmap_counts();
  const auto& d = g.dims;
  const GridPlacement& sg = obj.shell_grid();
  const auto& sd = sg.dims;
  const ObjectMemory mem = object_memory(obj);
  const DeviceConfig cfg;
  std::ostringstream t;
  t.precision(9);
  t << path << ": object of " << obj.source << " (source hash " << hex64(obj.source_hash) << ")\n"
    << "  voxmap   " << d[0] << " x " << d[1] << " x " << d[2] << " voxels of size " << g.voxel << ", origin ("
    << g.origin.x() << ", " << g.origin.y() << ", " << g.origin.z() << ")\n"
    << "  states   empty " << c[kEmpty] << ", surface " << c[kSurface] << ", interior " << c[kInterior] << "\n"
    << "  shell    " << obj.shell_count() << (obj.shell.on_surface ? " points on the surface" : " points")
    << " at spacing " << sg.voxel << " (voxel / " << obj.shell_ratio << "), grid " << sd[0] << " x "
    << sd[1] << " x " << sd[2] << "\n"
    << "  memory   voxmap " << mem.voxmap_bytes << " bytes (" << (obj.voxmap_sparse() ? "sparse, " : "") << "MEMW "
    << cfg.MEMW << "), shell " << mem.shell_bytes << " bytes (3 x PW " << cfg.PW << " bits per "
    << (obj.shell_sparse() ? "shell word, sparse" : "point") << "), total " << mem.voxmap_bytes + mem.shell_bytes
    << " bytes\n"
    << storage_text(storage_figures(obj));
  if (!obj.distance.empty()) {
    const DistanceField& f = obj.distance;
    const DistanceMemory dm = distance_memory(obj);
    t << "  distance " << f.bits << "-bit node values, step " << f.step << " voxels, band +-" << f.band()
      << " voxels, " << f.dims[0] + 1 << " x " << f.dims[1] + 1 << " x " << f.dims[2] + 1 << " nodes; device memory "
      << dm.words << " words (" << dm.bytes << " bytes, MEMW " << dm.cfg.MEMW << ", SB " << dm.cfg.SB << ")\n";
  }
  if (obj.distance_sparse()) t << sparse_distance_text(obj);
  t << repair_text(obj);
  return t.str();
}

// The picture of `obj` (voxmap slices, shell over the mesh when there is one) written to png_path, from the dense
// forms (made of a sparse object's when they fit: MeshError naming the object when they do not).
inline void write_object_picture(const std::string& png_path, const ObjectFile& obj, const Mesh* mesh) {
  if (obj.has_dense_voxmap() && obj.has_dense_shell() && obj.shell.size() == obj.shell_count()) {
    write_png(png_path, object_picture(obj.voxmap, obj.shell, mesh));
    return;
  }
  ObjectFile dense = obj;
  add_dense_forms(dense);
  const auto& d = dense.voxmap_grid().dims;
  if (!dense.has_dense_voxmap() || dense.shell.size() != dense.shell_count())
    throw MeshError(png_path + ": no picture of an object stored sparse at " + std::to_string(d[0]) + " x " +
                    std::to_string(d[1]) + " x " + std::to_string(d[2]) + " voxels (pictures draw the dense voxmap, "
                    "at most " + std::to_string(kMaxDenseDim) + " per axis)");
  write_png(png_path, object_picture(dense.voxmap, dense.shell, mesh));
}

}  // namespace voxcd::report
