#include "voxcd/host/api/object.h"

#include <cstring>

#include "voxcd/host/api/access.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"

namespace voxcd {

namespace {

Object build(const Mesh& mesh, const std::string& source, uint64_t hash, const MeshReport& report,
             const ObjectDef& def, const std::string& name) {
  ObjectOptions o;
  o.voxel = def.voxel > 0 ? def.voxel : 0;
  o.resolution = def.voxel > 0 ? 0 : def.resolution;
  o.distance_bits = def.distance_bits;
  o.band = def.band;
  o.threads = def.threads;
  set_storage(o, def.storage);
  return ApiAccess::object_of(
      std::make_shared<const ObjectType>(make_object_type(make_object(mesh, source, hash, o, &report), name)));
}

}  // namespace

Object Object::load(const std::string& file_or_shape, const ObjectDef& def) {
  const std::string name = def.name.empty() ? file_or_shape : def.name;
  if (is_object_file(file_or_shape)) {
    ObjectFile obj = read_object(file_or_shape);
    require_distance_bits(obj, def.distance_bits, name);
    return ApiAccess::object_of(std::make_shared<const ObjectType>(make_object_type(std::move(obj), name)));
  }
  std::string source;
  uint64_t hash = 0;
  MeshReport report;
  const Mesh mesh = load_source(file_or_shape, &source, &hash, &report, LoadOptions{def.strict});
  return build(mesh, source, hash, report, def, name);
}

Object Object::from_mesh(Mesh mesh, const ObjectDef& def) {
  if (!def.name.empty()) mesh.name = def.name;
  if (mesh.name.empty()) mesh.name = "arrays";
  const MeshReport report = def.strict ? prepare(mesh) : repair(mesh);
  std::string bytes;
  for (const auto& v : mesh.vertices) bytes.append(reinterpret_cast<const char*>(v.data()), 3 * sizeof(double));
  for (const auto& t : mesh.triangles) bytes.append(reinterpret_cast<const char*>(t.data()), 3 * sizeof(uint32_t));
  return build(mesh, mesh.name, hash_bytes(bytes), report, def, mesh.name);
}

Object Object::from_arrays(const double* vertices, size_t n_vertices, const uint32_t* triangles, size_t n_triangles,
                           const ObjectDef& def) {
  Mesh m;
  m.name = def.name.empty() ? "arrays" : def.name;
  m.vertices.resize(n_vertices);
  for (size_t i = 0; i < n_vertices; ++i) m.vertices[i] = Eigen::Vector3d(vertices + 3 * i);
  m.triangles.resize(n_triangles);
  for (size_t t = 0; t < n_triangles; ++t) std::memcpy(m.triangles[t].data(), triangles + 3 * t, 3 * sizeof(uint32_t));
  return from_mesh(std::move(m), def);
}

Object Object::from_arrays(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>& vertices,
                           const Eigen::Ref<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>& triangles,
                           const ObjectDef& def) {
  Mesh m;
  m.name = def.name.empty() ? "arrays" : def.name;
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) m.vertices.emplace_back(vertices.row(i).transpose());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    std::array<uint32_t, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, k);
      if (v < 0)
        throw MeshError(m.name + ": triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                        " (negative)");
      tri[size_t(k)] = uint32_t(v);
    }
    m.triangles.push_back(tri);
  }
  return from_mesh(std::move(m), def);
}

const std::string& Object::name() const { return impl_->type->name; }
double Object::voxel() const { return impl_->type->voxmap().voxel(); }
std::array<uint32_t, 3> Object::dims() const { return impl_->type->voxmap().dims(); }
size_t Object::shell_count() const { return impl_->type->object.shell_count(); }

namespace {

// The rows of `v`, one 3-vector each.
Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rows(const std::vector<Eigen::Vector3d>& v) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> m(Eigen::Index(v.size()), 3);
  for (size_t k = 0; k < v.size(); ++k) m.row(Eigen::Index(k)) = v[k].transpose();
  return m;
}

// The dense shell, which an object holds unless its shell is sparse on a grid too large for it.
const PointShell& dense_shell(const ObjectType& t) {
  if (t.object.shell.size() != t.object.shell_count())
    throw Error(t.name + ": the shell is stored sparse on a grid too large for its dense form (" +
                std::to_string(t.object.shell_count()) + " points): it has no array of points");
  return t.object.shell;
}

}  // namespace

Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Object::shell_points() const {
  return rows(dense_shell(*impl_->type).points);
}
Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Object::shell_normals() const {
  return rows(dense_shell(*impl_->type).normals);
}
int Object::distance_bits() const { return impl_->type->object.distance_bits(); }
const MeshReport& Object::report() const { return impl_->type->object.mesh_report; }
void Object::save(const std::string& path) const { write_object(path, impl_->type->object); }

}  // namespace voxcd
