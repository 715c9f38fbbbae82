// The ray-parity voxeliser (voxelize_raycast): crossings of every triangle with the voxel columns' rays, and the
// parity fill between them; for closed meshes only.
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

namespace {

using detail::GridMesh;
using detail::to_grid;

struct Crossing {
  uint32_t col;  // y + ny * z
  double x;      // along the ray, in voxels
};

// Every crossing of triangle t with the rays along x through the voxel-column centres.
void triangle_crossings(const GridMesh& gm, const Mesh& m, size_t t, const GridPlacement& gp,
                        std::vector<Crossing>& out) {
  detail::crossings_of(gm.q[m.triangles[t][0]], gm.q[m.triangles[t][1]], gm.q[m.triangles[t][2]], gp,
                       [&](uint32_t y, uint32_t z, double x, bool) {
                         out.push_back({uint32_t(y + uint64_t(gp.dims[1]) * z), x});
                       });
}

}  // namespace

Voxmap voxelize_raycast(const Mesh& mesh, const VoxelizeOptions& opt) {
  const GridPlacement gp = place_grid(mesh, opt);
  const GridMesh gm = to_grid(mesh, gp);
  ThreadPool pool(opt.threads);
  Voxmap vm(gp);

  // 1. Crossings of every triangle with every column ray, gathered per chunk, then bucketed by column.
  const auto parts = detail::chunks(mesh.size(), pool.size());
  std::vector<std::vector<Crossing>> found(parts.size());
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t t = parts[p].first; t < parts[p].second; ++t) triangle_crossings(gm, mesh, t, gp, found[p]);
  });
  const size_t cols = size_t(gp.dims[1]) * gp.dims[2];
  std::vector<uint32_t> start(cols + 1, 0);
  for (const auto& f : found)
    for (const Crossing& c : f) ++start[c.col + 1];
  for (size_t c = 0; c < cols; ++c) start[c + 1] += start[c];
  std::vector<double> xs(start[cols]);
  {
    std::vector<uint32_t> at(start.begin(), start.end() - 1);
    for (const auto& f : found)
      for (const Crossing& c : f) xs[at[c.col]++] = c.x;
  }
  found.clear();
  found.shrink_to_fit();

  // 2. Parity fill: a voxel whose centre has an odd number of crossings before it is inside.
  const uint64_t nx = gp.dims[0];
  for (size_t c = 0; c < cols; ++c) {
    double* b = xs.data() + start[c];
    double* e = xs.data() + start[c + 1];
    if (b == e) continue;
    std::sort(b, e);
    if ((e - b) % 2)
      throw MeshError(mesh.name + ": the ray through column (y " + std::to_string(c % gp.dims[1]) + ", z " +
                      std::to_string(c / gp.dims[1]) + ") crosses the surface an odd number of times");
    for (double* p = b; p < e; p += 2) {
      const double lo_i = std::max(0.0, std::floor(p[0] - 0.5) + 1);
      const double hi_i = std::min(double(nx) - 1, std::ceil(p[1] - 0.5) - 1);
      if (lo_i > hi_i) continue;
      const uint64_t base = uint64_t(c) * nx;
      detail::fill_interior(vm.words(), base + uint64_t(lo_i), base + uint64_t(hi_i) + 1);
    }
  }
  xs.clear();
  xs.shrink_to_fit();

  // 3. Surface voxels override.
  detail::apply_surface(vm, detail::surface_bits_grid(gm, mesh, gp, pool));
  return vm;
}

}  // namespace voxcd
