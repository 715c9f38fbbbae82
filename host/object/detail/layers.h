// Internal to host/object (voxelize_sparse.cpp, sparse_shell_build.cpp): a grid processed in layers of H planes of z,
// so that nothing is allocated per voxel of the whole box. Each layer gets the triangles (or points) that can reach
// it, and walks their surface voxels within it exactly as voxelize's surface (host/object/detail/voxel_geometry.h).
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "voxcd/host/object/detail/voxel_geometry.h"

namespace voxcd::detail {

// The items (triangle, chain item or point indices) of every layer: layer L holds items[start[L], start[L + 1]).
struct LayerLists {
  std::vector<uint64_t> start;
  std::vector<uint32_t> items;
  const uint32_t* begin(size_t layer) const { return items.data() + start[layer]; }
  size_t count(size_t layer) const { return size_t(start[layer + 1] - start[layer]); }
};

// Item i of n goes to every layer of height h that rows(i) (inclusive z rows; first > second: none) reaches, among
// `layers` layers.
LayerLists layer_lists(size_t n, size_t layers, uint32_t h, const std::function<std::pair<int64_t, int64_t>(size_t)>& rows);

// The layers of the surface: for a mesh with triangles, every triangle by the rows its grown voxels can reach; for a
// point cloud, every finite vertex by its grown voxel rows.
LayerLists surface_layers(const Mesh& mesh, const GridMesh& gm, const GridPlacement& gp, uint32_t h);

// Calls fn(item, x, y, z) for every surface voxel of the layer's items whose z lies in the window: each triangle's
// voxels (triangle_voxels), or each point's (point_voxels) for a point cloud. A voxel comes once per item that
// reaches it.
template <class Fn>
void layer_surface(const Mesh& mesh, const GridMesh& gm, const GridPlacement& gp, const uint32_t* items, size_t n,
                   const ZWindow& win, Fn&& fn) {
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = items[k];
    auto at = [&](uint32_t x, uint32_t y, uint32_t z) { fn(i, x, y, z); };
    if (mesh.points_only())
      point_voxels((mesh.vertices[i] - gp.origin) / gp.voxel, gp, at, win);
    else
      triangle_voxels(gm, mesh, i, gp, at, win);
  }
}

}  // namespace voxcd::detail
