#include "voxcd/host/view/object_view.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxmap_surface.h"
#include "voxcd/host/detail/base64.h"
#include "voxcd/host/view/detail/sparse_view.h"

namespace voxcd::view {

namespace {

using nlohmann::json;

// Every `stride`-th vector as floats, base64.
std::string floats(const std::vector<Eigen::Vector3d>& v, size_t stride = 1) {
  std::vector<float> f;
  f.reserve(3 * ((v.size() + stride - 1) / stride));
  for (size_t k = 0; k < v.size(); k += stride) f.insert(f.end(), {float(v[k].x()), float(v[k].y()), float(v[k].z())});
  return detail::base64(f);
}

json mesh_json(const Mesh& m) {
  std::vector<uint32_t> idx;
  idx.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles) idx.insert(idx.end(), t.begin(), t.end());
  return {{"vertices", floats(m.vertices)}, {"triangles", detail::base64(idx)}, {"triangle_count", m.triangles.size()}};
}

json report_json(const MeshReport& r) {
  return {{"input_vertices", r.input_vertices}, {"input_triangles", r.input_triangles}, {"vertices", r.vertices},
          {"triangles", r.triangles}, {"welded", r.welded}, {"welded_near", r.welded_near},
          {"weld_tolerance", r.weld_tolerance}, {"flipped", r.flipped}, {"dropped_nonfinite", r.dropped_nonfinite},
          {"dropped_repeated", r.dropped_repeated}, {"dropped_collinear", r.dropped_collinear},
          {"dropped_duplicate", r.dropped_duplicate}, {"reoriented", r.reoriented}, {"open_edges", r.open_edges},
          {"nonmanifold_edges", r.nonmanifold_edges}, {"inconsistent_edges", r.inconsistent_edges},
          {"components", r.components}, {"closed_components", r.closed_components},
          {"sheet_components", r.sheet_components}, {"closed", r.closed}, {"points_only", r.points_only},
          {"surface_only", r.surface_only}, {"repaired", r.repaired()}};
}

json places_json(const RepairPlaces& p) {
  auto edges = [](const std::vector<std::array<Eigen::Vector3d, 2>>& e) {
    std::vector<Eigen::Vector3d> flat;
    for (const auto& s : e) flat.insert(flat.end(), s.begin(), s.end());
    return floats(flat);
  };
  return {{"dropped", floats(p.dropped)}, {"moved", floats(p.moved)}, {"reoriented", floats(p.reoriented)},
          {"open_edges", edges(p.open_edges)}, {"nonmanifold_edges", edges(p.nonmanifold_edges)},
          {"sheet_triangles", detail::base64(p.sheet_triangles)}};
}

// The voxmap's surface, drawn when the mesh is not at hand (`note` says why, and gets what is drawn instead); none
// for a voxmap held sparse alone, too large for its dense form.
Mesh surface_of(const ObjectFile& o, std::string& note) {
  if (o.has_dense_voxmap()) {
    note += ": drawing the voxmap's surface";
    return voxmap_surface(o.voxmap);
  }
  note += ": the voxmap is stored sparse and too large for its surface, drawing its bricks";
  return Mesh{};
}

// The places repair changed in the mesh at `path` (a file; not a shape), when it can be read again.
std::optional<RepairPlaces> places_of(const std::string& path, const Mesh& repaired, const MeshReport& report) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  LoadOptions raw;
  raw.repair = false;
  return repair_places(load_mesh(path, nullptr, raw), repaired, report);
}

// The voxmap's states as the page reads them (the dense form's 64-bit words), when that form is held and within
// `max_bytes`; else null, and a note saying why.
json states_json(const ObjectFile& o, uint64_t max_bytes, json& notes) {
  if (!o.has_dense_voxmap()) {
    notes.push_back("the voxmap is stored sparse on a grid larger than a dense voxmap takes (" +
                    std::to_string(kMaxDenseDim) + " voxels per axis): no voxels or state slices, its bricks drawn");
    return nullptr;
  }
  const uint64_t bytes = 8 * uint64_t(o.voxmap.words().size());
  if (bytes <= max_bytes) return detail::base64(o.voxmap.words());
  notes.push_back("the voxmap's states take " + std::to_string(bytes) + " bytes, more than the page is sent (" +
                  std::to_string(max_bytes) + "): no voxels or state slices");
  return nullptr;
}

// The shell's points and normals, every k-th beyond `limit` points; none when the dense shell is not held.
json shell_json(const ObjectFile& o, size_t limit, json& notes) {
  const PointShell& sh = o.shell;
  const size_t stride = sh.size() <= limit ? 1 : (sh.size() + limit - 1) / limit;
  if (sh.size() < o.shell_count())
    notes.push_back("the shell is stored sparse on a grid too large for its dense form: no shell points");
  else if (stride > 1)
    notes.push_back("one shell point in " + std::to_string(stride) + " is drawn (at most " + std::to_string(limit) +
                    " are sent)");
  return {{"count", o.shell_count()}, {"sent", (sh.size() + stride - 1) / stride}, {"stride", stride},
          {"on_surface", sh.on_surface}, {"points", floats(sh.points, stride)},
          {"normals", floats(sh.normals, stride)}};
}

// The field's values for the slices: the dense field's nodes, or a sparse field's level-0 nodes (dense_from_sparse),
// within `max_bytes` (else "q" null, and a note saying why); null without a field.
json distance_json(const ObjectFile& o, uint64_t max_bytes, json& notes) {
  if (!o.has_distance()) return nullptr;
  const auto& d = o.distance_sparse() ? o.sparse_distance.dims() : o.distance.dims;
  const uint64_t nodes = (uint64_t(d[0]) + 1) * (uint64_t(d[1]) + 1) * (uint64_t(d[2]) + 1);
  json j = {{"storage", o.distance_sparse() ? "sparse" : "dense"}, {"bits", o.distance_bits()},
            {"step", o.distance_step()}, {"band", o.distance_band()}, {"nodes", {d[0] + 1, d[1] + 1, d[2] + 1}},
            {"q", nullptr}};
  if (2 * nodes > max_bytes)
    notes.push_back("the distance field's " + std::to_string(nodes) + " nodes take more bytes than the page is sent (" +
                    std::to_string(max_bytes) + "): no distance slices");
  else if (o.distance_sparse())
    j["q"] = detail::base64(dense_from_sparse(o.sparse_distance).q);
  else
    j["q"] = detail::base64(o.distance.q);
  return j;
}

}  // namespace

ObjectView make_object_view(const std::string& file_or_shape, double voxel, uint32_t resolution, int distance_bits,
                            double band) {
  ObjectView v;
  v.name = file_or_shape;
  if (is_object_file(file_or_shape)) {
    v.object = read_object(file_or_shape);
    const std::string& src = v.object.source;
    try {
      if (src.rfind("shape:", 0) == 0) {
        v.surface = make_shape(src.substr(6));
      } else if (hash_file(src) != v.object.source_hash) {
        v.note = src + " has changed since the object was made";
      } else {
        MeshReport r;
        v.surface = load_mesh(src, &r);
        v.places = places_of(src, v.surface, r);
      }
    } catch (const std::exception& e) {
      v.note = std::string("the mesh cannot be read again (") + e.what() + ")";
    }
    v.from_mesh = v.note.empty();
    if (!v.from_mesh) v.surface = surface_of(v.object, v.note);
    return v;
  }
  std::string source;
  uint64_t hash = 0;
  MeshReport report;
  v.surface = load_source(file_or_shape, &source, &hash, &report);
  ObjectOptions opt;
  opt.voxel = voxel;
  opt.resolution = voxel > 0 ? 0 : resolution;
  opt.distance_bits = distance_bits;
  opt.band = band;
  v.object = make_object(v.surface, source, hash, opt, &report);
  v.from_mesh = true;
  if (source.rfind("shape:", 0) != 0) v.places = places_of(file_or_shape, v.surface, report);
  if (v.surface.triangles.empty()) {
    v.surface = voxmap_surface(v.object.voxmap);
    v.from_mesh = false;
    v.note = "a point cloud: drawing the voxmap's surface";
  }
  return v;
}

std::string object_view_json(const ObjectView& v, const ViewLimits& limits) {
  const ObjectFile& o = v.object;
  const GridPlacement& g = o.voxmap_grid();
  const auto counts = o.voxmap_counts();
  json notes = json::array();
  json j = {{"kind", "object"}, {"name", v.name}, {"source", o.source}, {"voxel", g.voxel},
            {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}}, {"dims", {g.dims[0], g.dims[1], g.dims[2]}},
            {"counts", {{"empty", counts[kEmpty]}, {"surface", counts[kSurface]}, {"interior", counts[kInterior]}}}};
  j["voxmap"] = states_json(o, limits.array_bytes, notes);
  j["surface"] = mesh_json(v.surface);
  j["surface"]["from_mesh"] = v.from_mesh;
  j["surface"]["note"] = v.note;
  j["shell"] = shell_json(o, limits.shell_points, notes);
  j["distance"] = distance_json(o, limits.array_bytes, notes);
  j["storage"] = detail::storage_view_json(o);
  j["bricks"] = detail::bricks_view_json(o, limits.boxes, notes);
  j["limits"] = {{"boxes", limits.boxes}, {"shell_points", limits.shell_points}, {"array_bytes", limits.array_bytes}};
  j["report"] = o.has_report ? report_json(o.mesh_report) : json(nullptr);
  if (o.has_report) j["report"]["uncertain_voxels"] = o.voxelize_report.uncertain;
  j["places"] = v.places ? places_json(*v.places) : json(nullptr);
  j["notes"] = notes;
  return j.dump();
}

}  // namespace voxcd::view
