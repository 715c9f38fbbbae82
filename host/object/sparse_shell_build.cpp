// sparse_point_shell(): the centre shell built layer by layer into shell bricks (host/object/sparse_shell.h).
// Two passes over the layers: the first finds the bricks and their masks (so the chains can be ordered), the second
// each point's nearest triangle, whose normal goes straight to the point's place in chain order. So the normals are
// held once, and a layer's work space is a 32-bit triangle a point of that layer.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "voxcd/host/object/detail/layers.h"
#include "voxcd/host/object/detail/octahedral.h"
#include "voxcd/host/object/detail/shell_chain.h"
#include "voxcd/host/object/detail/shell_grid.h"
#include "voxcd/host/object/detail/shell_normals.h"
#include "voxcd/host/object/sparse_shell.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

namespace {

// Layers of two brick planes.
constexpr uint32_t kLayer = 2 * kShellBrickEdge;

// The bricks of one layer, found by their position in the layer through an index that each thread keeps from layer
// to layer (reset entry by entry), so no layer clears or allocates an array of the layer's whole extent.
class LayerIndex {
 public:
  LayerIndex(const GridPlacement& g, uint32_t z0) : bx_((g.dims[0] + 3) / 4), by_((g.dims[1] + 3) / 4), z0_(z0) {
    thread_local std::vector<uint32_t> index;
    const uint64_t n = bx_ * by_ * (kLayer / kShellBrickEdge);
    if (index.size() < n) index.assign(n, UINT32_MAX);
    index_ = &index;
  }
  ~LayerIndex() {
    for (uint64_t k : keys_) (*index_)[k] = UINT32_MAX;
  }
  LayerIndex(const LayerIndex&) = delete;
  LayerIndex& operator=(const LayerIndex&) = delete;
  uint64_t key(uint32_t x, uint32_t y, uint32_t z) const {
    return x / kShellBrickEdge + bx_ * (y / kShellBrickEdge + by_ * ((z - z0_) / kShellBrickEdge));
  }
  uint64_t key(const detail::BrickPos& b) const { return b[0] + bx_ * (b[1] + by_ * (b[2] - z0_ / kShellBrickEdge)); }
  // The slot of a key (UINT32_MAX: none), and a slot given to it.
  uint32_t& slot(uint64_t k) { return (*index_)[k]; }
  void keep(uint64_t k, uint32_t s) {
    (*index_)[k] = s;
    keys_.push_back(k);
  }
  detail::BrickPos position(uint64_t k) const {
    return {uint16_t(k % bx_), uint16_t(k / bx_ % by_), uint16_t(k / (bx_ * by_) + z0_ / kShellBrickEdge)};
  }
  const std::vector<uint64_t>& keys() const { return keys_; }

 private:
  uint64_t bx_, by_;
  uint32_t z0_;
  std::vector<uint32_t>* index_;
  std::vector<uint64_t> keys_;
};

uint32_t bit_of(uint32_t x, uint32_t y, uint32_t z) { return (x & 3) | (y & 3) << 2 | (z & 3) << 4; }

// What the passes share.
struct ShellJob {
  const Mesh* mesh;
  const detail::GridMesh* gm;
  GridPlacement g;
  detail::LayerLists items;
};

// Calls fn(item, x, y, z) for every surface voxel of the layer's items.
template <class Fn>
void layer_voxels(const ShellJob& job, size_t layer, Fn&& fn) {
  const uint32_t z0 = uint32_t(layer * kLayer), z1 = std::min(job.g.dims[2], z0 + kLayer);
  detail::layer_surface(*job.mesh, *job.gm, job.g, job.items.begin(layer), job.items.count(layer),
                        detail::ZWindow{z0, int64_t(z1) - 1}, fn);
}

// Pass 1: the layer's bricks in z, y, x order and their masks.
struct LayerBricks {
  std::vector<detail::BrickPos> bricks;
  std::vector<uint64_t> masks;
};

LayerBricks layer_bricks(const ShellJob& job, size_t layer) {
  LayerIndex index(job.g, uint32_t(layer * kLayer));
  std::vector<uint64_t> masks;
  layer_voxels(job, layer, [&](uint32_t, uint32_t x, uint32_t y, uint32_t z) {
    const uint64_t k = index.key(x, y, z);
    if (index.slot(k) == UINT32_MAX) {
      index.keep(k, uint32_t(masks.size()));
      masks.push_back(0);
    }
    masks[index.slot(k)] |= uint64_t{1} << bit_of(x, y, z);
  });
  std::vector<uint32_t> order(masks.size());
  for (uint32_t s = 0; s < order.size(); ++s) order[s] = s;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return index.keys()[a] < index.keys()[b]; });
  LayerBricks out;
  for (uint32_t s : order) {
    out.bricks.push_back(index.position(index.keys()[s]));
    out.masks.push_back(masks[s]);
  }
  return out;
}

// Pass 2: each point of the layer's bricks (bricks[0, n), sorted as pass 1 gave them) gets the normal of its nearest
// triangle among those through its voxel, written to normals[dest[j] + r] for bit r of brick j. A point keeps only
// its nearest triangle's index; the distance of the incumbent is computed again when a triangle competes (the same
// bits, so the same choice as point_shell's).
void layer_normals(const ShellJob& job, size_t layer, const detail::BrickPos* bricks, const uint64_t* masks, size_t n,
                   const uint64_t* dest, uint32_t* normals) {
  LayerIndex index(job.g, uint32_t(layer * kLayer));
  std::vector<uint64_t> first(n + 1, 0);
  for (size_t j = 0; j < n; ++j) {
    index.keep(index.key(bricks[j]), uint32_t(j));
    first[j + 1] = first[j] + uint64_t(__builtin_popcountll(masks[j]));
  }
  const Mesh& m = *job.mesh;
  auto d2 = [&](const Eigen::Vector3d& p, uint32_t t) {
    return detail::dist2_point_triangle(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
  };
  std::vector<uint32_t> best(first[n], UINT32_MAX);
  layer_voxels(job, layer, [&](uint32_t t, uint32_t x, uint32_t y, uint32_t z) {
    const uint32_t j = index.slot(index.key(x, y, z));
    const uint64_t below = (uint64_t{1} << bit_of(x, y, z)) - 1;
    uint32_t& b = best[first[j] + uint64_t(__builtin_popcountll(masks[j] & below))];
    if (b == UINT32_MAX) {
      b = t;
      return;
    }
    const Eigen::Vector3d p = detail::centre_of(job.g, {x, y, z});
    if (detail::Nearest{d2(p, t), t}.better_than(detail::Nearest{d2(p, b), b})) b = t;
  });
  for (size_t j = 0; j < n; ++j)
    for (uint64_t k = first[j]; k < first[j + 1]; ++k) {
      if (best[k] == UINT32_MAX) throw std::logic_error("sparse_point_shell: shell point without a triangle");
      normals[dest[j] + (k - first[j])] = detail::encode_normal(detail::triangle_normal(m, best[k]));
    }
}

// Pass 1 over every layer: the bricks in z, y, x order, and where each layer's begin.
void all_bricks(const ShellJob& job, ThreadPool& pool, std::vector<detail::BrickPos>& bricks,
                std::vector<uint64_t>& masks, std::vector<size_t>& layer_first) {
  std::vector<LayerBricks> layers((job.g.dims[2] + kLayer - 1) / kLayer);
  pool.parallel_for(layers.size(), [&](size_t l) { layers[l] = layer_bricks(job, l); });
  size_t total = 0;
  for (const LayerBricks& l : layers) total += l.bricks.size();
  bricks.reserve(total);
  masks.reserve(total);
  layer_first.assign(1, 0);
  for (LayerBricks& l : layers) {
    bricks.insert(bricks.end(), l.bricks.begin(), l.bricks.end());
    masks.insert(masks.end(), l.masks.begin(), l.masks.end());
    layer_first.push_back(bricks.size());
    l = LayerBricks{};
  }
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
  const detail::GridMesh gm = mesh.points_only() ? detail::GridMesh{} : detail::to_grid(mesh, out.grid);
  const ShellJob job{&mesh, &gm, out.grid, detail::surface_layers(mesh, gm, out.grid, kLayer)};
  ThreadPool pool(opt.threads);
  std::vector<detail::BrickPos> sorted;
  std::vector<uint64_t> masks;
  std::vector<size_t> layer_first;
  all_bricks(job, pool, sorted, masks, layer_first);
  // The chains, and each sorted brick's first point in chain order.
  const std::vector<uint32_t> order = detail::chain_order(sorted);
  std::vector<uint64_t> dest(sorted.size());
  uint64_t points = 0;
  out.bricks.reserve(order.size());
  out.masks.reserve(order.size());
  for (uint32_t b : order) {
    out.bricks.push_back(sorted[b]);
    out.masks.push_back(masks[b]);
    dest[b] = points;
    points += uint64_t(__builtin_popcountll(masks[b]));
  }
  out.normals.assign(points, 0);
  if (mesh.points_only()) {
    const auto normals = detail::cloud_normals(mesh, out.grid, out.cells());
    for (size_t k = 0; k < normals.size(); ++k) out.normals[k] = detail::encode_normal(normals[k]);
    return out;
  }
  pool.parallel_for(layer_first.size() - 1, [&](size_t l) {
    const size_t b = layer_first[l];
    layer_normals(job, l, sorted.data() + b, masks.data() + b, layer_first[l + 1] - b, dest.data() + b,
                  out.normals.data());
  });
  return out;
}

}  // namespace voxcd
