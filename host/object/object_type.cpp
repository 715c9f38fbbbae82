#include "voxcd/host/object/object_type.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "voxcd/host/object/bounds.h"
#include "voxcd/host/mesh/mesh.h"

namespace voxcd {

namespace {

// One line of the squared Euclidean distance transform (Felzenszwalb and Huttenlocher): f holds squared
// distances along the line so far (or `inf`), d receives min_q (f[q] + (p - q)^2).
void edt_line(const double* f, double* d, int n, std::vector<int>& v, std::vector<double>& z) {
  const double inf = std::numeric_limits<double>::infinity();
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == inf) continue;
    while (k >= 0) {
      const double s = ((f[q] + double(q) * q) - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]));
      if (s <= z[k]) {
        --k;
        continue;
      }
      break;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -inf : ((f[q] + double(q) * q) - (f[v[k - 1]] + double(v[k - 1]) * v[k - 1])) /
                               (2.0 * (q - v[k - 1]));
    z[k + 1] = inf;
  }
  if (k < 0) {
    for (int p = 0; p < n; ++p) d[p] = inf;
    return;
  }
  int j = 0;
  for (int p = 0; p < n; ++p) {
    while (z[j + 1] < p) ++j;
    d[p] = double(p - v[j]) * (p - v[j]) + f[v[j]];
  }
}

std::vector<float> surface_depth(const Voxmap& vm) {
  const auto& n = vm.dims();
  const size_t total = vm.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> g(total);
  for (size_t i = 0; i < total; ++i) g[i] = vm.at(i) == kSurface ? 0.0 : inf;
  const int maxn = int(std::max({n[0], n[1], n[2]}));
  std::vector<double> f(maxn), d(maxn), z(maxn + 1);
  std::vector<int> v(maxn);
  const size_t stride[3] = {1, n[0], size_t(n[0]) * n[1]};
  for (int axis = 0; axis < 3; ++axis) {
    const int len = int(n[axis]);
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    for (uint32_t i2 = 0; i2 < n[a2]; ++i2)
      for (uint32_t i1 = 0; i1 < n[a1]; ++i1) {
        const size_t base = i1 * stride[a1] + i2 * stride[a2];
        for (int q = 0; q < len; ++q) f[q] = g[base + q * stride[axis]];
        edt_line(f.data(), d.data(), len, v, z);
        for (int q = 0; q < len; ++q) g[base + q * stride[axis]] = d[q];
      }
  }
  std::vector<float> depth(total, 0.0f);
  for (size_t i = 0; i < total; ++i)
    if (vm.at(i) == kInterior) depth[i] = float(std::sqrt(g[i]));
  return depth;
}

}  // namespace

ObjectType make_object_type(ObjectFile obj, const std::string& name) {
  ObjectType t;
  t.name = name;
  t.object = std::move(obj);
  add_dense_forms(t.object);
  // Pair tests and scenes read the dense forms; a sparse object too large for them says so.
  if (!t.object.has_dense_voxmap() || !t.object.has_dense_shell()) {
    const auto& d = t.object.voxmap_grid().dims;
    throw MeshError(name + ": the object is stored sparse (voxmap " + std::to_string(d[0]) + "x" + std::to_string(d[1]) +
                    "x" + std::to_string(d[2]) + "); collision queries take a dense voxmap of at most " +
                    std::to_string(kMaxDenseDim) + " voxels per axis and a dense shell");
  }
  const Voxmap& vm = t.object.voxmap;
  const auto counts = vm.counts();
  if (counts[kSurface] == 0) throw MeshError(name + ": the voxmap has no surface voxel");
  t.depth = surface_depth(vm);
  // Bounds: corners of non-empty voxels, and shell points.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const auto& n = vm.dims();
  for (uint32_t z = 0; z < n[2]; ++z)
    for (uint32_t y = 0; y < n[1]; ++y)
      for (uint32_t x = 0; x < n[0]; ++x) {
        if (vm.at(x, y, z) == kEmpty) continue;
        const Eigen::Vector3d c = vm.centre(x, y, z);
        lo = lo.cwiseMin(c - Eigen::Vector3d::Constant(0.5 * vm.voxel()));
        hi = hi.cwiseMax(c + Eigen::Vector3d::Constant(0.5 * vm.voxel()));
      }
  for (const auto& p : t.object.shell.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  t.lo = lo;
  t.hi = hi;
  // The smallest sphere around the corners of the surface voxels (interior voxels lie within them) and the shell.
  std::vector<Eigen::Vector3d> pts = t.object.shell.points;
  const double h = 0.5 * vm.voxel();
  for (uint32_t z = 0; z < n[2]; ++z)
    for (uint32_t y = 0; y < n[1]; ++y)
      for (uint32_t x = 0; x < n[0]; ++x) {
        if (vm.at(x, y, z) != kSurface) continue;
        const Eigen::Vector3d c = vm.centre(x, y, z);
        for (int k = 0; k < 8; ++k)
          pts.push_back(c + Eigen::Vector3d(k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? h : -h));
      }
  const Sphere s = min_sphere(pts);
  t.centre = s.centre;
  t.radius = s.radius;
  return t;
}

bool is_object_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  return in.read(magic, 8) && std::memcmp(magic, "VOXCDOBJ", 8) == 0;
}

void require_distance_bits(const ObjectFile& obj, int distance_bits, const std::string& name) {
  if (distance_bits > 0 && obj.distance_bits() != distance_bits)
    throw MeshError(name + ": the object has " +
                    (!obj.has_distance() ? std::string("no distance field")
                                         : "a distance field of " + std::to_string(obj.distance_bits()) + " bits") +
                    "; " + std::to_string(distance_bits) +
                    " bits were asked for (an object voxelised with distance_bits = " + std::to_string(distance_bits) +
                    ")");
}

ObjectType load_object_type(const std::string& file_or_shape, double voxel, int distance_bits, double band,
                            ObjectStorage storage) {
  if (is_object_file(file_or_shape)) {
    ObjectFile obj = read_object(file_or_shape);
    require_distance_bits(obj, distance_bits, file_or_shape);
    return make_object_type(std::move(obj), file_or_shape);
  }
  if (!(std::isfinite(voxel) && voxel > 0))
    throw MeshError(file_or_shape + ": a mesh or shape needs a positive voxel size (--voxel) to be voxelised");
  std::string source;
  uint64_t hash = 0;
  const Mesh mesh = load_source(file_or_shape, &source, &hash);
  ObjectOptions opt;
  opt.voxel = voxel;
  opt.distance_bits = distance_bits;
  opt.band = band;
  set_storage(opt, storage);
  ObjectType t = make_object_type(make_object(mesh, source, hash, opt), file_or_shape);
  t.mesh = std::make_shared<const Mesh>(mesh);
  return t;
}

double shared_voxel(const std::vector<std::string>& sources, uint32_t resolution) {
  if (resolution < kMinVoxelsAcross)
    throw MeshError("a resolution of " + std::to_string(resolution) + " voxels is too coarse; at least " +
                    std::to_string(kMinVoxelsAcross) + " voxels must span the longest side");
  double side = 0;
  for (const std::string& s : sources) {
    if (is_object_file(s)) continue;
    const Mesh m = load_source(s);
    Eigen::Vector3d lo, hi;
    m.bounds(lo, hi);
    side = std::max(side, (hi - lo).maxCoeff());
  }
  return side / resolution;
}

}  // namespace voxcd
