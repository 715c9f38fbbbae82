#include "voxcd/host/object/voxelize.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/host/object/detail/column_crossings.h"
#include "voxcd/host/object/detail/solid.h"
#include "voxcd/host/object/detail/voxel_geometry.h"

namespace voxcd {

namespace {

using detail::GridMesh;
using detail::to_grid;

struct Crossing {
  uint32_t col;  // y + ny * z
  double x;      // along the ray, in voxels
};

// Every crossing of triangle t with the rays along x through the voxel-column centres.
void triangle_crossings(const GridMesh& gm, const Mesh& m, size_t t, const GridPlacement& gp,
                        std::vector<Crossing>& out) {
  detail::crossings_of(gm.q[m.triangles[t][0]], gm.q[m.triangles[t][1]], gm.q[m.triangles[t][2]], gp,
                       [&](uint32_t y, uint32_t z, double x, bool) {
                         out.push_back({uint32_t(y + uint64_t(gp.dims[1]) * z), x});
                       });
}

std::vector<uint64_t> surface_bits_grid(const GridMesh& gm, const Mesh& m, const GridPlacement& gp,
                                        ThreadPool& pool) {
  std::vector<uint64_t> bits((gp.size() + 63) / 64, 0);
  const auto parts = detail::chunks(m.size(), pool.size());
  const uint64_t nx = gp.dims[0], nxy = nx * gp.dims[1];
  pool.parallel_for(parts.size(), [&](size_t p) {
    for (size_t t = parts[p].first; t < parts[p].second; ++t)
      detail::triangle_voxels(gm, m, t, gp, [&](uint32_t x, uint32_t y, uint32_t z) {
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
    detail::point_voxels((p - gp.origin) / gp.voxel, gp, [&](uint32_t x, uint32_t y, uint32_t z) {
      const uint64_t i = uint64_t(x) + nx * uint64_t(y) + nxy * uint64_t(z);
      bits[i >> 6] |= uint64_t{1} << (i & 63);
    });
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

// The caps' winding number moves W only near the holes: voxels where it could reach kUncertainLow are evaluated one
// by one (W + caps >= 1/2), every other voxel keeps W's answer. Voxels set in *skip are left as they are.
void refine_near_holes(const std::vector<detail::ChainTriangle>& caps, const GridPlacement& gp,
                       const detail::ColumnCrossings& cc, ThreadPool& pool, const std::vector<uint64_t>* skip,
                       Voxmap& vm, VoxelizeReport& rep) {
  const detail::CapField field(caps, detail::kFrac);
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
      const double w = detail::near_hole_winding(field, cc, x, y, z, near, bound);
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
  const detail::Chain chain = detail::closed_chain(mesh, gm);
  // 2. and 3.: the chain's crossings with every column, and the fill they give (W >= 1).
  const detail::ColumnCrossings cc = detail::column_crossings(chain, gm, gp, pool, detail::ZWindow{});
  const uint64_t nx = gp.dims[0];
  detail::walk_columns(mesh.name, gp, cc, [&](size_t c, uint64_t lo, uint64_t hi) {
    fill_interior(vm.words(), uint64_t(c) * nx + lo, uint64_t(c) * nx + hi);
  });
  // 4. Near the holes.
  if (!chain.caps.empty()) refine_near_holes(chain.caps, gp, cc, pool, skip, vm, rep);
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
    dd[a] = std::floor(ghi + 4 * detail::kGrow) + 2;
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
    detail::triangle_voxels(gm, mesh, t, g, [&](uint32_t x, uint32_t y, uint32_t z) { fn(t, x, y, z); });
}

Voxmap voxelize_raycast(const Mesh& mesh, const VoxelizeOptions& opt) {
  const GridPlacement gp = place_grid(mesh, opt);
  const GridMesh gm = to_grid(mesh, gp);
  ThreadPool pool(opt.threads);
  Voxmap vm(gp);

  // 1. Crossings of every triangle with every column ray, gathered per chunk, then bucketed by column.
  const auto parts = detail::chunks(mesh.size(), pool.size());
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
