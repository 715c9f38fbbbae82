#include "voxcd/host/object/point_shell.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <unordered_map>
#include <limits>
#include <stdexcept>
#include <string>

#include "voxcd/host/object/detail/shell_grid.h"
#include "voxcd/host/object/detail/shell_normals.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/float_model.h"

namespace voxcd {

namespace detail {

double dist2_point_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (ap - ab * (d1 / (d1 - d3))).squaredNorm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (ap - ac * (d2 / (d2 - d6))).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (bp - (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).squaredNorm();
  const double denom = 1 / (va + vb + vc);
  return (ap - ab * (vb * denom) - ac * (vc * denom)).squaredNorm();
}

Eigen::Vector3d triangle_normal(const Mesh& mesh, size_t t) {
  return (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0)).normalized();
}

// The direction of least spread of the cloud's points within two shell spacings of the point (principal components),
// turned away from the cloud's centroid (+z when at right angles); with fewer than three neighbours, the direction
// from the centroid.
std::vector<Eigen::Vector3d> cloud_normals(const Mesh& mesh, const GridPlacement& grid,
                                           const std::vector<std::array<uint32_t, 3>>& cells) {
  const double h = grid.voxel;
  std::unordered_map<uint64_t, std::vector<uint32_t>> by_cell;
  auto key = [](int64_t x, int64_t y, int64_t z) {
    return (uint64_t(x) & 0x1fffff) | (uint64_t(y) & 0x1fffff) << 21 | (uint64_t(z) & 0x1fffff) << 42;
  };
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  size_t n = 0;
  for (uint32_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d& p = mesh.vertices[v];
    if (!p.allFinite()) continue;
    const Eigen::Vector3d g = (p - grid.origin) / h;
    by_cell[key(int64_t(std::floor(g.x())), int64_t(std::floor(g.y())), int64_t(std::floor(g.z())))].push_back(v);
    centroid += p;
    ++n;
  }
  centroid /= double(std::max<size_t>(n, 1));
  std::vector<Eigen::Vector3d> normals(cells.size());
  for (size_t k = 0; k < cells.size(); ++k) {
    const Eigen::Vector3d c = centre_of(grid, cells[k]);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> near;
    for (int64_t dz = -2; dz <= 2; ++dz)
      for (int64_t dy = -2; dy <= 2; ++dy)
        for (int64_t dx = -2; dx <= 2; ++dx) {
          const auto it = by_cell.find(key(int64_t(cells[k][0]) + dx, int64_t(cells[k][1]) + dy,
                                           int64_t(cells[k][2]) + dz));
          if (it == by_cell.end()) continue;
          for (uint32_t v : it->second)
            if ((mesh.vertices[v] - c).norm() <= 2 * h) {
              near.push_back(mesh.vertices[v]);
              mean += mesh.vertices[v];
            }
        }
    Eigen::Vector3d nrm = c - centroid;
    if (near.size() >= 3) {
      mean /= double(near.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const auto& p : near) cov += (p - mean) * (p - mean).transpose();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
      nrm = es.eigenvectors().col(0);
      if (nrm.dot(c - centroid) < 0) nrm = -nrm;
    }
    if (!(nrm.norm() > 0) || !nrm.allFinite()) nrm = Eigen::Vector3d::UnitZ();
    normals[k] = nrm.normalized();
  }
  return normals;
}

}  // namespace detail

std::vector<ShellWord> PointShell::words(const DeviceConfig& cfg) const {
  std::vector<ShellWord> w(size());
  for (size_t k = 0; k < size(); ++k) {
    const Eigen::Vector3d g = grid_point(k);
    const double p[3] = {g.x(), g.y(), g.z()};
    w[k] = quantize_point(cfg, p, "shell point " + std::to_string(k));
  }
  return w;
}

double PointShell::max_grid_coordinate() const {
  double m = 0;
  for (size_t k = 0; k < size(); ++k) m = std::max(m, grid_point(k).maxCoeff());
  return m;
}

namespace {

// The points at the centres of the voxels set in bits (cells and points of s, in voxel order); returns the rank of
// every word (set bits before it), so that a voxel's point index is found in O(1).
std::vector<uint64_t> centre_points(const std::vector<uint64_t>& bits, PointShell& s) {
  std::vector<uint64_t> rank(bits.size() + 1, 0);
  for (size_t i = 0; i < bits.size(); ++i) rank[i + 1] = rank[i] + uint64_t(__builtin_popcountll(bits[i]));
  const size_t n = rank.back();
  const uint64_t nx = s.grid.dims[0], nxy = nx * s.grid.dims[1];
  s.cells.reserve(n);
  s.points.reserve(n);
  for (size_t i = 0; i < bits.size(); ++i)
    for (uint64_t w = bits[i]; w; w &= w - 1) {
      const uint64_t v = i * 64 + uint64_t(__builtin_ctzll(w));
      const std::array<uint32_t, 3> c = {uint32_t(v % nx), uint32_t(v / nx % s.grid.dims[1]), uint32_t(v / nxy)};
      s.cells.push_back(c);
      s.points.push_back(detail::centre_of(s.grid, c));
    }
  return rank;
}

// Each point's normal: that of the nearest triangle overlapping its voxel (index_of(linear index) gives the voxel's
// point). Each worker keeps its own nearest for a share of the triangles, merged by (distance, triangle).
template <class IndexOf>
std::vector<Eigen::Vector3d> nearest_normals(const Mesh& mesh, const PointShell& s, IndexOf&& index_of,
                                             unsigned threads) {
  using detail::Nearest;
  const size_t n = s.size();
  const uint64_t nx = s.grid.dims[0], nxy = nx * s.grid.dims[1];
  ThreadPool pool(threads);
  const size_t parts = std::max<size_t>(1, std::min<size_t>(mesh.size(), pool.size()));
  std::vector<std::vector<Nearest>> best(parts, std::vector<Nearest>(n));
  pool.parallel_for(parts, [&](size_t p) {
    auto& b = best[p];
    for_each_overlap(mesh, s.grid, mesh.size() * p / parts, mesh.size() * (p + 1) / parts,
                     [&](size_t t, uint32_t x, uint32_t y, uint32_t z) {
                       const size_t k = index_of(x + nx * y + nxy * z);
                       const Nearest here{detail::dist2_point_triangle(s.points[k], mesh.corner(t, 0),
                                                                       mesh.corner(t, 1), mesh.corner(t, 2)),
                                          uint32_t(t)};
                       if (here.better_than(b[k])) b[k] = here;
                     });
  });
  std::vector<Eigen::Vector3d> normals(n);
  for (size_t k = 0; k < n; ++k) {
    Nearest b = best[0][k];
    for (size_t p = 1; p < parts; ++p)
      if (best[p][k].better_than(b)) b = best[p][k];
    if (b.tri == UINT32_MAX) throw std::logic_error("point_shell: shell point without a triangle");
    normals[k] = detail::triangle_normal(mesh, b.tri);
  }
  return normals;
}

}  // namespace

PointShell point_shell(const Mesh& mesh, const ShellOptions& opt) {
  if (opt.on_surface) return surface_shell(mesh, opt);
  PointShell s;
  s.grid = detail::shell_grid(mesh, opt);
  const std::vector<uint64_t> bits = surface_bits(mesh, s.grid, opt.threads);
  const std::vector<uint64_t> rank = centre_points(bits, s);
  if (mesh.points_only()) {
    s.normals = detail::cloud_normals(mesh, s.grid, s.cells);
    return s;
  }
  s.normals = nearest_normals(
      mesh, s,
      [&](uint64_t v) {
        return size_t(rank[v >> 6] + uint64_t(__builtin_popcountll(bits[v >> 6] & ((uint64_t{1} << (v & 63)) - 1))));
      },
      opt.threads);
  return s;
}

PointShell detail::centre_shell(const Mesh& mesh, const GridPlacement& g, std::vector<std::array<uint32_t, 3>> cells,
                                unsigned threads) {
  PointShell s;
  s.grid = g;
  s.cells = std::move(cells);
  s.points.reserve(s.cells.size());
  for (const auto& c : s.cells) s.points.push_back(centre_of(g, c));
  if (mesh.points_only()) {
    s.normals = cloud_normals(mesh, g, s.cells);
    return s;
  }
  const uint64_t nx = g.dims[0], ny = g.dims[1];
  std::vector<uint64_t> lin(s.size());
  for (size_t k = 0; k < s.size(); ++k) lin[k] = s.cells[k][0] + nx * (s.cells[k][1] + ny * uint64_t(s.cells[k][2]));
  s.normals = nearest_normals(
      mesh, s, [&](uint64_t v) { return size_t(std::lower_bound(lin.begin(), lin.end(), v) - lin.begin()); }, threads);
  return s;
}

}  // namespace voxcd
