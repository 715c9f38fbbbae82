// The voxeliser (voxelize): the grid placed on a mesh, then the surface voxels (voxelize_surface.cpp) over the solid
// fill (voxelize_solid.cpp); the voxmap's words.
#include "voxcd/host/object/voxelize.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/host/object/detail/column_crossings.h"
#include "voxcd/host/object/detail/solid.h"
#include "voxcd/host/object/detail/voxel_geometry.h"
#include "voxcd/host/object/detail/voxelize_stages.h"

namespace voxcd {

using detail::GridMesh;
using detail::to_grid;

Voxmap::Voxmap(const GridPlacement& g) : grid_(g), words_((g.size() + 31) / 32, 0) {}

std::array<uint64_t, 4> Voxmap::counts() const {
  std::array<uint64_t, 4> c = {0, 0, 0, 0};
  constexpr uint64_t kLo = 0x5555555555555555ull;
  for (uint64_t w : words_) {
    const uint64_t lo = w & kLo, hi = (w >> 1) & kLo;
    c[kSurface] += __builtin_popcountll(lo & ~hi);
    c[kInterior] += __builtin_popcountll(hi & ~lo);
    c[kReserved] += __builtin_popcountll(lo & hi);
  }
  c[kEmpty] = size() - c[kSurface] - c[kInterior] - c[kReserved];
  return c;
}

std::vector<uint64_t> Voxmap::device_words(int memw) const {
  if (memw < 2 || memw > 64 || (memw & (memw - 1)))
    throw std::invalid_argument("MEMW must be a power of two in 2..64, got " + std::to_string(memw));
  if (memw == 64) return words_;
  const uint64_t per = uint64_t(memw) / 2;
  std::vector<uint64_t> out((size() + per - 1) / per, 0);
  for (uint64_t i = 0; i < size(); ++i) out[i / per] |= uint64_t(at(i)) << (2 * (i % per));
  return out;
}

double voxel_for_resolution(const Mesh& mesh, uint32_t resolution) {
  if (resolution < kMinVoxelsAcross)
    throw MeshError(mesh.name + ": a resolution of " + std::to_string(resolution) + " voxels is too coarse; at least " +
                    std::to_string(kMinVoxelsAcross) + " voxels must span the longest side");
  if (mesh.triangles.empty() && mesh.vertices.empty()) throw MeshError(mesh.name + ": the mesh has no triangles and no points");
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  const double longest = (hi - lo).maxCoeff();
  if (!std::isfinite(longest)) throw MeshError(mesh.name + ": vertex coordinates are not finite");
  if (!(longest > 0)) throw MeshError(mesh.name + ": the model has no extent (all its points coincide)");
  return longest / resolution;
}

GridPlacement place_grid(const Mesh& mesh, const VoxelizeOptions& opt) {
  if (mesh.triangles.empty() && mesh.vertices.empty())
    throw MeshError(mesh.name + ": the mesh has no triangles and no points");
  const double voxel = opt.resolution ? voxel_for_resolution(mesh, opt.resolution) : opt.voxel;
  if (!(std::isfinite(voxel) && voxel > 0))
    throw MeshError(mesh.name + ": the voxel size must be a positive finite number, got " + std::to_string(voxel));
  for (int a = 0; a < 3; ++a)
    if (!(opt.shift[a] >= 1.0 / 1024 && opt.shift[a] <= 1))
      throw MeshError(mesh.name + ": grid shift components must lie in [1/1024, 1], got " + std::to_string(opt.shift[a]));
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  if (!lo.allFinite() || !hi.allFinite()) throw MeshError(mesh.name + ": vertex coordinates are not finite");
  const double longest = (hi - lo).maxCoeff();
  if (!(longest >= kMinVoxelsAcross * voxel)) {
    std::ostringstream s;
    s.precision(9);
    if (!(longest > 0)) {
      s << mesh.name << ": the model has no extent (all its points coincide)";
    } else {
      s << mesh.name << ": voxel size " << voxel << " leaves " << longest / voxel
        << " voxels along the model's longest side (" << longest << "); at least " << kMinVoxelsAcross
        << " are needed: use a voxel size of at most " << longest / kMinVoxelsAcross << " (or --resolution)";
    }
    throw MeshError(s.str());
  }
  GridPlacement g;
  g.voxel = voxel;
  g.origin = lo - voxel * (Eigen::Vector3d::Ones() + opt.shift);
  bool too_big = false;
  double dd[3];
  for (int a = 0; a < 3; ++a) {
    const double ghi = (hi[a] - g.origin[a]) / voxel;
    dd[a] = std::floor(ghi + 4 * detail::kGrow) + 2;
    if (!(dd[a] <= opt.max_dim)) too_big = true;
  }
  if (too_big) {
    std::ostringstream s;
    s << mesh.name << ": at voxel size " << voxel << " the voxmap would be " << dd[0] << "x" << dd[1] << "x"
      << dd[2] << " voxels; at most " << opt.max_dim << " per axis are allowed (use a voxel size of at least "
      << longest / (opt.max_dim - 4) << ")";
    throw MeshError(s.str());
  }
  for (int a = 0; a < 3; ++a) g.dims[a] = uint32_t(dd[a]);
  return g;
}

Voxmap voxelize(const Mesh& mesh, const VoxelizeOptions& opt, VoxelizeReport* report) {
  const GridPlacement gp = place_grid(mesh, opt);
  Voxmap vm(gp);
  VoxelizeReport rep;
  if (mesh.points_only()) {
    detail::apply_surface(vm, detail::point_bits(mesh, gp));
    if (report) *report = rep;
    return vm;
  }
  const GridMesh gm = to_grid(mesh, gp);
  ThreadPool pool(opt.threads);
  const std::vector<uint64_t> sb = detail::surface_bits_grid(gm, mesh, gp, pool);
  detail::fill_solid(mesh, gm, gp, pool, &sb, vm, rep);
  // 5. Surface voxels override.
  detail::apply_surface(vm, sb);
  if (report) *report = rep;
  return vm;
}

}  // namespace voxcd
