#include "voxcd/host/object/detail/layers.h"

namespace voxcd::detail {

LayerLists layer_lists(size_t n, size_t layers, uint32_t h,
                       const std::function<std::pair<int64_t, int64_t>(size_t)>& rows) {
  LayerLists l;
  l.start.assign(layers + 1, 0);
  // Two passes (count, then place), so the lists take one array.
  auto span = [&](size_t i, int64_t& l0, int64_t& l1) {
    const auto r = rows(i);
    l0 = std::max<int64_t>(0, r.first) / h;
    l1 = std::min<int64_t>(r.second, int64_t(layers) * h - 1) / h;
    return r.first <= r.second && l0 <= l1;
  };
  int64_t l0, l1;
  for (size_t i = 0; i < n; ++i)
    if (span(i, l0, l1))
      for (int64_t k = l0; k <= l1; ++k) ++l.start[size_t(k) + 1];
  for (size_t k = 0; k < layers; ++k) l.start[k + 1] += l.start[k];
  l.items.resize(l.start[layers]);
  std::vector<uint64_t> at(l.start.begin(), l.start.end() - 1);
  for (size_t i = 0; i < n; ++i)
    if (span(i, l0, l1))
      for (int64_t k = l0; k <= l1; ++k) l.items[at[size_t(k)]++] = uint32_t(i);
  return l;
}

LayerLists surface_layers(const Mesh& mesh, const GridMesh& gm, const GridPlacement& gp, uint32_t h) {
  const size_t layers = (gp.dims[2] + h - 1) / h;
  if (mesh.points_only())
    return layer_lists(mesh.vertices.size(), layers, h, [&](size_t i) -> std::pair<int64_t, int64_t> {
      const Eigen::Vector3d& p = mesh.vertices[i];
      if (!p.allFinite()) return {1, 0};
      const double z = (p[2] - gp.origin[2]) / gp.voxel;
      return {std::max<int64_t>(0, int64_t(std::floor(z - kGrow))),
              std::min<int64_t>(int64_t(gp.dims[2]) - 1, int64_t(std::floor(z + kGrow)))};
    });
  return layer_lists(mesh.size(), layers, h, [&](size_t t) {
    const auto& tri = mesh.triangles[t];
    const double zlo = std::min({gm.g[tri[0]][2], gm.g[tri[1]][2], gm.g[tri[2]][2]});
    const double zhi = std::max({gm.g[tri[0]][2], gm.g[tri[1]][2], gm.g[tri[2]][2]});
    return voxel_rows(zlo, zhi, gp.dims[2]);
  });
}

}  // namespace voxcd::detail
