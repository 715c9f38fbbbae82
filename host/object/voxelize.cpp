#include "voxcd/host/object/voxelize.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "voxcd/ref/fast/thread_pool.h"
#include "voxcd/host/object/detail/solid.h"
#include "voxcd/host/object/detail/winding.h"

namespace voxcd {

namespace {

using i128 = __int128;

// Vertices are snapped to 2^-kFrac voxel in grid coordinates, so that the parity predicates below are exact
// integer arithmetic. Snapping moves a vertex by at most 2^-(kFrac+1) per axis, the surface by at most
// sqrt(3) * 2^-(kFrac+1) < 2^-kFrac; surface voxels are grown by kGrow > that, so they stay conservative for
// the mesh as given.
constexpr int kFrac = 20;
constexpr int64_t kOne = int64_t{1} << kFrac;
constexpr int64_t kHalf = kOne / 2;
constexpr double kGrow = 1.0 / (1 << 19);
// Bound on the far caps' winding number below which the near caps' exact part stands for the whole.
constexpr double kNearEnough = 0.02;

struct GridMesh {
  std::vector<std::array<int64_t, 3>> q;  // snapped grid coordinates, kFrac fraction bits
  std::vector<Eigen::Vector3d> g;         // the same values as doubles, in voxels
};

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

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

// Edge function of the directed edge a->b at p in the (y, z) projection; its sign says on which side p is.
// Zero is resolved by simulation of simplicity: p is taken at (p_y + e, p_z + e^2) for an infinitesimal e, so a
// ray through an edge or a vertex belongs to exactly one side, and both triangles of an edge agree on it.
inline bool positive_side(const std::array<int64_t, 3>& a, const std::array<int64_t, 3>& b, int64_t py,
                          int64_t pz, i128& w) {
  w = i128(b[1] - a[1]) * (pz - a[2]) - i128(b[2] - a[2]) * (py - a[1]);
  if (w != 0) return w > 0;
  if (b[2] != a[2]) return b[2] < a[2];
  return b[1] > a[1];
}

struct Crossing {
  uint32_t col;  // y + ny * z
  double x;      // along the ray, in voxels
};

struct SignedCrossing {
  uint32_t col;  // y + ny * z
  int32_t sign;  // +1 where the ray leaves the side the normal points away from (normal x > 0), times the weight
  double x;      // along the ray, in voxels
};

// Every crossing of triangle ABC with the rays along x through the voxel-column centres; calls
// emit(column, x, front) for each, front when the triangle's normal has a positive x component.
template <class Emit>
void crossings_of(const std::array<int64_t, 3>& A, const std::array<int64_t, 3>& B, const std::array<int64_t, 3>& C,
                  const GridPlacement& gp, Emit&& emit) {
  const i128 area = i128(B[1] - A[1]) * (C[2] - A[2]) - i128(B[2] - A[2]) * (C[1] - A[1]);
  if (area == 0) return;  // parallel to the rays: no perturbed ray meets it
  const bool front = area > 0;
  const int64_t ylo = std::min({A[1], B[1], C[1]}), yhi = std::max({A[1], B[1], C[1]});
  const int64_t zlo = std::min({A[2], B[2], C[2]}), zhi = std::max({A[2], B[2], C[2]});
  // Columns whose centre is within the bounds (a perturbed ray is never outside them when its centre is).
  const int64_t j0 = std::max<int64_t>(0, ceil_div(ylo - kHalf, kOne));
  const int64_t j1 = std::min<int64_t>(gp.dims[1] - 1, floor_div(yhi - kHalf, kOne));
  const int64_t k0 = std::max<int64_t>(0, ceil_div(zlo - kHalf, kOne));
  const int64_t k1 = std::min<int64_t>(gp.dims[2] - 1, floor_div(zhi - kHalf, kOne));
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
      emit(uint32_t(j + int64_t(gp.dims[1]) * k), std::ldexp(x, -kFrac), front);
    }
  }
}

// Every crossing of triangle t with the rays along x through the voxel-column centres.
void triangle_crossings(const GridMesh& gm, const Mesh& m, size_t t, const GridPlacement& gp,
                        std::vector<Crossing>& out) {
  crossings_of(gm.q[m.triangles[t][0]], gm.q[m.triangles[t][1]], gm.q[m.triangles[t][2]], gp,
               [&](uint32_t col, double x, bool) { out.push_back({col, x}); });
}

// Calls fn(x, y, z) for every voxel of the grid whose cube grown by kGrow meets triangle t. Walks the columns
// along the triangle's dominant normal axis, so the work is proportional to its area, not its bounding box.
template <class Fn>
void triangle_voxels(const GridMesh& gm, const Mesh& m, size_t t, const GridPlacement& gp, Fn&& fn) {
  const Eigen::Vector3d& A = gm.g[m.triangles[t][0]];
  const Eigen::Vector3d& B = gm.g[m.triangles[t][1]];
  const Eigen::Vector3d& C = gm.g[m.triangles[t][2]];
  const Eigen::Vector3d lo = A.cwiseMin(B).cwiseMin(C), hi = A.cwiseMax(B).cwiseMax(C);
  const Eigen::Vector3d n = (B - A).cross(C - A);
  int a = 0;
  if (std::abs(n[1]) > std::abs(n[a])) a = 1;
  if (std::abs(n[2]) > std::abs(n[a])) a = 2;
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  const double h = 0.5 + kGrow;
  const double slack = 2 * kGrow + 1e-9;
  auto range = [&](double l, double r, int axis, int64_t& i0, int64_t& i1) {
    i0 = std::max<int64_t>(0, int64_t(std::ceil(l - 1 - slack)));
    i1 = std::min<int64_t>(int64_t(gp.dims[axis]) - 1, int64_t(std::floor(r + slack)));
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
        if (amin > amax + slack) continue;
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

std::vector<std::pair<size_t, size_t>> chunks(size_t n, unsigned workers) {
  const size_t parts = std::max<size_t>(1, std::min<size_t>(n, size_t(workers) * 16));
  std::vector<std::pair<size_t, size_t>> r;
  for (size_t p = 0; p < parts; ++p) r.emplace_back(n * p / parts, n * (p + 1) / parts);
  return r;
}

std::vector<uint64_t> surface_bits_grid(const GridMesh& gm, const Mesh& m, const GridPlacement& gp,
                                        ThreadPool& pool) {
  std::vector<uint64_t> bits((gp.size() + 63) / 64, 0);
  const auto parts = chunks(m.size(), pool.size());
  const uint64_t nx = gp.dims[0], nxy = nx * gp.dims[1];
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t t = parts[p].first; t < parts[p].second; ++t)
      triangle_voxels(gm, m, t, gp, [&](uint32_t x, uint32_t y, uint32_t z) {
        const uint64_t i = x + nx * y + nxy * z;
        uint64_t* w = &bits[i >> 6];
        const uint64_t bit = uint64_t{1} << (i & 63);
        if (!(__atomic_load_n(w, __ATOMIC_RELAXED) & bit)) __atomic_fetch_or(w, bit, __ATOMIC_RELAXED);
      });
  });
  return bits;
}

// 32 bits to the even bits of 64.
uint64_t spread(uint64_t x) {
  x &= 0xffffffffull;
  x = (x | (x << 16)) & 0x0000ffff0000ffffull;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffull;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0full;
  x = (x | (x << 2)) & 0x3333333333333333ull;
  x = (x | (x << 1)) & 0x5555555555555555ull;
  return x;
}

// Sets voxels [b, e) of an all-empty-or-interior word array to interior.
void fill_interior(std::vector<uint64_t>& w, uint64_t b, uint64_t e) {
  constexpr uint64_t kInt = 0xaaaaaaaaaaaaaaaaull;
  while (b < e) {
    const uint64_t wi = b >> 5, first = b & 31;
    const uint64_t last = std::min<uint64_t>(32, first + (e - b));
    const uint64_t lo_mask = first == 0 ? ~uint64_t{0} : ~((uint64_t{1} << (2 * first)) - 1);
    const uint64_t hi_mask = last == 32 ? ~uint64_t{0} : ((uint64_t{1} << (2 * last)) - 1);
    w[wi] |= kInt & lo_mask & hi_mask;
    b += last - first;
  }
}

// Bit i set for every voxel whose cube, grown by kGrow, holds a vertex (a point cloud's surface).
std::vector<uint64_t> point_bits(const Mesh& m, const GridPlacement& gp) {
  std::vector<uint64_t> bits((gp.size() + 63) / 64, 0);
  const uint64_t nx = gp.dims[0], nxy = nx * gp.dims[1];
  for (const Eigen::Vector3d& p : m.vertices) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d g = (p - gp.origin) / gp.voxel;
    int64_t i0[3], i1[3];
    for (int a = 0; a < 3; ++a) {
      i0[a] = std::max<int64_t>(0, int64_t(std::floor(g[a] - kGrow)));
      i1[a] = std::min<int64_t>(int64_t(gp.dims[a]) - 1, int64_t(std::floor(g[a] + kGrow)));
    }
    for (int64_t z = i0[2]; z <= i1[2]; ++z)
      for (int64_t y = i0[1]; y <= i1[1]; ++y)
        for (int64_t x = i0[0]; x <= i1[0]; ++x) {
          const uint64_t i = uint64_t(x) + nx * uint64_t(y) + nxy * uint64_t(z);
          bits[i >> 6] |= uint64_t{1} << (i & 63);
        }
  }
  return bits;
}

// Surface voxels override whatever the fill gave.
void apply_surface(Voxmap& vm, const std::vector<uint64_t>& sb) {
  auto& w = vm.words();
  for (size_t i = 0; i < w.size(); ++i) {
    const uint64_t s = spread(sb[i >> 1] >> (32 * (i & 1)));
    w[i] = (w[i] & ~(s | (s << 1))) | s;
  }
}

// Signed crossings of the closed chain with every column ray, bucketed by column and sorted along it: column c's
// crossings are xs[start[c], start[c + 1]), (x, sign).
struct ColumnCrossings {
  std::vector<uint32_t> start;
  std::vector<std::pair<double, int32_t>> xs;
};

ColumnCrossings column_crossings(const std::vector<std::array<uint32_t, 3>>& solid,
                                 const std::vector<detail::ChainTriangle>& caps, const GridMesh& gm,
                                 const GridPlacement& gp, ThreadPool& pool) {
  const size_t n_items = solid.size() + caps.size();
  const auto parts = chunks(n_items, pool.size());
  std::vector<std::vector<SignedCrossing>> found(parts.size());
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t i = parts[p].first; i < parts[p].second; ++i) {
      if (i < solid.size()) {
        const auto& t = solid[i];
        crossings_of(gm.q[t[0]], gm.q[t[1]], gm.q[t[2]], gp, [&](uint32_t col, double x, bool front) {
          found[p].push_back({col, front ? 1 : -1, x});
        });
      } else {
        const auto& c = caps[i - solid.size()];
        crossings_of(c.a, c.b, c.c, gp, [&](uint32_t col, double x, bool front) {
          found[p].push_back({col, (front ? -1 : 1) * c.weight, x});
        });
      }
    }
  });
  const size_t cols = size_t(gp.dims[1]) * gp.dims[2];
  ColumnCrossings cc;
  cc.start.assign(cols + 1, 0);
  for (const auto& f : found)
    for (const SignedCrossing& c : f) ++cc.start[c.col + 1];
  for (size_t c = 0; c < cols; ++c) cc.start[c + 1] += cc.start[c];
  cc.xs.resize(cc.start[cols]);
  std::vector<uint32_t> at(cc.start.begin(), cc.start.end() - 1);
  for (const auto& f : found)
    for (const SignedCrossing& c : f) cc.xs[at[c.col]++] = {c.x, c.sign};
  found.clear();
  found.shrink_to_fit();
  const size_t sorts = std::min<size_t>(cols, 64);
  pool.parallel_for(sorts, [&](size_t part) {
    for (size_t c = cols * part / sorts; c < cols * (part + 1) / sorts; ++c)
      std::sort(cc.xs.begin() + cc.start[c], cc.xs.begin() + cc.start[c + 1]);
  });
  return cc;
}

// The integer part W (the chain's winding number: the signed crossings beyond the centre) fills every voxel where
// W >= 1; W is constant between crossings.
void fill_by_crossings(const Mesh& mesh, const GridPlacement& gp, const ColumnCrossings& cc, Voxmap& vm) {
  const uint64_t nx = gp.dims[0];
  const size_t cols = cc.start.size() - 1;
  for (size_t c = 0; c < cols; ++c) {
    const auto* b = cc.xs.data() + cc.start[c];
    const auto* e = cc.xs.data() + cc.start[c + 1];
    if (b == e) continue;
    int64_t prefix = 0;  // signs of the crossings at or before the current one; W = -prefix after it
    for (const auto* p = b; p < e; ++p) {
      prefix += p->second;
      if (-prefix < 1 || p + 1 == e) continue;
      // Voxels whose centre lies in [p->first, next crossing).
      const double lo_i = std::max(0.0, std::ceil(p->first - 0.5));
      const double hi_i = std::min(double(nx), std::ceil(p[1].first - 0.5));
      if (lo_i >= hi_i) continue;
      const uint64_t base = uint64_t(c) * nx;
      fill_interior(vm.words(), base + uint64_t(lo_i), base + uint64_t(hi_i));
    }
    if (prefix != 0)
      throw std::logic_error(mesh.name + ": the closed chain's crossings along column (y " +
                             std::to_string(c % gp.dims[1]) + ", z " + std::to_string(c / gp.dims[1]) +
                             ") do not sum to zero");
  }
}

// The caps' winding number moves W only near the holes: voxels where it could reach kUncertainLow are evaluated one
// by one (W + caps >= 1/2), every other voxel keeps W's answer. Voxels set in *skip are left as they are.
void refine_near_holes(const std::vector<detail::ChainTriangle>& caps, const GridPlacement& gp,
                       const ColumnCrossings& cc, ThreadPool& pool, const std::vector<uint64_t>* skip, Voxmap& vm,
                       VoxelizeReport& rep) {
  const detail::CapField field(caps, kFrac);
  constexpr uint32_t kBlock = 8;
  const uint32_t bx = (gp.dims[0] + kBlock - 1) / kBlock, by = (gp.dims[1] + kBlock - 1) / kBlock,
                 bz = (gp.dims[2] + kBlock - 1) / kBlock;
  struct Change {
    uint64_t index;
    bool inside;
  };
  std::vector<std::vector<Change>> changes(size_t(bx) * by * bz);
  std::vector<uint64_t> evaluated(changes.size(), 0), uncertain(changes.size(), 0);
  pool.parallel_for(changes.size(), [&](size_t blk) {
    const uint32_t x0 = uint32_t(blk % bx) * kBlock, y0 = uint32_t(blk / bx % by) * kBlock,
                   z0 = uint32_t(blk / (size_t(bx) * by)) * kBlock;
    const std::array<uint32_t, 3> lo = {x0, y0, z0};
    const std::array<uint32_t, 3> hi = {std::min(x0 + kBlock, gp.dims[0]), std::min(y0 + kBlock, gp.dims[1]),
                                        std::min(z0 + kBlock, gp.dims[2])};
    field.uncertain_voxels(lo, hi, kUncertainLow, [&](uint32_t x, uint32_t y, uint32_t z, double near, double bound) {
      const uint64_t i = vm.index(x, y, z);
      if (skip && ((*skip)[i >> 6] >> (i & 63)) & 1) return;
      ++evaluated[blk];
      const size_t c = size_t(y) + size_t(gp.dims[1]) * z;
      const double cx = x + 0.5;
      int64_t prefix = 0;
      for (uint32_t k = cc.start[c]; k < cc.start[c + 1] && cc.xs[k].first <= cx; ++k) prefix += cc.xs[k].second;
      // The near caps' exact part with the bound on the rest decides, unless 1/2 lies within the bound (or the
      // bound is too loose to say how certain the voxel is): then the whole field is evaluated.
      double w = double(-prefix) + near;
      if (!(bound <= kNearEnough && std::abs(w - 0.5) > bound))
        w = double(-prefix) + field.value(Eigen::Vector3d(cx, y + 0.5, z + 0.5));
      if (w >= kUncertainLow && w <= kUncertainHigh) ++uncertain[blk];
      const bool inside = w >= 0.5;
      if (inside != (vm.at(i) == kInterior)) changes[blk].push_back({i, inside});
    });
  });
  for (size_t b = 0; b < changes.size(); ++b) {
    for (const Change& ch : changes[b]) vm.set(ch.index, ch.inside ? kInterior : kEmpty);
    rep.evaluated += evaluated[b];
    rep.uncertain += uncertain[b];
  }
}

// Steps 1-4 of the voxeliser on grid gp: every voxel whose centre has a generalized winding number of the non-sheet
// triangles of at least 1/2 becomes interior in vm (all empty before). Step 4 leaves out the voxels set in *skip
// (the surface voxels, which voxelize overrides anyway); with skip null every voxel is decided.
void fill_solid(const Mesh& mesh, const GridMesh& gm, const GridPlacement& gp, ThreadPool& pool,
                const std::vector<uint64_t>* skip, Voxmap& vm, VoxelizeReport& rep) {
  // 1. The closed chain: the triangles that bound the solid (sheets excluded) minus the caps of their boundary.
  std::vector<std::array<uint32_t, 3>> solid_copy;
  if (!mesh.sheet.empty())
    for (size_t t = 0; t < mesh.size(); ++t)
      if (!mesh.is_sheet(t)) solid_copy.push_back(mesh.triangles[t]);
  const std::vector<std::array<uint32_t, 3>>& solid = mesh.sheet.empty() ? mesh.triangles : solid_copy;
  const std::vector<detail::ChainTriangle> caps = detail::boundary_caps(gm.q, solid, kFrac);
  // 2. and 3.: the chain's crossings with every column, and the fill they give.
  const ColumnCrossings cc = column_crossings(solid, caps, gm, gp, pool);
  fill_by_crossings(mesh, gp, cc, vm);
  // 4. Near the holes.
  if (!caps.empty()) refine_near_holes(caps, gp, cc, pool, skip, vm, rep);
}

}  // namespace

Voxmap::Voxmap(const GridPlacement& g) : grid_(g), words_((g.size() + 31) / 32, 0) {}

std::array<uint64_t, 4> Voxmap::counts() const {
  std::array<uint64_t, 4> c = {0, 0, 0, 0};
  constexpr uint64_t kLo = 0x5555555555555555ull;
  for (uint64_t w : words_) {
    const uint64_t lo = w & kLo, hi = (w >> 1) & kLo;
    c[kSurface] += __builtin_popcountll(lo & ~hi);
    c[kInterior] += __builtin_popcountll(hi & ~lo);
    c[kReserved] += __builtin_popcountll(lo & hi);
  }
  c[kEmpty] = size() - c[kSurface] - c[kInterior] - c[kReserved];
  return c;
}

std::vector<uint64_t> Voxmap::device_words(int memw) const {
  if (memw < 2 || memw > 64 || (memw & (memw - 1)))
    throw std::invalid_argument("MEMW must be a power of two in 2..64, got " + std::to_string(memw));
  if (memw == 64) return words_;
  const uint64_t per = uint64_t(memw) / 2;
  std::vector<uint64_t> out((size() + per - 1) / per, 0);
  for (uint64_t i = 0; i < size(); ++i) out[i / per] |= uint64_t(at(i)) << (2 * (i % per));
  return out;
}

double voxel_for_resolution(const Mesh& mesh, uint32_t resolution) {
  if (resolution < kMinVoxelsAcross)
    throw MeshError(mesh.name + ": a resolution of " + std::to_string(resolution) + " voxels is too coarse; at least " +
                    std::to_string(kMinVoxelsAcross) + " voxels must span the longest side");
  if (mesh.triangles.empty() && mesh.vertices.empty()) throw MeshError(mesh.name + ": the mesh has no triangles and no points");
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  const double longest = (hi - lo).maxCoeff();
  if (!std::isfinite(longest)) throw MeshError(mesh.name + ": vertex coordinates are not finite");
  if (!(longest > 0)) throw MeshError(mesh.name + ": the model has no extent (all its points coincide)");
  return longest / resolution;
}

GridPlacement place_grid(const Mesh& mesh, const VoxelizeOptions& opt) {
  if (mesh.triangles.empty() && mesh.vertices.empty())
    throw MeshError(mesh.name + ": the mesh has no triangles and no points");
  const double voxel = opt.resolution ? voxel_for_resolution(mesh, opt.resolution) : opt.voxel;
  if (!(std::isfinite(voxel) && voxel > 0))
    throw MeshError(mesh.name + ": the voxel size must be a positive finite number, got " + std::to_string(voxel));
  for (int a = 0; a < 3; ++a)
    if (!(opt.shift[a] >= 1.0 / 1024 && opt.shift[a] <= 1))
      throw MeshError(mesh.name + ": grid shift components must lie in [1/1024, 1], got " + std::to_string(opt.shift[a]));
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  if (!lo.allFinite() || !hi.allFinite()) throw MeshError(mesh.name + ": vertex coordinates are not finite");
  const double longest = (hi - lo).maxCoeff();
  if (!(longest >= kMinVoxelsAcross * voxel)) {
    std::ostringstream s;
    s.precision(9);
    if (!(longest > 0)) {
      s << mesh.name << ": the model has no extent (all its points coincide)";
    } else {
      s << mesh.name << ": voxel size " << voxel << " leaves " << longest / voxel
        << " voxels along the model's longest side (" << longest << "); at least " << kMinVoxelsAcross
        << " are needed: use a voxel size of at most " << longest / kMinVoxelsAcross << " (or --resolution)";
    }
    throw MeshError(s.str());
  }
  GridPlacement g;
  g.voxel = voxel;
  g.origin = lo - voxel * (Eigen::Vector3d::Ones() + opt.shift);
  bool too_big = false;
  double dd[3];
  for (int a = 0; a < 3; ++a) {
    const double ghi = (hi[a] - g.origin[a]) / voxel;
    dd[a] = std::floor(ghi + 4 * kGrow) + 2;
    if (!(dd[a] <= opt.max_dim)) too_big = true;
  }
  if (too_big) {
    std::ostringstream s;
    s << mesh.name << ": at voxel size " << voxel << " the voxmap would be " << dd[0] << "x" << dd[1] << "x"
      << dd[2] << " voxels; at most " << opt.max_dim << " per axis are allowed (use a voxel size of at least "
      << longest / (opt.max_dim - 4) << ")";
    throw MeshError(s.str());
  }
  for (int a = 0; a < 3; ++a) g.dims[a] = uint32_t(dd[a]);
  return g;
}

std::vector<uint64_t> surface_bits(const Mesh& mesh, const GridPlacement& g, unsigned threads) {
  if (mesh.points_only()) return point_bits(mesh, g);
  ThreadPool pool(threads);
  return surface_bits_grid(to_grid(mesh, g), mesh, g, pool);
}

void for_each_overlap(const Mesh& mesh, const GridPlacement& g, size_t t0, size_t t1,
                      const std::function<void(size_t, uint32_t, uint32_t, uint32_t)>& fn) {
  const GridMesh gm = to_grid(mesh, g);
  for (size_t t = t0; t < t1 && t < mesh.size(); ++t)
    triangle_voxels(gm, mesh, t, g, [&](uint32_t x, uint32_t y, uint32_t z) { fn(t, x, y, z); });
}

Voxmap voxelize_raycast(const Mesh& mesh, const VoxelizeOptions& opt) {
  const GridPlacement gp = place_grid(mesh, opt);
  const GridMesh gm = to_grid(mesh, gp);
  ThreadPool pool(opt.threads);
  Voxmap vm(gp);

  // 1. Crossings of every triangle with every column ray, gathered per chunk, then bucketed by column.
  const auto parts = chunks(mesh.size(), pool.size());
  std::vector<std::vector<Crossing>> found(parts.size());
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t t = parts[p].first; t < parts[p].second; ++t) triangle_crossings(gm, mesh, t, gp, found[p]);
  });
  const size_t cols = size_t(gp.dims[1]) * gp.dims[2];
  std::vector<uint32_t> start(cols + 1, 0);
  for (const auto& f : found)
    for (const Crossing& c : f) ++start[c.col + 1];
  for (size_t c = 0; c < cols; ++c) start[c + 1] += start[c];
  std::vector<double> xs(start[cols]);
  {
    std::vector<uint32_t> at(start.begin(), start.end() - 1);
    for (const auto& f : found)
      for (const Crossing& c : f) xs[at[c.col]++] = c.x;
  }
  found.clear();
  found.shrink_to_fit();

  // 2. Parity fill: a voxel whose centre has an odd number of crossings before it is inside.
  const uint64_t nx = gp.dims[0];
  for (size_t c = 0; c < cols; ++c) {
    double* b = xs.data() + start[c];
    double* e = xs.data() + start[c + 1];
    if (b == e) continue;
    std::sort(b, e);
    if ((e - b) % 2)
      throw MeshError(mesh.name + ": the ray through column (y " + std::to_string(c % gp.dims[1]) + ", z " +
                      std::to_string(c / gp.dims[1]) + ") crosses the surface an odd number of times");
    for (double* p = b; p < e; p += 2) {
      const double lo_i = std::max(0.0, std::floor(p[0] - 0.5) + 1);
      const double hi_i = std::min(double(nx) - 1, std::ceil(p[1] - 0.5) - 1);
      if (lo_i > hi_i) continue;
      const uint64_t base = uint64_t(c) * nx;
      fill_interior(vm.words(), base + uint64_t(lo_i), base + uint64_t(hi_i) + 1);
    }
  }
  xs.clear();
  xs.shrink_to_fit();

  // 3. Surface voxels override.
  apply_surface(vm, surface_bits_grid(gm, mesh, gp, pool));
  return vm;
}

Voxmap voxelize(const Mesh& mesh, const VoxelizeOptions& opt, VoxelizeReport* report) {
  const GridPlacement gp = place_grid(mesh, opt);
  Voxmap vm(gp);
  VoxelizeReport rep;
  if (mesh.points_only()) {
    apply_surface(vm, point_bits(mesh, gp));
    if (report) *report = rep;
    return vm;
  }
  const GridMesh gm = to_grid(mesh, gp);
  ThreadPool pool(opt.threads);
  const std::vector<uint64_t> sb = surface_bits_grid(gm, mesh, gp, pool);
  fill_solid(mesh, gm, gp, pool, &sb, vm, rep);
  // 5. Surface voxels override.
  apply_surface(vm, sb);
  if (report) *report = rep;
  return vm;
}

namespace detail {

std::vector<uint64_t> solid_bits(const Mesh& mesh, const GridPlacement& g, unsigned threads,
                                 std::vector<uint64_t>* surface) {
  if (mesh.points_only()) throw MeshError(mesh.name + ": a point cloud encloses no solid");
  const GridMesh gm = to_grid(mesh, g);
  ThreadPool pool(threads);
  if (surface) *surface = surface_bits_grid(gm, mesh, g, pool);
  Voxmap vm(g);
  VoxelizeReport rep;
  fill_solid(mesh, gm, g, pool, nullptr, vm, rep);
  // Interior states (2) to bits.
  std::vector<uint64_t> bits((g.size() + 63) / 64, 0);
  const auto& w = vm.words();
  for (size_t i = 0; i < w.size(); ++i) {
    uint64_t x = (w[i] >> 1) & 0x5555555555555555ull;  // the high bit of each state
    // Compact the even bits into 32 bits.
    x = (x | (x >> 1)) & 0x3333333333333333ull;
    x = (x | (x >> 2)) & 0x0f0f0f0f0f0f0f0full;
    x = (x | (x >> 4)) & 0x00ff00ff00ff00ffull;
    x = (x | (x >> 8)) & 0x0000ffff0000ffffull;
    x = (x | (x >> 16)) & 0x00000000ffffffffull;
    bits[i >> 1] |= x << (32 * (i & 1));
  }
  return bits;
}

}  // namespace detail


bool triangle_meets_cube(const Eigen::Vector3d& c, double h, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             const Eigen::Vector3d& d) {
  const Eigen::Vector3d v0 = a - c, v1 = b - c, v2 = d - c;
  for (int i = 0; i < 3; ++i) {
    if (std::min({v0[i], v1[i], v2[i]}) > h || std::max({v0[i], v1[i], v2[i]}) < -h) return false;
  }
  const Eigen::Vector3d e[3] = {v1 - v0, v2 - v1, v0 - v2};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d axis = Eigen::Vector3d::Zero();
      axis[i] = 1;
      axis = axis.cross(e[k]);
      const double p0 = axis.dot(v0), p1 = axis.dot(v1), p2 = axis.dot(v2);
      const double r = h * axis.cwiseAbs().sum();
      if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
    }
  const Eigen::Vector3d n = e[0].cross(e[1]);
  return std::abs(n.dot(v0)) <= h * n.cwiseAbs().sum();
}

}  // namespace voxcd
