// Internal to host/object (voxelize.cpp, voxelize_sparse.cpp, the sparse shell): the voxeliser's geometry on a grid.
// Vertices snapped to fixed point, the crossings of a triangle with the rays along x through the voxel-column
// centres (exact integer predicates), and the voxels a triangle passes through. Both walks take a window of z so that
// a grid can be processed in layers; a window changes which voxels are visited, never what is decided for a voxel.
// Every file that instantiates these templates is compiled with -ffp-contract=off (host/CMakeLists.txt), so the
// float side gives the same bits everywhere.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

using i128 = __int128;

// Vertices are snapped to 2^-kFrac voxel in grid coordinates, so that the parity predicates below are exact
// integer arithmetic. Snapping moves a vertex by at most 2^-(kFrac+1) per axis, the surface by at most
// sqrt(3) * 2^-(kFrac+1) < 2^-kFrac; surface voxels are grown by kGrow > that, so they stay conservative for
// the mesh as given.
constexpr int kFrac = 20;
constexpr int64_t kOne = int64_t{1} << kFrac;
constexpr int64_t kHalf = kOne / 2;
constexpr double kGrow = 1.0 / (1 << 19);

struct GridMesh {
  std::vector<std::array<int64_t, 3>> q;  // snapped grid coordinates, kFrac fraction bits
  std::vector<Eigen::Vector3d> g;         // the same values as doubles, in voxels
};

// The mesh's vertices in grid gp's coordinates, snapped.
GridMesh to_grid(const Mesh& m, const GridPlacement& gp);

inline int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
inline int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

// A range of z voxel indices [z0, z1] (inclusive); the default is every z.
struct ZWindow {
  int64_t z0 = 0, z1 = INT64_MAX;
  bool all() const { return z0 <= 0 && z1 == INT64_MAX; }
};

// Edge function of the directed edge a->b at p in the (y, z) projection; its sign says on which side p is.
// Zero is resolved by simulation of simplicity: p is taken at (p_y + e, p_z + e^2) for an infinitesimal e, so a
// ray through an edge or a vertex belongs to exactly one side, and both triangles of an edge agree on it.
inline bool positive_side(const std::array<int64_t, 3>& a, const std::array<int64_t, 3>& b, int64_t py, int64_t pz,
                          i128& w) {
  w = i128(b[1] - a[1]) * (pz - a[2]) - i128(b[2] - a[2]) * (py - a[1]);
  if (w != 0) return w > 0;
  if (b[2] != a[2]) return b[2] < a[2];
  return b[1] > a[1];
}

// The columns (k: z) whose centre rays can cross a triangle spanning snapped z in [zlo, zhi], within the grid.
inline std::pair<int64_t, int64_t> crossing_rows(int64_t zlo, int64_t zhi, uint32_t nz) {
  return {std::max<int64_t>(0, ceil_div(zlo - kHalf, kOne)), std::min<int64_t>(nz - 1, floor_div(zhi - kHalf, kOne))};
}

// Every crossing of triangle ABC with the rays along x through the voxel-column centres of the window's z; calls
// emit(y, z, x, front) for each (x along the ray, in voxels), front when the triangle's normal has a positive x
// component.
template <class Emit>
void crossings_of(const std::array<int64_t, 3>& A, const std::array<int64_t, 3>& B, const std::array<int64_t, 3>& C,
                  const GridPlacement& gp, Emit&& emit, const ZWindow& win = {}) {
  const i128 area = i128(B[1] - A[1]) * (C[2] - A[2]) - i128(B[2] - A[2]) * (C[1] - A[1]);
  if (area == 0) return;  // parallel to the rays: no perturbed ray meets it
  const bool front = area > 0;
  const int64_t ylo = std::min({A[1], B[1], C[1]}), yhi = std::max({A[1], B[1], C[1]});
  const int64_t zlo = std::min({A[2], B[2], C[2]}), zhi = std::max({A[2], B[2], C[2]});
  // Columns whose centre is within the bounds (a perturbed ray is never outside them when its centre is).
  const int64_t j0 = std::max<int64_t>(0, ceil_div(ylo - kHalf, kOne));
  const int64_t j1 = std::min<int64_t>(gp.dims[1] - 1, floor_div(yhi - kHalf, kOne));
  auto [k0, k1] = crossing_rows(zlo, zhi, gp.dims[2]);
  k0 = std::max(k0, win.z0);
  k1 = std::min(k1, win.z1);
  for (int64_t k = k0; k <= k1; ++k) {
    const int64_t pz = k * kOne + kHalf;
    for (int64_t j = j0; j <= j1; ++j) {
      const int64_t py = j * kOne + kHalf;
      i128 wa, wb, wc;
      if (positive_side(B, C, py, pz, wa) != front) continue;
      if (positive_side(C, A, py, pz, wb) != front) continue;
      if (positive_side(A, B, py, pz, wc) != front) continue;
      const double da = double(wa), db = double(wb), dc = double(wc);
      const double x = (da * double(A[0]) + db * double(B[0]) + dc * double(C[0])) / (da + db + dc);
      emit(uint32_t(j), uint32_t(k), std::ldexp(x, -kFrac), front);
    }
  }
}

// The candidate voxel range of an axis for coordinates [l, r] (a voxel's cube grown by kGrow may meet them).
constexpr double kVoxelSlack = 2 * kGrow + 1e-9;
inline void voxel_range(double l, double r, uint32_t n, int64_t& i0, int64_t& i1) {
  i0 = std::max<int64_t>(0, int64_t(std::ceil(l - 1 - kVoxelSlack)));
  i1 = std::min<int64_t>(int64_t(n) - 1, int64_t(std::floor(r + kVoxelSlack)));
}

// The voxels of z whose grown cubes a triangle spanning [zlo, zhi] can meet.
inline std::pair<int64_t, int64_t> voxel_rows(double zlo, double zhi, uint32_t nz) {
  int64_t i0, i1;
  voxel_range(zlo, zhi, nz, i0, i1);
  return {i0, i1};
}

// The bounding box of the part of triangle ABC within z in [zl, zh] (lo > hi on every axis when there is none).
void clipped_bounds(const Eigen::Vector3d& A, const Eigen::Vector3d& B, const Eigen::Vector3d& C, double zl, double zh,
                    Eigen::Vector3d& lo, Eigen::Vector3d& hi);

// Calls fn(x, y, z) for every voxel of the grid, z in the window, whose cube grown by kGrow meets triangle t (the
// separating-axis test triangle_meets_cube). Walks the columns along the triangle's dominant normal axis, so the work
// is proportional to its area, not its bounding box; a window first clips the triangle to its z range (widened by
// more than the growth), which only drops candidates that cannot meet.
template <class Fn>
void triangle_voxels(const GridMesh& gm, const Mesh& m, size_t t, const GridPlacement& gp, Fn&& fn,
                     const ZWindow& win = {}) {
  const Eigen::Vector3d& A = gm.g[m.triangles[t][0]];
  const Eigen::Vector3d& B = gm.g[m.triangles[t][1]];
  const Eigen::Vector3d& C = gm.g[m.triangles[t][2]];
  Eigen::Vector3d lo = A.cwiseMin(B).cwiseMin(C), hi = A.cwiseMax(B).cwiseMax(C);
  if (!win.all()) {
    Eigen::Vector3d clo, chi;
    clipped_bounds(A, B, C, double(win.z0) - 2 * kVoxelSlack, double(win.z1) + 1 + 2 * kVoxelSlack, clo, chi);
    if (!(clo[2] <= chi[2])) return;
    lo = lo.cwiseMax(clo);
    hi = hi.cwiseMin(chi);
  }
  const Eigen::Vector3d n = (B - A).cross(C - A);
  int a = 0;
  if (std::abs(n[1]) > std::abs(n[a])) a = 1;
  if (std::abs(n[2]) > std::abs(n[a])) a = 2;
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  const double h = 0.5 + kGrow;
  auto range = [&](double l, double r, int axis, int64_t& i0, int64_t& i1) {
    voxel_range(l, r, gp.dims[axis], i0, i1);
    if (axis == 2) {
      i0 = std::max(i0, win.z0);
      i1 = std::min(i1, win.z1);
    }
  };
  int64_t u0, u1, v0, v1;
  range(lo[u], hi[u], u, u0, u1);
  range(lo[v], hi[v], v, v0, v1);
  const double d = n.dot(A);
  const bool flat = n[a] == 0;  // snapped to a degenerate triangle: walk its (tiny) bounding box
  int idx[3];
  for (int64_t iv = v0; iv <= v1; ++iv)
    for (int64_t iu = u0; iu <= u1; ++iu) {
      double amin = lo[a], amax = hi[a];
      if (!flat) {
        double pmin = HUGE_VAL, pmax = -HUGE_VAL;
        for (double pu : {iu - kGrow, iu + 1 + kGrow})
          for (double pv : {iv - kGrow, iv + 1 + kGrow}) {
            const double pa = (d - n[u] * pu - n[v] * pv) / n[a];
            pmin = std::min(pmin, pa);
            pmax = std::max(pmax, pa);
          }
        amin = std::max(amin, pmin);
        amax = std::min(amax, pmax);
        if (amin > amax + kVoxelSlack) continue;
      }
      int64_t a0, a1;
      range(amin, amax, a, a0, a1);
      idx[u] = int(iu);
      idx[v] = int(iv);
      for (int64_t ia = a0; ia <= a1; ++ia) {
        idx[a] = int(ia);
        const Eigen::Vector3d c(idx[0] + 0.5, idx[1] + 0.5, idx[2] + 0.5);
        if (triangle_meets_cube(c, h, A, B, C)) fn(uint32_t(idx[0]), uint32_t(idx[1]), uint32_t(idx[2]));
      }
    }
}

// The voxels of z in the window whose cube, grown by kGrow, holds point p (grid coordinates): a point cloud's
// surface. fn(x, y, z) for each.
template <class Fn>
void point_voxels(const Eigen::Vector3d& g, const GridPlacement& gp, Fn&& fn, const ZWindow& win = {}) {
  int64_t i0[3], i1[3];
  for (int a = 0; a < 3; ++a) {
    i0[a] = std::max<int64_t>(0, int64_t(std::floor(g[a] - kGrow)));
    i1[a] = std::min<int64_t>(int64_t(gp.dims[a]) - 1, int64_t(std::floor(g[a] + kGrow)));
  }
  i0[2] = std::max(i0[2], win.z0);
  i1[2] = std::min(i1[2], win.z1);
  for (int64_t z = i0[2]; z <= i1[2]; ++z)
    for (int64_t y = i0[1]; y <= i1[1]; ++y)
      for (int64_t x = i0[0]; x <= i1[0]; ++x) fn(uint32_t(x), uint32_t(y), uint32_t(z));
}

// [begin, end) ranges splitting n items into at most 16 per worker.
std::vector<std::pair<size_t, size_t>> chunks(size_t n, unsigned workers);

}  // namespace voxcd::detail
