// sparse_point_shell(): the centre shell built layer by layer into shell bricks (host/object/sparse_shell.h).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "voxcd/host/object/detail/layers.h"
#include "voxcd/host/object/detail/octahedral.h"
#include "voxcd/host/object/detail/shell_chain.h"
#include "voxcd/host/object/detail/shell_grid.h"
#include "voxcd/host/object/detail/shell_normals.h"
#include "voxcd/host/object/sparse_shell.h"
#include "voxcd/ref/fast/thread_pool.h"

namespace voxcd {

namespace {

// Layers of two brick planes.
constexpr uint32_t kLayer = 2 * kShellBrickEdge;

// A layer's bricks sorted by z, y, x, their masks, and their points' normals (bricks in order, bits ascending;
// empty for a point cloud, whose normals need every point).
struct ShellLayer {
  std::vector<detail::BrickPos> bricks;
  std::vector<uint64_t> masks;
  std::vector<uint32_t> normals;
};

// The bricks of one layer being filled: a slot per brick reached, found through an index over the layer's brick
// positions that each thread keeps from layer to layer (reset entry by entry), so no layer clears a whole array.
class LayerBricks {
 public:
  LayerBricks(uint64_t bx, uint64_t by, bool nearest) : bx_(bx), by_(by), nearest_(nearest) {
    thread_local std::vector<uint32_t> index;
    if (index.size() < bx * by * (kLayer / kShellBrickEdge)) index.assign(bx * by * (kLayer / kShellBrickEdge), UINT32_MAX);
    index_ = &index;
  }
  ~LayerBricks() {
    for (uint64_t k : keys_) (*index_)[k] = UINT32_MAX;
  }
  LayerBricks(const LayerBricks&) = delete;
  LayerBricks& operator=(const LayerBricks&) = delete;
  // Sets voxel (x, y, z - z0) and keeps triangle t's distance when it is the nearest yet.
  void add(uint32_t x, uint32_t y, uint32_t zl, const detail::Nearest& here) {
    const uint64_t k = x / kShellBrickEdge + bx_ * (y / kShellBrickEdge + by_ * (zl / kShellBrickEdge));
    uint32_t& s = (*index_)[k];
    if (s == UINT32_MAX) {
      s = uint32_t(keys_.size());
      keys_.push_back(k);
      masks_.push_back(0);
      if (nearest_) near_.resize(near_.size() + 64);
    }
    const uint32_t bit = (x & 3) | (y & 3) << 2 | (zl & 3) << 4;
    masks_[s] |= uint64_t{1} << bit;
    if (nearest_ && here.better_than(near_[s * 64 + bit])) near_[s * 64 + bit] = here;
  }
  // The layer's bricks in z, y, x order, with normals from the nearest triangles.
  ShellLayer finish(const Mesh& mesh, uint32_t z0) const;

 private:
  uint64_t bx_, by_;
  bool nearest_;
  std::vector<uint32_t>* index_;
  std::vector<uint64_t> keys_, masks_;
  std::vector<detail::Nearest> near_;
};

ShellLayer LayerBricks::finish(const Mesh& mesh, uint32_t z0) const {
  std::vector<uint32_t> by_key(keys_.size());
  for (uint32_t s = 0; s < by_key.size(); ++s) by_key[s] = s;
  std::sort(by_key.begin(), by_key.end(), [&](uint32_t a, uint32_t b) { return keys_[a] < keys_[b]; });
  ShellLayer out;
  out.bricks.reserve(keys_.size());
  out.masks.reserve(keys_.size());
  if (nearest_) {
    uint64_t points = 0;
    for (uint64_t m : masks_) points += uint64_t(__builtin_popcountll(m));
    out.normals.reserve(points);  // exactly: every point of every layer is kept until the chains are known
  }
  for (uint32_t s : by_key) {
    const uint64_t k = keys_[s];
    out.bricks.push_back({uint16_t(k % bx_), uint16_t(k / bx_ % by_), uint16_t(k / (bx_ * by_) + z0 / kShellBrickEdge)});
    out.masks.push_back(masks_[s]);
    if (!nearest_) continue;
    for (uint64_t m = masks_[s]; m; m &= m - 1) {
      const detail::Nearest& n = near_[s * 64 + uint64_t(__builtin_ctzll(m))];
      if (n.tri == UINT32_MAX) throw std::logic_error("sparse_point_shell: shell point without a triangle");
      out.normals.push_back(detail::encode_normal(detail::triangle_normal(mesh, n.tri)));
    }
  }
  return out;
}

ShellLayer shell_layer(const Mesh& mesh, const detail::GridMesh& gm, const GridPlacement& g,
                       const detail::LayerLists& items, size_t layer) {
  const uint32_t z0 = uint32_t(layer * kLayer), z1 = std::min(g.dims[2], z0 + kLayer);
  LayerBricks lb((g.dims[0] + 3) / 4, (g.dims[1] + 3) / 4, !mesh.points_only());
  detail::layer_surface(mesh, gm, g, items.begin(layer), items.count(layer), detail::ZWindow{z0, int64_t(z1) - 1},
                        [&](uint32_t t, uint32_t x, uint32_t y, uint32_t z) {
                          detail::Nearest here;
                          if (!mesh.points_only())
                            here = {detail::dist2_point_triangle(detail::centre_of(g, {x, y, z}), mesh.corner(t, 0),
                                                                 mesh.corner(t, 1), mesh.corner(t, 2)),
                                    t};
                          lb.add(x, y, z - z0, here);
                        });
  return lb.finish(mesh, z0);
}

// Every layer's bricks (z, y, x order) and normals, layer by layer: kept apart, so that no array of every point is
// grown (and copied) while the layers come in.
std::vector<ShellLayer> all_layers(const Mesh& mesh, const GridPlacement& g, unsigned threads) {
  const detail::GridMesh gm = mesh.points_only() ? detail::GridMesh{} : detail::to_grid(mesh, g);
  const detail::LayerLists items = detail::surface_layers(mesh, gm, g, kLayer);
  ThreadPool pool(threads);
  std::vector<ShellLayer> layers((g.dims[2] + kLayer - 1) / kLayer);
  pool.parallel_for(layers.size(), [&](size_t k) { layers[k] = shell_layer(mesh, gm, g, items, k); });
  return layers;
}

}  // namespace

SparseShell sparse_point_shell(const Mesh& mesh, const ShellOptions& opt) {
  if (opt.on_surface)
    throw std::invalid_argument(mesh.name + ": a shell on the surface has no sparse form (sparse shells hold voxel "
                                            "centres)");
  SparseShell out;
  out.grid = detail::shell_grid(mesh, opt);
  for (uint32_t d : out.grid.dims)
    if (d / kShellBrickEdge >= 65536)
      throw MeshError(mesh.name + ": a shell grid of " + std::to_string(d) + " voxels per axis has more bricks than a "
                      "sparse shell numbers (65536 per axis)");
  std::vector<ShellLayer> layers = all_layers(mesh, out.grid, opt.threads);
  // The bricks in z, y, x order; each brick's layer and its first point in that layer's normals.
  std::vector<detail::BrickPos> sorted;
  std::vector<uint64_t> masks;
  std::vector<std::pair<uint32_t, uint32_t>> where;  // (layer, first point)
  size_t total = 0;
  for (const ShellLayer& l : layers) total += l.bricks.size();
  sorted.reserve(total);
  masks.reserve(total);
  where.reserve(total);
  for (uint32_t l = 0; l < layers.size(); ++l) {
    uint32_t point = 0;
    for (size_t b = 0; b < layers[l].bricks.size(); ++b) {
      sorted.push_back(layers[l].bricks[b]);
      masks.push_back(layers[l].masks[b]);
      where.push_back({l, point});
      point += uint32_t(__builtin_popcountll(layers[l].masks[b]));
    }
    layers[l].bricks = {};
    layers[l].masks = {};
  }
  const std::vector<uint32_t> order = detail::chain_order(sorted);
  out.bricks.reserve(order.size());
  out.masks.reserve(order.size());
  uint64_t points = 0;
  for (uint32_t b : order) {
    out.bricks.push_back(sorted[b]);
    out.masks.push_back(masks[b]);
    points += uint64_t(__builtin_popcountll(masks[b]));
  }
  if (mesh.points_only()) {
    for (const Eigen::Vector3d& n : detail::cloud_normals(mesh, out.grid, out.cells()))
      out.normals.push_back(detail::encode_normal(n));
    return out;
  }
  out.normals.reserve(points);
  for (uint32_t b : order) {
    const auto& from = layers[where[b].first].normals;
    const auto at = from.begin() + int64_t(where[b].second);
    out.normals.insert(out.normals.end(), at, at + __builtin_popcountll(masks[b]));
  }
  return out;
}

}  // namespace voxcd
