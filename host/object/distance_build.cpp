// distance_field(): the exact signed distance of a mesh at the nodes of a voxmap's grid (host/object/distance_field.h).
// The sign is the voxeliser's solid at each node, computed by the voxeliser itself on the grid of cells centred on
// the nodes; the magnitude is the distance to the nearest triangle, searched in a tree only for nodes that can lie
// within the band (the rest clamp), along each row of nodes with the distance to the previous node's nearest
// triangle as the radius.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "voxcd/host/mesh/closest.h"
#include "voxcd/host/object/detail/node_value.h"
#include "voxcd/host/object/detail/solid.h"
#include "voxcd/host/object/detail/unresolved.h"
#include "voxcd/host/object/distance_field.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

namespace {

bool bit(const std::vector<uint64_t>& b, uint64_t i) { return (b[i >> 6] >> (i & 63)) & 1; }

// Near[i] is 1 when the centre of some set cell of `surface` (cells centred on the nodes) lies within sqrt(limit2)
// of node i: the squared Euclidean distance transform of the set cells (Felzenszwalb and Huttenlocher, one axis at a
// time, lower envelopes of parabolas), in integers clamped to limit2 + 1 (a clamped value exceeds limit2 either way,
// and the minimum that reaches limit2 or less never takes one).
std::vector<uint8_t> near_nodes(const std::vector<uint64_t>& surface, const std::array<uint64_t, 3>& n,
                                uint32_t limit2, ThreadPool& pool) {
  const uint64_t total = n[0] * n[1] * n[2];
  if (limit2 >= 65534) return std::vector<uint8_t>(total, 1);  // a band as wide as the largest grid
  const uint16_t cap = uint16_t(limit2 + 1);
  std::vector<uint16_t> d(total);
  for (uint64_t i = 0; i < total; ++i) d[i] = bit(surface, i) ? 0 : cap;
  const uint64_t stride[3] = {1, n[0], n[0] * n[1]};
  for (int axis = 0; axis < 3; ++axis) {
    const uint64_t len = n[size_t(axis)], lines = total / len;
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const uint64_t parts = std::min<uint64_t>(lines, 256);
    pool.parallel_for(parts, [&](size_t part) {
      std::vector<int64_t> f(len), v(len);
      std::vector<double> z(len + 1);
      for (uint64_t line = lines * part / parts; line < lines * (part + 1) / parts; ++line) {
        const uint64_t base = (line % n[size_t(u)]) * stride[u] + (line / n[size_t(u)]) * stride[w];
        for (uint64_t k = 0; k < len; ++k) f[k] = d[base + k * stride[axis]];
        // The lower envelope of the parabolas (x - q)^2 + f[q] of the sites q with f[q] < cap.
        int64_t sites = 0;
        for (int64_t q = 0; q < int64_t(len); ++q) {
          if (f[size_t(q)] >= cap) continue;
          while (sites > 0) {
            const int64_t p = v[size_t(sites - 1)];
            const double s = double((f[size_t(q)] + q * q) - (f[size_t(p)] + p * p)) / double(2 * (q - p));
            if (s > z[size_t(sites - 1)]) {
              v[size_t(sites)] = q;
              z[size_t(sites)] = s;
              ++sites;
              break;
            }
            --sites;
          }
          if (sites == 0) {
            v[0] = q;
            z[0] = -HUGE_VAL;
            sites = 1;
          }
        }
        z[size_t(sites)] = HUGE_VAL;
        for (int64_t x = 0, k = 0; x < int64_t(len); ++x) {
          int64_t out = cap;
          if (sites > 0) {
            while (z[size_t(k + 1)] < double(x)) ++k;
            const int64_t p = v[size_t(k)];
            out = std::min<int64_t>(cap, (x - p) * (x - p) + f[size_t(p)]);
          }
          d[base + uint64_t(x) * stride[axis]] = uint16_t(out);
        }
      }
    });
  }
  std::vector<uint8_t> near(total);
  for (uint64_t i = 0; i < total; ++i) near[i] = d[i] <= limit2;
  return near;
}

}  // namespace

namespace {

// What step 3 of distance_field needs: the nodes' sign and nearness, the triangles in grid coordinates.
struct NodeGrid {
  std::array<uint64_t, 3> n;
  const std::vector<uint64_t>& solid;
  const std::vector<uint8_t>& near;
  std::vector<Eigen::Vector3d> gv;  // the vertices in grid coordinates: node (X, Y, Z) at (X, Y, Z)
};

// The values of the nodes of one row (Y, Z): clamped beyond the band, else the rounded signed distance.
void measure_row(const NodeGrid& ng, const detail::NodeMeasure& m, uint64_t row, DistanceField& f) {
  const uint64_t Y = row % ng.n[1], Z = row / ng.n[1];
  uint32_t prev = UINT32_MAX;  // the previous node's nearest triangle in this row, when measured
  for (uint64_t X = 0; X < ng.n[0]; ++X) {
    const uint64_t i = X + ng.n[0] * row;
    const bool inside = bit(ng.solid, i);
    if (!ng.near[i]) {
      f.q[i] = int16_t(inside ? m.qmin : m.qmax);
      prev = UINT32_MAX;
      continue;
    }
    f.q[i] = detail::node_value(m, Eigen::Vector3d(double(X), double(Y), double(Z)), inside, prev);
  }
}

}  // namespace

namespace detail {

void check_distance_options(const Mesh& mesh, const DistanceOptions& opt) {
  if (!valid_distance_bits(opt.bits))
    throw MeshError(mesh.name + ": distance bits must be " + distance_bits_text() + ", got " +
                    std::to_string(opt.bits));
  if (!(std::isfinite(opt.band) && opt.band > 0)) {
    std::ostringstream s;
    s << mesh.name << ": the distance band must be a positive finite number of voxels, got " << opt.band;
    throw MeshError(s.str());
  }
  if (mesh.points_only())
    throw MeshError(mesh.name + ": a point cloud has no surface to measure a signed distance from (" +
                    std::to_string(mesh.vertices.size()) + " points, no triangles); give a mesh with faces");
  if (mesh.triangles.empty()) throw MeshError(mesh.name + ": the mesh has no triangles");
}

}  // namespace detail

DistanceField distance_field(const Mesh& mesh, const Voxmap& voxmap, const DistanceOptions& opt,
                             uint64_t* conservative) {
  detail::check_distance_options(mesh, opt);
  const GridPlacement& g = voxmap.grid();
  DistanceField f;
  f.bits = opt.bits;
  f.step = opt.band / double(1 << (opt.bits - 1));
  f.dims = g.dims;
  const std::array<uint64_t, 3> n = {uint64_t(g.dims[0]) + 1, uint64_t(g.dims[1]) + 1, uint64_t(g.dims[2]) + 1};
  f.q.assign(n[0] * n[1] * n[2], 0);

  // 1. The grid whose voxel centres are the nodes: the solid there is the sign, its surface voxels say which nodes
  // can be near the surface.
  GridPlacement cells;
  cells.voxel = g.voxel;
  cells.origin = g.origin - Eigen::Vector3d::Constant(0.5 * g.voxel);
  for (int a = 0; a < 3; ++a) cells.dims[size_t(a)] = uint32_t(n[size_t(a)]);
  std::vector<uint64_t> surface;
  const std::vector<uint64_t> solid = detail::solid_bits(mesh, cells, opt.threads, &surface);

  // 2. A surface point within the band of a node lies in a surface node cell (side 1, centred on a node, grown by
  // more than the voxeliser's snapping moves the surface) whose centre is within band + sqrt(3)/2 of the node: every
  // node without such a cell is farther than the band from the surface and clamps.
  ThreadPool pool(opt.threads);
  const double reach = opt.band + std::sqrt(3.0) / 2 + 1e-3;
  const std::vector<uint8_t> near =
      near_nodes(surface, n, uint32_t(std::min(std::floor(reach * reach), 65535.0)), pool);
  surface.clear();
  surface.shrink_to_fit();

  // 3. Distances in voxels, a row of nodes at a time, from the tree over the triangles in grid coordinates.
  NodeGrid ng{n, solid, near, std::vector<Eigen::Vector3d>(mesh.vertices.size())};
  for (size_t i = 0; i < ng.gv.size(); ++i) ng.gv[i] = (mesh.vertices[i] - g.origin) / g.voxel;
  const detail::TriangleTree tree(ng.gv, mesh.triangles);
  // Nodes beyond the band clamp: any distance > band rounds to at least 2^(bits-1) steps. The search radius is a
  // little larger so that a distance at the band's edge is still measured exactly.
  const detail::NodeMeasure m{mesh, ng.gv, tree, opt.band * (1 + 1e-9), 1 / f.step, f.qmin(), f.qmax()};
  const uint64_t rows = n[1] * n[2];
  const uint64_t parts = std::min<uint64_t>(rows, 1024);
  pool.parallel_for(parts, [&](size_t part) {
    for (uint64_t row = rows * part / parts; row < rows * (part + 1) / parts; ++row) measure_row(ng, m, row, f);
  });
  // 4. What the nodes cannot resolve becomes conservative.
  const uint64_t lowered = opt.conservative ? detail::make_unresolved_conservative(mesh, g, f, opt.threads) : 0;
  if (conservative) *conservative = lowered;
  return f;
}

}  // namespace voxcd
