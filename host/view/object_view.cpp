#include "voxcd/host/view/object_view.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxmap_surface.h"
#include "voxcd/host/view/detail/base64.h"

namespace voxcd::view {

namespace {

using nlohmann::json;

std::string floats(const std::vector<Eigen::Vector3d>& v) {
  std::vector<float> f;
  f.reserve(3 * v.size());
  for (const auto& p : v) f.insert(f.end(), {float(p.x()), float(p.y()), float(p.z())});
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

// The places repair changed in the mesh at `path` (a file; not a shape), when it can be read again.
std::optional<RepairPlaces> places_of(const std::string& path, const Mesh& repaired, const MeshReport& report) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  LoadOptions raw;
  raw.repair = false;
  return repair_places(load_mesh(path, nullptr, raw), repaired, report);
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
        v.note = src + " has changed since the object was made: drawing the voxmap's surface";
      } else {
        MeshReport r;
        v.surface = load_mesh(src, &r);
        v.places = places_of(src, v.surface, r);
      }
    } catch (const std::exception& e) {
      v.note = std::string("the mesh cannot be read again (") + e.what() + "): drawing the voxmap's surface";
    }
    v.from_mesh = v.note.empty();
    if (!v.from_mesh) v.surface = voxmap_surface(v.object.voxmap);
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

std::string object_view_json(const ObjectView& v) {
  const ObjectFile& o = v.object;
  const Voxmap& m = o.voxmap;
  const auto counts = m.counts();
  json j = {{"kind", "object"}, {"name", v.name}, {"source", o.source}, {"voxel", m.voxel()},
            {"origin", {m.origin().x(), m.origin().y(), m.origin().z()}},
            {"dims", {m.dims()[0], m.dims()[1], m.dims()[2]}},
            {"counts", {{"empty", counts[kEmpty]}, {"surface", counts[kSurface]}, {"interior", counts[kInterior]}}},
            {"voxmap", detail::base64(m.words())}};
  j["surface"] = mesh_json(v.surface);
  j["surface"]["from_mesh"] = v.from_mesh;
  j["surface"]["note"] = v.note;
  j["shell"] = {{"count", o.shell.size()}, {"on_surface", o.shell.on_surface}, {"points", floats(o.shell.points)},
                {"normals", floats(o.shell.normals)}};
  j["distance"] = nullptr;
  if (!o.distance.empty())
    j["distance"] = {{"bits", o.distance.bits}, {"step", o.distance.step}, {"band", o.distance.band()},
                     {"nodes", {o.distance.dims[0] + 1, o.distance.dims[1] + 1, o.distance.dims[2] + 1}},
                     {"q", detail::base64(o.distance.q)}};
  j["report"] = o.has_report ? report_json(o.mesh_report) : json(nullptr);
  if (o.has_report) j["report"]["uncertain_voxels"] = o.voxelize_report.uncertain;
  j["places"] = v.places ? places_json(*v.places) : json(nullptr);
  return j.dump();
}

}  // namespace voxcd::view
