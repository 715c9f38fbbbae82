#include "voxcd/host/object/detail/voxel_geometry.h"

namespace voxcd::detail {

GridMesh to_grid(const Mesh& m, const GridPlacement& gp) {
  GridMesh gm;
  gm.q.resize(m.vertices.size());
  gm.g.resize(m.vertices.size());
  for (size_t i = 0; i < m.vertices.size(); ++i) {
    const Eigen::Vector3d g = (m.vertices[i] - gp.origin) / gp.voxel;
    for (int a = 0; a < 3; ++a) {
      gm.q[i][a] = std::llround(std::ldexp(g[a], kFrac));
      gm.g[i][a] = std::ldexp(double(gm.q[i][a]), -kFrac);
    }
  }
  return gm;
}

std::vector<std::pair<size_t, size_t>> chunks(size_t n, unsigned workers) {
  const size_t parts = std::max<size_t>(1, std::min<size_t>(n, size_t(workers) * 16));
  std::vector<std::pair<size_t, size_t>> r;
  for (size_t p = 0; p < parts; ++p) r.emplace_back(n * p / parts, n * (p + 1) / parts);
  return r;
}

void clipped_bounds(const Eigen::Vector3d& A, const Eigen::Vector3d& B, const Eigen::Vector3d& C, double zl, double zh,
                    Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  // Sutherland-Hodgman against z >= zl, then z <= zh; the bounds of what is left. A triangle has at most 5 corners
  // after two planes.
  Eigen::Vector3d poly[8] = {A, B, C}, next[8];
  int n = 3;
  for (int side = 0; side < 2 && n > 0; ++side) {
    auto inside = [&](const Eigen::Vector3d& p) { return side == 0 ? p[2] >= zl : p[2] <= zh; };
    const double plane = side == 0 ? zl : zh;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d& p = poly[i];
      const Eigen::Vector3d& q = poly[(i + 1) % n];
      if (inside(p)) next[m++] = p;
      if (inside(p) != inside(q)) {
        const double s = (plane - p[2]) / (q[2] - p[2]);
        Eigen::Vector3d x = p + s * (q - p);
        x[2] = plane;
        next[m++] = x;
      }
    }
    n = m;
    for (int i = 0; i < n; ++i) poly[i] = next[i];
  }
  lo = Eigen::Vector3d::Constant(HUGE_VAL);
  hi = Eigen::Vector3d::Constant(-HUGE_VAL);
  for (int i = 0; i < n; ++i) {
    lo = lo.cwiseMin(poly[i]);
    hi = hi.cwiseMax(poly[i]);
  }
}

}  // namespace voxcd::detail
