// surface_shell(): the point shell of an object with a distance field, on the surface itself
// (host/object/point_shell.h). A shell point's field value is then ~0, so a hit's interpolated distance measures
// the penetration of the surface, not of a voxel centre up to sqrt(3)/2 spacings away from it.
#include <algorithm>
#include <cmath>
#include <string>

#include "voxcd/host/mesh/closest.h"
#include "voxcd/host/object/detail/shell_grid.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

namespace {

// A shell point found for one surface voxel: its fixed-point grid coordinates and normal.
struct Candidate {
  std::array<int32_t, 3> coords;
  uint64_t cell;    // linear index of the voxel holding the rounded point
  uint64_t source;  // its voxel's position in `voxels`: the first of equal points is kept
  Eigen::Vector3d normal;
};

// The closest point of the surface to each voxel's centre, rounded to kShellFrac fraction bits of the grid.
std::vector<Candidate> closest_points(const Mesh& mesh, const GridPlacement& grid, const std::vector<uint64_t>& voxels,
                                      unsigned threads) {
  // Closest points in the shell grid's coordinates (so rounding is per axis of the grid), normals in the object's.
  std::vector<Eigen::Vector3d> gv(mesh.vertices.size());
  for (size_t i = 0; i < gv.size(); ++i) gv[i] = (mesh.vertices[i] - grid.origin) / grid.voxel;
  const detail::TriangleTree tree(gv, mesh.triangles);
  const detail::PseudoNormals pseudo(mesh.vertices, mesh.triangles);
  std::vector<Candidate> cand(voxels.size());
  const uint64_t nx = grid.dims[0], ny = grid.dims[1], nxy = nx * ny;
  const double unit = double(1 << kShellFrac);
  // The rounding below moves a point by at most this (grid units): closest points this near an edge or a corner may
  // land on it, and take its normal.
  const double kSnap = std::sqrt(3.0) / (2 * unit);
  ThreadPool pool(threads);
  const size_t parts = std::max<size_t>(1, std::min<size_t>(voxels.size(), 256));
  pool.parallel_for(parts, [&](size_t p) {
    for (size_t k = voxels.size() * p / parts; k < voxels.size() * (p + 1) / parts; ++k) {
      const uint64_t v = voxels[k];
      const Eigen::Vector3d centre(double(v % nx) + 0.5, double(v / nx % ny) + 0.5, double(v / nxy) + 0.5);
      const detail::Closest found = tree.closest(centre);
      const auto& t = mesh.triangles[found.triangle];
      const detail::Closest c = detail::snap_feature(found, gv[t[0]], gv[t[1]], gv[t[2]], kSnap);
      Candidate& out = cand[k];
      uint64_t cell[3];
      for (int a = 0; a < 3; ++a) {
        const double g = std::round(c.point[a] * unit);  // >= 0: the mesh lies inside the padded grid
        out.coords[size_t(a)] = int32_t(g);
        cell[a] = std::min<uint64_t>(uint64_t(std::max(0.0, std::floor(g / unit))), grid.dims[size_t(a)] - 1);
      }
      out.cell = cell[0] + nx * cell[1] + nxy * cell[2];
      out.source = k;
      out.normal = pseudo.at(c);
    }
  });
  return cand;
}

// The candidates in cell order, each point once (the first voxel's), appended to s.
void add_unique(std::vector<Candidate>& cand, PointShell& s) {
  const uint64_t nx = s.grid.dims[0], ny = s.grid.dims[1], nxy = nx * ny;
  std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) {
    if (x.cell != y.cell) return x.cell < y.cell;
    for (int a = 2; a >= 0; --a)
      if (x.coords[size_t(a)] != y.coords[size_t(a)]) return x.coords[size_t(a)] < y.coords[size_t(a)];
    return x.source < y.source;
  });
  for (size_t k = 0; k < cand.size(); ++k) {
    const Candidate& c = cand[k];
    if (k > 0 && c.coords == cand[k - 1].coords) continue;
    s.coords.push_back(c.coords);
    s.cells.push_back({uint32_t(c.cell % nx), uint32_t(c.cell / nx % ny), uint32_t(c.cell / nxy)});
    s.points.push_back(s.grid.origin + s.grid.voxel * s.grid_point(s.size() - 1));
    s.normals.push_back(c.normal);
  }
}

}  // namespace

PointShell surface_shell(const Mesh& mesh, const ShellOptions& opt) {
  detail::check_shell_options(mesh, opt);
  if (mesh.points_only())
    throw MeshError(mesh.name + ": a point cloud has no surface to put shell points on (" +
                    std::to_string(mesh.vertices.size()) + " points, no triangles)");
  PointShell s;
  s.on_surface = true;
  s.grid = detail::shell_grid(mesh, opt);
  const std::vector<uint64_t> bits = surface_bits(mesh, s.grid, opt.threads);
  std::vector<uint64_t> voxels;
  for (size_t i = 0; i < bits.size(); ++i)
    for (uint64_t w = bits[i]; w; w &= w - 1) voxels.push_back(i * 64 + uint64_t(__builtin_ctzll(w)));
  std::vector<Candidate> cand = closest_points(mesh, s.grid, voxels, opt.threads);
  add_unique(cand, s);
  return s;
}

}  // namespace voxcd
