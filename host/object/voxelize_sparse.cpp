#include "voxcd/host/object/voxelize_sparse.h"

#include <algorithm>
#include <memory>

#include "voxcd/host/object/detail/voxel_layer.h"

namespace voxcd {

namespace {

// The layers of the closed chain's items: the rows of columns whose centre rays can cross each.
detail::LayerLists chain_layers(const detail::Chain& chain, const detail::GridMesh& gm, const GridPlacement& gp,
                                uint32_t h) {
  const size_t layers = (gp.dims[2] + h - 1) / h;
  return detail::layer_lists(chain.size(), layers, h, [&](size_t i) {
    const std::array<int64_t, 3>* p[3];
    if (i < chain.solid.size()) {
      for (int k = 0; k < 3; ++k) p[k] = &gm.q[chain.solid[i][k]];
    } else {
      const auto& c = chain.caps[i - chain.solid.size()];
      p[0] = &c.a;
      p[1] = &c.b;
      p[2] = &c.c;
    }
    return detail::crossing_rows(std::min({(*p[0])[2], (*p[1])[2], (*p[2])[2]}),
                                 std::max({(*p[0])[2], (*p[1])[2], (*p[2])[2]}), gp.dims[2]);
  });
}

}  // namespace

SparseVoxmap voxelize_sparse(const Mesh& mesh, const VoxelizeOptions& opt, VoxelizeReport* report, int bl) {
  const GridPlacement gp = place_grid(mesh, opt);
  SparseVoxmap out(gp, bl);
  detail::LayerJob job;
  job.mesh = &mesh;
  job.gp = gp;
  job.bl = bl;
  // Whole cells and whole refinement blocks (8^3, as voxelize's) in every layer.
  job.height = std::max<uint32_t>(8, out.edge());
  const detail::GridMesh gm = mesh.points_only() ? detail::GridMesh{} : detail::to_grid(mesh, gp);
  job.gm = &gm;
  detail::Chain chain;
  detail::LayerLists chain_items;
  std::unique_ptr<detail::CapField> field;
  if (!mesh.points_only()) {
    chain = detail::closed_chain(mesh, gm);
    chain_items = chain_layers(chain, gm, gp, job.height);
    job.chain = &chain;
    job.chain_items = &chain_items;
    if (!chain.caps.empty()) field = std::make_unique<detail::CapField>(chain.caps, detail::kFrac);
    job.field = field.get();
  }
  const detail::LayerLists surface = detail::surface_layers(mesh, gm, gp, job.height);
  job.surface = &surface;
  ThreadPool pool(opt.threads);
  const size_t layers = (gp.dims[2] + job.height - 1) / job.height, batch = 4 * size_t(pool.size());
  VoxelizeReport rep;
  std::vector<detail::LayerCells> done(batch);
  for (size_t first = 0; first < layers; first += batch) {
    const size_t n = std::min(batch, layers - first);
    pool.parallel_for(n, [&](size_t k) { done[k] = detail::voxelize_layer(job, first + k, pool); });
    // In table order: the layers one after another, each layer's cells in its own table order.
    for (size_t k = 0; k < n; ++k) {
      const uint64_t* brick = done[k].bricks.data();
      for (uint8_t c : done[k].codes) {
        out.append(c, c == kCodeBrick ? brick : nullptr);
        if (c == kCodeBrick) brick += out.brick_words();
      }
      rep.evaluated += done[k].evaluated;
      rep.uncertain += done[k].uncertain;
      done[k] = detail::LayerCells{};
    }
  }
  if (report) *report = rep;
  return out;
}

}  // namespace voxcd
