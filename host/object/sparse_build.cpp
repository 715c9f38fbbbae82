// sparse_distance_field() (host/object/sparse_field.h): which coarse cells lie near the surface (a triangle within
// the band of the cell), then one layer of cells at a time, each cell on its own (detail/brick_build.h): no array of
// the whole grid's nodes is ever made, and exact distances are measured only at the nodes of bricks.
#include <algorithm>
#include <utility>

#include "voxcd/host/object/detail/brick_build.h"
#include "voxcd/host/object/detail/cube_walk.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

namespace {

constexpr double kEdge = SparseDistanceField::kEdge;

std::array<int64_t, 3> cells_hi(const std::array<uint32_t, 3>& c) { return {c[0], c[1], c[2]}; }

// (cell, triangle) for every coarse cell each triangle meets (grown as the voxeliser grows a surface voxel), sorted:
// a cell's triangles are one run, and a layer's cells one range.
std::vector<std::pair<uint64_t, uint32_t>> cell_triangles(const Mesh& mesh, const std::vector<Eigen::Vector3d>& gv,
                                                          const std::array<uint32_t, 3>& c, ThreadPool& pool) {
  const size_t parts = std::max<size_t>(1, std::min<size_t>(mesh.size(), size_t(pool.size()) * 16));
  std::vector<std::vector<std::pair<uint64_t, uint32_t>>> found(parts);
  pool.parallel_for(parts, [&](size_t p) {
    for (size_t t = mesh.size() * p / parts; t < mesh.size() * (p + 1) / parts; ++t) {
      const auto& tri = mesh.triangles[t];
      detail::for_each_cube_meeting(gv[tri[0]], gv[tri[1]], gv[tri[2]], kEdge, 1.0 / (1 << 19), {0, 0, 0}, cells_hi(c),
                                    [&](int64_t x, int64_t y, int64_t z) {
                                      const uint64_t i = uint64_t(x) + c[0] * (uint64_t(y) + c[1] * uint64_t(z));
                                      found[p].emplace_back(i, uint32_t(t));
                                    });
    }
  });
  std::vector<std::pair<uint64_t, uint32_t>> all;
  for (auto& f : found) all.insert(all.end(), f.begin(), f.end());
  std::sort(all.begin(), all.end());
  return all;
}

// 1 for every cell whose cube, grown by the band, meets a triangle: the cells some of whose nodes may lie within the
// band (every node of any other cell is farther than the band from every triangle, so it clamps).
std::vector<uint8_t> near_cells(const Mesh& mesh, const std::vector<Eigen::Vector3d>& gv,
                                const std::array<uint32_t, 3>& c, double band) {
  std::vector<uint8_t> near(uint64_t(c[0]) * c[1] * c[2], 0);
  const double grow = band * (1 + 1e-6) + 1e-6;
  for (const auto& tri : mesh.triangles)
    detail::for_each_cube_meeting(
        gv[tri[0]], gv[tri[1]], gv[tri[2]], kEdge, grow, {0, 0, 0}, cells_hi(c),
        [&](int64_t x, int64_t y, int64_t z) { near[uint64_t(x) + c[0] * (uint64_t(y) + c[1] * uint64_t(z))] = 1; });
  return near;
}

// The parts the field is assembled from, in table order.
struct Parts {
  std::vector<uint8_t> codes;
  std::vector<int16_t> nodes;
  std::vector<uint64_t> keys;
};

// Every cell of layer cz, each built on its own (in parallel), appended in table order.
void build_layer(const detail::BrickContext& ctx, uint32_t cz, const std::vector<uint8_t>& near,
                 const std::vector<std::pair<uint64_t, uint32_t>>& ct, ThreadPool& pool, Parts& out) {
  const uint64_t per_layer = uint64_t(ctx.cells[0]) * ctx.cells[1], first = per_layer * cz;
  std::vector<detail::BrickResult> res(per_layer);
  pool.parallel_for(per_layer, [&](size_t i) {
    const uint64_t t = first + i;
    const std::array<uint32_t, 3> c = {uint32_t(i % ctx.cells[0]), uint32_t(i / ctx.cells[0]), cz};
    if (!near[t]) {
      res[i] = detail::far_cell(ctx, c);
      return;
    }
    auto b = std::lower_bound(ct.begin(), ct.end(), std::make_pair(t, uint32_t(0)));
    std::vector<uint32_t> tris;
    for (; b != ct.end() && b->first == t; ++b) tris.push_back(b->second);
    res[i] = detail::build_brick(ctx, c, t, tris);
  });
  for (detail::BrickResult& r : res) {
    out.codes.push_back(r.code);
    out.nodes.insert(out.nodes.end(), r.nodes.begin(), r.nodes.end());
    out.keys.insert(out.keys.end(), r.conservative.begin(), r.conservative.end());
  }
}

}  // namespace

SparseDistanceField sparse_distance_field(const Mesh& mesh, const GridPlacement& g, const SparseFieldOptions& opt) {
  detail::check_distance_options(mesh, opt.distance);
  if (opt.max_level < 0 || opt.max_level > SparseDistanceField::kMaxLevel)
    throw MeshError(mesh.name + ": a sparse field's bricks refine to levels 0 to 3, not " +
                    std::to_string(opt.max_level));
  const int bits = opt.distance.bits;
  const double step = opt.distance.band / double(1 << (bits - 1));
  std::array<uint32_t, 3> cells;
  for (int a = 0; a < 3; ++a)
    cells[size_t(a)] = (g.dims[size_t(a)] + SparseDistanceField::kEdge - 1) / SparseDistanceField::kEdge;
  std::vector<Eigen::Vector3d> gv(mesh.vertices.size());
  for (size_t i = 0; i < gv.size(); ++i) gv[i] = (mesh.vertices[i] - g.origin) / g.voxel;
  const detail::TriangleTree tree(gv, mesh.triangles);
  const detail::PseudoNormals normals(gv, mesh.triangles);
  const int qmax = (1 << (bits - 1)) - 1, qmin = -(1 << (bits - 1));
  const detail::NodeMeasure m{mesh, gv, tree, opt.distance.band * (1 + 1e-9), 1 / step, qmin, qmax};
  ThreadPool pool(opt.distance.threads);
  const auto ct = cell_triangles(mesh, gv, cells, pool);
  const std::vector<uint8_t> near = near_cells(mesh, gv, cells, opt.distance.band);
  detail::BrickSigns signs(mesh, g, cells, opt.whole_solid_nodes, opt.distance.threads);
  const detail::BrickContext ctx{mesh, g, cells, m, normals, signs, step, opt.max_level, opt.distance.conservative};
  Parts parts;
  for (uint32_t cz = 0; cz < cells[2]; ++cz) {
    signs.load_layer(cz);
    build_layer(ctx, cz, near, ct, pool, parts);
  }
  std::sort(parts.keys.begin(), parts.keys.end());
  return SparseDistanceField(bits, step, g.dims, std::move(parts.codes), std::move(parts.nodes), std::move(parts.keys));
}

}  // namespace voxcd
