// build_brick() and far_cell() (host/object/detail/brick_build.h). A brick that a triangle crosses is measured with a
// margin of one node on every side, so that the resolution test, which samples up to kResolvedDepth sub-cells inside
// the surface, reads the field of the brick's own level wherever it samples.
#include "voxcd/host/object/detail/brick_build.h"

#include <algorithm>
#include <cmath>

#include "voxcd/host/object/detail/cube_walk.h"
#include "voxcd/host/object/detail/unresolved.h"
#include "voxcd/host/object/sparse_field.h"

namespace voxcd::detail {

namespace {

// The voxeliser's growth of a surface voxel (host/object/voxelize.cpp): a sub-cell that a triangle meets within it is
// one the triangle crosses, as at level 0.
constexpr double kGrow = 1.0 / (1 << 19);

// The level-l nodes lo + (i, j, k), 0 <= i, j, k < n: the cell's 8 2^l + 1 nodes per axis and `margin` (0 or 1) more
// on each side (the resolution test samples up to one sub-cell outside the cell; a cell no triangle crosses needs
// none).
struct ExtGrid {
  int level = 0;
  uint32_t margin = 1;
  std::array<int64_t, 3> lo = {0, 0, 0};
  uint32_t n = 0;
  std::vector<int16_t> q;
  int16_t& at(uint64_t i, uint64_t j, uint64_t k) { return q[i + n * (j + uint64_t(n) * k)]; }
  int16_t at(uint64_t i, uint64_t j, uint64_t k) const { return q[i + n * (j + uint64_t(n) * k)]; }
};

ExtGrid measure_level(const BrickContext& ctx, const std::array<uint32_t, 3>& c, int level, uint32_t margin) {
  ExtGrid e;
  e.level = level;
  e.margin = margin;
  const int64_t side = int64_t{8} << level;
  e.n = uint32_t(side + 1 + 2 * margin);
  for (int a = 0; a < 3; ++a) e.lo[size_t(a)] = int64_t(c[size_t(a)]) * side - margin;
  e.q.assign(uint64_t(e.n) * e.n * e.n, int16_t(ctx.measure.qmax));
  const std::vector<uint64_t> fine = level > 0 ? ctx.signs.fine(level, e.lo, e.n) : std::vector<uint64_t>();
  const double h = std::ldexp(1.0, -level);
  for (uint32_t k = 0; k < e.n; ++k)
    for (uint32_t j = 0; j < e.n; ++j) {
      uint32_t prev = UINT32_MAX;
      for (uint32_t i = 0; i < e.n; ++i) {
        const std::array<int64_t, 3> G = {e.lo[0] + i, e.lo[1] + j, e.lo[2] + k};
        bool outside_grid = false;
        for (int a = 0; a < 3; ++a) outside_grid |= G[size_t(a)] < 0 || G[size_t(a)] > ctx.cells[size_t(a)] * side;
        if (outside_grid) continue;  // never sampled: samples are clamped to the grid
        const uint64_t b = i + e.n * (j + uint64_t(e.n) * k);
        const bool inside = level > 0 ? (fine[b >> 6] >> (b & 63)) & 1 : ctx.signs.inside(G[0], G[1], G[2]);
        const Eigen::Vector3d p(double(G[0]) * h, double(G[1]) * h, double(G[2]) * h);
        e.q[b] = node_value(ctx.measure, p, inside, prev);
      }
    }
  return e;
}

// The interpolant of e at grid point p, computed as DistanceField::sample computes it (p clamped to the grid, the
// cell below the point, the same order of operations), so that level 0 agrees with the dense field to the bit.
double sample(const ExtGrid& e, const std::array<uint32_t, 3>& dims, double step, const Eigen::Vector3d& p) {
  int64_t X[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double nd = double(dims[size_t(a)]);
    const double w = std::ldexp(std::clamp(p[a], 0.0, nd), e.level);
    const double cell = std::min(std::floor(w), std::ldexp(nd, e.level) - 1);
    X[a] = int64_t(cell) - e.lo[size_t(a)];
    f[a] = w - cell;
    if (X[a] < 0) X[a] = 0, f[a] = 0;  // beyond the margin (never, for the test's samples): its edge
    if (X[a] > int64_t(e.n) - 2) X[a] = int64_t(e.n) - 2, f[a] = 1;
  }
  double v[8];
  for (int k = 0; k < 8; ++k)
    v[k] = e.at(uint64_t(X[0] + (k & 1)), uint64_t(X[1] + (k >> 1 & 1)), uint64_t(X[2] + (k >> 2 & 1))) * step;
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double x00 = lerp(v[0], v[1], f[0]), x10 = lerp(v[2], v[3], f[0]);
  const double x01 = lerp(v[4], v[5], f[0]), x11 = lerp(v[6], v[7], f[0]);
  const double y0 = lerp(x00, x10, f[1]), y1 = lerp(x01, x11, f[1]);
  return lerp(y0, y1, f[2]);
}

// The depth test of a brick's sub-cell at x, a point of triangle t: the point delta inside along the inward normal
// reads at most 0, delta the depth or half the part's thickness there (the distance along the normal to the next
// triangle), whichever is less; so a part thinner than the depth is tested at its middle, where nodes that see its
// inside read below 0. A point of that kind within delta / 2 of the surface is not inside the part (x on a convex
// edge, whose inward normal runs along the next face) and passes.
template <class Field>
bool deep_resolved(const BrickContext& ctx, const Field& field, uint32_t t, const Eigen::Vector3d& x,
                   const Eigen::Vector3d& inward, double depth) {
  double l = HUGE_VAL;
  bool front = false;
  const uint32_t hit = ctx.measure.tree.first_hit(x, inward, t, 1e-9, &l, &front);
  const double delta = hit == UINT32_MAX ? depth : std::min(depth, l / 2);
  const Eigen::Vector3d y = x + delta * inward;
  if (ctx.measure.tree.closest(y, delta * delta / 4).found()) return true;
  return field(y) <= 0;
}

// What the resolution test says of a sub-cell (flags over the brick's sub-cells X + s (Y + s Z), s = 8 2^l).
constexpr uint8_t kCrossed = 1;     // a triangle crosses it
constexpr uint8_t kUnresolved = 2;  // and the field does not resolve it: refine, and at max_level lower its nodes
constexpr uint8_t kMembrane = 4;    // no triangle crosses it, yet its nodes hold both signs: the solid's boundary where
                                    // the winding number fills a hole; refine (the zero crossing moves with the nodes)
constexpr uint8_t kTooFarOut = 8;    // a triangle crosses it and the interpolant reads at most 0 at a point of it that
                                    // lies outside, farther than kOutsideTolerance from the surface: refine (a contact
                                    // there would lie that far out), never lower

// Flags the crossed sub-cells where the field puts the surface too far out (its zero set outside the object): at the
// sub-cell's centre, face centres and edge midpoints, a point where the interpolant is at most 0 that lies outside (by
// the nearest feature's pseudo-normal) farther than kOutsideTolerance from every triangle.
template <class Field>
void flag_too_far_out(const BrickContext& ctx, const Field& field, const Eigen::Vector3d& o, double h,
                     std::vector<uint8_t>& flag) {
  const uint64_t s = uint64_t{8} << int(std::lround(std::log2(1 / h)));
  const double far2 = kOutsideTolerance * kOutsideTolerance;
  for (uint64_t i = 0; i < flag.size(); ++i) {
    if (!(flag[i] & kCrossed) || (flag[i] & kUnresolved)) continue;
    const Eigen::Vector3d lo = o + Eigen::Vector3d(double(i % s), double(i / s % s), double(i / (s * s))) * h;
    for (int m = 0; m < 27; ++m) {
      const Eigen::Vector3d f(m % 3, m / 3 % 3, m / 9);
      if ((f.array() != 1).count() == 3) continue;  // the corners are nodes: the field is exact there
      const Eigen::Vector3d p = lo + f * (h / 2);
      if (field(p) > 0 || ctx.measure.tree.closest(p, far2).found()) continue;
      const Closest c = ctx.measure.tree.closest(p);
      if (!c.found() || ctx.mesh.is_sheet(c.triangle) || (p - c.point).dot(ctx.normals.at(c)) <= 0) continue;
      flag[i] |= kTooFarOut;
      break;
    }
  }
}

// Flags the sub-cells whose nodes hold both signs that no triangle crosses.
void flag_membranes(const ExtGrid& e, std::vector<uint8_t>& flag) {
  const uint64_t s = uint64_t{8} << e.level;
  for (uint64_t k = 0; k < s; ++k)
    for (uint64_t j = 0; j < s; ++j)
      for (uint64_t i = 0; i < s; ++i) {
        uint8_t& fl = flag[i + s * (j + s * k)];
        if (fl) continue;
        bool neg = false, pos = false;
        for (int m = 0; m < 8; ++m) {
          const int16_t q = e.at(i + e.margin + (m & 1), j + e.margin + (m >> 1 & 1), k + e.margin + (m >> 2 & 1));
          neg |= q < 0;
          pos |= q > 0;
        }
        if (neg && pos) fl = kMembrane;
      }
}

// The resolution test of every sub-cell of e's level; *sheet: a sheet's triangle crosses the cell.
std::vector<uint8_t> unresolved(const BrickContext& ctx, const std::array<uint32_t, 3>& c,
                                const std::vector<uint32_t>& tris, const ExtGrid& e, bool* sheet) {
  const int64_t s = int64_t{8} << e.level;
  const double h = std::ldexp(1.0, -e.level);
  const Eigen::Vector3d o(8.0 * c[0], 8.0 * c[1], 8.0 * c[2]);
  const double tolerance = kResolvedTolerance + ctx.step / 2, depth = kResolvedDepth * h;
  const auto field = [&](const Eigen::Vector3d& p) { return sample(e, ctx.g.dims, ctx.step, p); };
  std::vector<uint8_t> flag(uint64_t(s * s * s), 0);
  for (uint32_t t : tris) {
    const auto& tri = ctx.mesh.triangles[t];
    const Eigen::Vector3d& a = ctx.measure.gv[tri[0]];
    const Eigen::Vector3d& b = ctx.measure.gv[tri[1]];
    const Eigen::Vector3d& cc = ctx.measure.gv[tri[2]];
    const bool is_sheet = ctx.mesh.is_sheet(t);
    *sheet |= is_sheet;
    Eigen::Vector3d inward;
    const bool solid = !is_sheet && inward_normal(a, b, cc, inward);
    const auto deep = [&](const Eigen::Vector3d& x) { return deep_resolved(ctx, field, t, x, inward, depth); };
    for_each_cube_meeting(a - o, b - o, cc - o, h, kGrow, {0, 0, 0}, {s, s, s}, [&](int64_t i, int64_t j, int64_t k) {
      uint8_t& fl = flag[uint64_t(i + s * (j + s * k))];
      if (fl & kUnresolved) return;
      fl |= kCrossed;
      const Eigen::Vector3d lo = o + Eigen::Vector3d(double(i), double(j), double(k)) * h;
      if (!(solid && piece_resolved(field, piece_in_cube(a, b, cc, lo, h), tolerance, deep))) fl |= kUnresolved;
    });
  }
  flag_too_far_out(ctx, field, o, h, flag);
  flag_membranes(e, flag);
  return flag;
}

// Lowers the nodes of the flagged sub-cells to at most 0 and returns their keys.
std::vector<uint64_t> lower(ExtGrid& e, const std::vector<uint8_t>& flag, uint64_t t) {
  const uint64_t s = uint64_t{8} << e.level;
  std::vector<uint64_t> keys;
  for (uint64_t k = 0; k < s; ++k)
    for (uint64_t j = 0; j < s; ++j)
      for (uint64_t i = 0; i < s; ++i) {
        if (!(flag[i + s * (j + s * k)] & kUnresolved)) continue;
        keys.push_back(SparseDistanceField::conservative_key(t, uint32_t(i), uint32_t(j), uint32_t(k)));
        for (int m = 0; m < 8; ++m) {
          int16_t& q = e.at(i + e.margin + (m & 1), j + e.margin + (m >> 1 & 1), k + e.margin + (m >> 2 & 1));
          q = std::min<int16_t>(q, 0);
        }
      }
  return keys;
}

// The cell's brick from e (its margin dropped), or a uniform code when every node is qmax or every node qmin.
BrickResult finish(const ExtGrid& e, const NodeMeasure& m, std::vector<uint64_t> keys) {
  BrickResult r;
  const uint64_t n = e.n - 2 * e.margin, lo = e.margin;
  r.nodes.reserve(n * n * n);
  bool far = true, deep = true;
  for (uint64_t k = lo; k < lo + n; ++k)
    for (uint64_t j = lo; j < lo + n; ++j)
      for (uint64_t i = lo; i < lo + n; ++i) {
        const int16_t q = e.at(i, j, k);
        r.nodes.push_back(q);
        far = far && q == m.qmax;
        deep = deep && q == m.qmin;
      }
  if (far || deep) {
    r.code = far ? 0 : 1;
    r.nodes.clear();
    return r;
  }
  r.code = uint8_t(2 + e.level);
  r.conservative = std::move(keys);
  return r;
}

bool any_to_refine(const std::vector<uint8_t>& flags) {
  return std::any_of(flags.begin(), flags.end(),
                     [](uint8_t f) { return (f & (kUnresolved | kMembrane | kTooFarOut)) != 0; });
}

// A cell whose nodes all lie beyond the band at level l: each node clamped by its sign.
BrickResult clamped_brick(const BrickContext& ctx, const std::array<uint32_t, 3>& c, int level) {
  const uint32_t n = uint32_t(brick_side(level));
  const std::array<int64_t, 3> lo = {int64_t(c[0]) * (n - 1), int64_t(c[1]) * (n - 1), int64_t(c[2]) * (n - 1)};
  const std::vector<uint64_t> in = ctx.signs.fine(level, lo, n);
  BrickResult r;
  r.code = uint8_t(2 + level);
  r.nodes.resize(uint64_t(n) * n * n);
  for (uint64_t i = 0; i < r.nodes.size(); ++i)
    r.nodes[i] = int16_t((in[i >> 6] >> (i & 63)) & 1 ? ctx.measure.qmin : ctx.measure.qmax);
  return r;
}

}  // namespace

BrickResult build_brick(const BrickContext& ctx, const std::array<uint32_t, 3>& c, uint64_t t,
                        const std::vector<uint32_t>& tris) {
  const uint32_t margin = ctx.resolve && !tris.empty() ? 1 : 0;
  ExtGrid e = measure_level(ctx, c, 0, margin);
  std::vector<uint64_t> keys;
  while (ctx.resolve) {
    bool sheet = false;
    const std::vector<uint8_t> flags = unresolved(ctx, c, tris, e, &sheet);
    if (!any_to_refine(flags)) break;
    if (e.level >= ctx.max_level) {
      keys = lower(e, flags, t);
      break;
    }
    e = measure_level(ctx, c, sheet ? ctx.max_level : e.level + 1, margin);
  }
  return finish(e, ctx.measure, std::move(keys));
}

BrickResult far_cell(const BrickContext& ctx, const std::array<uint32_t, 3>& c) {
  const int64_t x0 = int64_t(c[0]) * 8, y0 = int64_t(c[1]) * 8, z0 = int64_t(c[2]) * 8;
  BrickResult r;
  bool all_in = true, all_out = true;
  for (int64_t Z = z0; Z <= z0 + 8; ++Z)
    for (int64_t Y = y0; Y <= y0 + 8; ++Y)
      for (int64_t X = x0; X <= x0 + 8; ++X) {
        const bool in = ctx.signs.inside(X, Y, Z);
        all_in = all_in && in;
        all_out = all_out && !in;
        r.nodes.push_back(int16_t(in ? ctx.measure.qmin : ctx.measure.qmax));
      }
  if (all_in || all_out) {
    r.code = all_in ? 1 : 0;
    r.nodes.clear();
  } else if (ctx.resolve && ctx.max_level > 0) {
    return clamped_brick(ctx, c, ctx.max_level);  // a hole's filling: its boundary at the finest level
  } else {
    r.code = 2;
  }
  return r;
}

}  // namespace voxcd::detail
