// make_object: a mesh or a built-in shape (load_source) to an object's voxmap and shell, dense or sparse
// (host/object/object_file.h).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "voxcd/host/object/detail/shell_normals.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize_sparse.h"
#include "voxcd/ref/fnv1a.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

uint64_t hash_bytes(const std::string& bytes) { return fnv1a(bytes); }

uint64_t hash_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ObjectFileError(path + ": cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return hash_bytes(bytes);
}

Mesh load_source(const std::string& mesh_or_shape, std::string* source, uint64_t* hash, MeshReport* report,
                 const LoadOptions& opt) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(mesh_or_shape, ec)) {
    Mesh m = load_mesh(mesh_or_shape, report, opt);
    if (source) *source = mesh_or_shape;
    if (hash) *hash = hash_file(mesh_or_shape);
    return m;
  }
  if (is_shape(mesh_or_shape)) {
    if (source) *source = "shape:" + mesh_or_shape;
    if (hash) *hash = hash_bytes("shape:" + mesh_or_shape);
    Mesh m = make_shape(mesh_or_shape);
    if (report) {
      *report = MeshReport{};
      report->input_vertices = report->vertices = m.vertices.size();
      report->input_triangles = report->triangles = m.size();
      report->components = report->closed_components = 1;
      report->closed = true;
    }
    return m;
  }
  std::string known;
  for (const auto& n : shape_names()) known += (known.empty() ? "" : ", ") + n;
  if (std::filesystem::exists(mesh_or_shape, ec))
    throw MeshError(mesh_or_shape + ": not a regular file");
  throw MeshError(mesh_or_shape + ": no such file, and not a built-in shape (" + known + ")");
}

namespace {

// The dense voxmap's device bytes with the default widths (MEMW-bit words of 2-bit states).
uint64_t dense_voxmap_bytes(const GridPlacement& g) {
  const DeviceConfig cfg;
  const uint64_t per = uint64_t(cfg.states_per_word());
  return (g.size() + per - 1) / per * uint64_t(cfg.MEMW) / 8;
}

// The voxmap, sparse; kAuto turns it dense where that is smaller and fits.
void sparse_voxmap_of(const Mesh& mesh, const VoxelizeOptions& vo, ObjectStorage storage, ObjectFile& obj) {
  obj.sparse_voxmap = voxelize_sparse(mesh, vo, &obj.voxelize_report);
  const GridPlacement& g = obj.sparse_voxmap.grid();
  const bool fits = std::max({g.dims[0], g.dims[1], g.dims[2]}) <= kMaxDenseDim;
  if (storage == ObjectStorage::kAuto && fits && dense_voxmap_bytes(g) <= obj.sparse_voxmap.bytes()) {
    obj.voxmap = obj.sparse_voxmap.to_dense();
    obj.sparse_voxmap = SparseVoxmap();
  }
}

// The centre shell, sparse; kAuto turns it dense (point_shell's normals, exactly) where that is smaller and fits.
void sparse_shell_of(const Mesh& mesh, ShellOptions so, ObjectStorage storage, ObjectFile& obj) {
  const uint32_t dense_limit = so.max_dim;
  so.max_dim = kMaxSparseShellDim;
  obj.sparse_shell = sparse_point_shell(mesh, so);
  const GridPlacement& g = obj.sparse_shell.grid;
  const bool fits = std::max({g.dims[0], g.dims[1], g.dims[2]}) <= dense_limit;
  const uint64_t word_bytes = (3 * uint64_t(DeviceConfig{}.PW) + 7) / 8;
  if (storage == ObjectStorage::kAuto && fits && obj.sparse_shell.size() * word_bytes <= obj.sparse_shell.bytes()) {
    obj.shell = detail::centre_shell(mesh, g, obj.sparse_shell.to_point_shell().cells, so.threads);
    obj.sparse_shell = SparseShell();
  }
}

// The distance field in the form `storage` asks for: sparse with refined bricks (docs/objects.md, "Sparse distance
// field"), dense, or (auto) whichever takes fewer words of a device with the default widths and SB = d.bits.
void distance_of(const Mesh& mesh, const DistanceOptions& d, ObjectStorage storage, ObjectFile& obj) {
  if (storage != ObjectStorage::kDense) {
    SparseFieldOptions so;
    so.distance = d;
    obj.sparse_distance = sparse_distance_field(mesh, obj.voxmap.grid(), so);
    if (storage == ObjectStorage::kSparse) {
      obj.voxelize_report.conservative = obj.sparse_distance.counts().conservative;
      return;
    }
  }
  obj.distance = distance_field(mesh, obj.voxmap, d, &obj.voxelize_report.conservative);
  if (storage != ObjectStorage::kAuto) return;
  DeviceConfig cfg;
  cfg.SB = d.bits;
  cfg.BL = SparseDistanceField::kBrickLog;
  const SparseImage img = obj.sparse_distance.device_image(cfg);
  Job j;
  j.nx = obj.voxmap.dims()[0], j.ny = obj.voxmap.dims()[1], j.nz = obj.voxmap.dims()[2];
  if (img.table.size() + img.bricks.size() < map_words(cfg, j)) {
    obj.distance = DistanceField{};
    obj.voxelize_report.conservative = obj.sparse_distance.counts().conservative;
  } else {
    obj.sparse_distance = SparseDistanceField{};
  }
}

}  // namespace

void set_storage(ObjectOptions& opt, ObjectStorage storage) {
  opt.storage = storage;
  opt.max_dim = storage == ObjectStorage::kDense || opt.distance_bits ? kMaxDenseDim : kMaxSparseDim;
}

std::optional<ObjectStorage> parse_storage(const std::string& name) {
  if (name == "auto") return ObjectStorage::kAuto;
  if (name == "dense") return ObjectStorage::kDense;
  if (name == "sparse") return ObjectStorage::kSparse;
  return std::nullopt;
}

ObjectFile make_object(const Mesh& mesh, const std::string& source, uint64_t source_hash, const ObjectOptions& opt,
                       const MeshReport* report) {
  ObjectFile obj;
  if (opt.distance_bits != 0 && !valid_distance_bits(opt.distance_bits))
    throw MeshError(mesh.name + ": distance bits must be " + distance_bits_text() + " (or 0 for none), got " +
                    std::to_string(opt.distance_bits));
  const double voxel = opt.resolution ? voxel_for_resolution(mesh, opt.resolution) : opt.voxel;
  obj.source = source;
  obj.source_hash = source_hash;
  obj.shell_ratio = opt.shell_ratio;
  obj.shift = opt.shift;
  if (report) {
    obj.has_report = true;
    obj.mesh_report = *report;
  }
  VoxelizeOptions vo;
  vo.voxel = voxel;
  vo.shift = opt.shift;
  vo.max_dim = opt.max_dim;
  vo.threads = opt.threads;
  ShellOptions so;
  so.target_voxel = voxel;
  so.ratio = opt.shell_ratio;
  so.shift = opt.shift;
  so.threads = opt.threads;
  if (opt.storage != ObjectStorage::kDense && opt.distance_bits == 0) {
    sparse_voxmap_of(mesh, vo, opt.storage, obj);
    sparse_shell_of(mesh, so, opt.storage, obj);
    return obj;
  }
  obj.voxmap = voxelize(mesh, vo, &obj.voxelize_report);
  if (opt.distance_bits) {
    DistanceOptions d;
    d.bits = opt.distance_bits;
    d.band = opt.band;
    d.threads = opt.threads;
    distance_of(mesh, d, opt.storage, obj);
    so.on_surface = true;
  }
  obj.shell = point_shell(mesh, so);
  return obj;
}

}  // namespace voxcd
