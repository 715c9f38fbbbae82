#include "voxcd/host/pairs/detail/empty_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

namespace {

using Dims = std::array<uint32_t, 3>;

// The finest level that keeps the blocks of a grid of n entries within kMaxBaseCells.
int base_level(const Dims& n) {
  int b = 0;
  auto cells = [&](int l) {
    uint64_t c = 1;
    for (int i = 0; i < 3; ++i) c *= (uint64_t(n[size_t(i)]) + (uint64_t{1} << l) - 1) >> l;
    return c;
  };
  while (cells(b) > EmptySpace::kMaxBaseCells) ++b;
  return b;
}

Dims blocks(const Dims& n, int l) {
  Dims d;
  for (size_t i = 0; i < 3; ++i) d[i] = uint32_t((uint64_t(n[i]) + (uint64_t{1} << l) - 1) >> l);
  return d;
}

}  // namespace

EmptySpace EmptySpace::of_states(const Voxmap& vm) {
  EmptySpace e;
  e.n_ = vm.dims();
  if (vm.size() == 0) return e;
  e.base_ = base_level(e.n_);
  Level l{blocks(e.n_, e.base_), {}};
  l.v.assign(uint64_t(l.dims[0]) * l.dims[1] * l.dims[2], 0);
  for (uint32_t z = 0; z < e.n_[2]; ++z)
    for (uint32_t y = 0; y < e.n_[1]; ++y) {
      const uint64_t row = uint64_t(l.dims[0]) * ((y >> e.base_) + uint64_t(l.dims[1]) * (z >> e.base_));
      const uint64_t first = vm.index(0, y, z);
      for (uint32_t x = 0; x < e.n_[0]; ++x) l.v[row + (x >> e.base_)] |= int16_t(1 << int(vm.at(first + x)));
    }
  e.levels_.push_back(std::move(l));
  e.build_near();
  e.build_coarser();
  return e;
}

void EmptySpace::build_near() {
  const Level& l = levels_.front();
  const int64_t nx = l.dims[0], ny = l.dims[1], nz = l.dims[2];
  // Padded by one block of "far" on every side, so that no neighbour needs a bounds test.
  const int64_t px = nx + 2, py = ny + 2, pz = nz + 2;
  std::vector<uint8_t> d(size_t(px * py * pz), 255);
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y)
      for (int64_t x = 0; x < nx; ++x)
        if (uint16_t(l.v[size_t(x + nx * (y + ny * z))]) & 6u) d[size_t((x + 1) + px * ((y + 1) + py * (z + 1)))] = 0;
  // The 13 neighbours before a block in raster order (and, backwards, the 13 after it).
  int64_t off[13];
  int k = 0;
  for (int64_t dz = -1; dz <= 0; ++dz)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dx = -1; dx <= 1; ++dx)
        if (dz < 0 || dy < 0 || (dy == 0 && dx < 0)) off[k++] = dx + px * (dy + py * dz);
  auto relax = [&](int64_t i, int sign) {
    uint8_t best = d[size_t(i)];
    for (int64_t o : off) best = std::min<uint8_t>(best, uint8_t(std::min(255, d[size_t(i + sign * o)] + 1)));
    d[size_t(i)] = best;
  };
  for (int64_t z = 1; z <= nz; ++z)
    for (int64_t y = 1; y <= ny; ++y)
      for (int64_t x = 1; x <= nx; ++x) relax(x + px * (y + py * z), 1);
  for (int64_t z = nz; z >= 1; --z)
    for (int64_t y = ny; y >= 1; --y)
      for (int64_t x = nx; x >= 1; --x) relax(x + px * (y + py * z), -1);
  near_.assign(size_t(nx * ny * nz) + 3, 255);  // 3 bytes of padding (Near)
  for (int64_t z = 0; z < nz; ++z)
    for (int64_t y = 0; y < ny; ++y)
      for (int64_t x = 0; x < nx; ++x)
        near_[size_t(x + nx * (y + ny * z))] = d[size_t((x + 1) + px * ((y + 1) + py * (z + 1)))];
}

bool EmptySpace::may_hit_near(const std::array<int64_t, 3>& c, int64_t r) const {
  if (near_.empty()) return true;
  const Dims& bd = levels_.front().dims;
  // A voxel within r of c lies in a block within ceil(r / b) blocks of c's.
  const int64_t rb = (r + (int64_t{1} << base_) - 1) >> base_;
  const uint64_t i = uint64_t(c[0] >> base_) + bd[0] * (uint64_t(c[1] >> base_) + bd[1] * uint64_t(c[2] >> base_));
  return int64_t(near_[i]) <= rb;
}

EmptySpace EmptySpace::of_field(const DistanceField& f) {
  EmptySpace e;
  e.n_ = f.dims;
  e.min_ = true;
  if (f.empty() || uint64_t(f.dims[0]) * f.dims[1] * f.dims[2] == 0) return e;
  e.base_ = base_level(e.n_);
  Level l{blocks(e.n_, e.base_), {}};
  l.v.assign(uint64_t(l.dims[0]) * l.dims[1] * l.dims[2], std::numeric_limits<int16_t>::max());
  // Every node lowers the blocks of the (up to 8) cells it is a corner of.
  for (uint32_t Z = 0; Z <= e.n_[2]; ++Z)
    for (uint32_t Y = 0; Y <= e.n_[1]; ++Y)
      for (uint32_t X = 0; X <= e.n_[0]; ++X) {
        const int16_t q = int16_t(f.at(X, Y, Z));
        for (uint32_t dz = Z ? Z - 1 : 0; dz <= std::min(Z, e.n_[2] - 1); ++dz)
          for (uint32_t dy = Y ? Y - 1 : 0; dy <= std::min(Y, e.n_[1] - 1); ++dy)
            for (uint32_t dx = X ? X - 1 : 0; dx <= std::min(X, e.n_[0] - 1); ++dx) {
              int16_t& v = l.v[(dx >> e.base_) + uint64_t(l.dims[0]) * ((dy >> e.base_) +
                                                                          uint64_t(l.dims[1]) * (dz >> e.base_))];
              v = std::min(v, q);
            }
      }
  e.levels_.push_back(std::move(l));
  e.build_coarser();
  return e;
}

namespace {

// The voxels [lo, hi] per axis a node at `pos` (voxel units) is a corner of, within [0, n) and the cell [c0, c0 + B).
void node_voxels(double pos, uint32_t c0, uint32_t n, uint32_t& lo, uint32_t& hi) {
  const double f = std::floor(pos);
  const int64_t a = f == pos ? int64_t(f) - 1 : int64_t(f), b = int64_t(f);
  lo = uint32_t(std::max<int64_t>({a, 0, c0}));
  hi = uint32_t(std::min<int64_t>({b, int64_t(n) - 1, int64_t(c0) + SparseDistanceField::kEdge - 1}));
}

}  // namespace

EmptySpace EmptySpace::of_sparse_field(const SparseDistanceField& f) {
  EmptySpace e;
  e.n_ = f.dims();
  e.min_ = true;
  if (f.empty() || uint64_t(e.n_[0]) * e.n_[1] * e.n_[2] == 0) return e;
  e.base_ = base_level(e.n_);
  Level l{blocks(e.n_, e.base_), {}};
  l.v.assign(uint64_t(l.dims[0]) * l.dims[1] * l.dims[2], std::numeric_limits<int16_t>::max());
  auto lower = [&](uint32_t x, uint32_t y, uint32_t z, int16_t q) {
    int16_t& v = l.v[(x >> e.base_) + uint64_t(l.dims[0]) * ((y >> e.base_) + uint64_t(l.dims[1]) * (z >> e.base_))];
    v = std::min(v, q);
  };
  const uint32_t B = SparseDistanceField::kEdge;
  const auto& cells = f.cells();
  for (uint64_t t = 0; t < f.codes().size(); ++t) {
    const uint32_t c[3] = {uint32_t(t % cells[0]) * B, uint32_t(t / cells[0] % cells[1]) * B,
                           uint32_t(t / (uint64_t(cells[0]) * cells[1])) * B};
    const int level = f.level(t);
    if (level < 0) {  // a uniform cell: its value in every voxel
      const int16_t q = int16_t(f.at(t, 0, 0, 0));
      for (uint32_t z = c[2]; z < std::min(c[2] + B, e.n_[2]); ++z)
        for (uint32_t y = c[1]; y < std::min(c[1] + B, e.n_[1]); ++y)
          for (uint32_t x = c[0]; x < std::min(c[0] + B, e.n_[0]); ++x) lower(x, y, z, q);
      continue;
    }
    const uint64_t side = brick_side(level);
    const double unit = std::ldexp(1.0, -level);
    for (uint64_t Z = 0; Z < side; ++Z)
      for (uint64_t Y = 0; Y < side; ++Y)
        for (uint64_t X = 0; X < side; ++X) {
          const int16_t q = int16_t(f.at(t, X, Y, Z));
          uint32_t lo[3], hi[3];
          const uint64_t N[3] = {X, Y, Z};
          for (int i = 0; i < 3; ++i) node_voxels(c[i] + double(N[i]) * unit, c[i], e.n_[i], lo[i], hi[i]);
          for (uint32_t z = lo[2]; z <= hi[2]; ++z)
            for (uint32_t y = lo[1]; y <= hi[1]; ++y)
              for (uint32_t x = lo[0]; x <= hi[0]; ++x) lower(x, y, z, q);
        }
  }
  e.levels_.push_back(std::move(l));
  e.build_coarser();
  return e;
}

void EmptySpace::build_coarser() {
  for (;;) {
    const Level& fine = levels_.back();
    if (fine.dims[0] == 1 && fine.dims[1] == 1 && fine.dims[2] == 1) return;
    Level c;
    for (size_t i = 0; i < 3; ++i) c.dims[i] = (fine.dims[i] + 1) / 2;
    c.v.assign(uint64_t(c.dims[0]) * c.dims[1] * c.dims[2],
               min_ ? std::numeric_limits<int16_t>::max() : int16_t(0));
    for (uint32_t z = 0; z < fine.dims[2]; ++z)
      for (uint32_t y = 0; y < fine.dims[1]; ++y)
        for (uint32_t x = 0; x < fine.dims[0]; ++x) {
          const int16_t v = fine.v[x + uint64_t(fine.dims[0]) * (y + uint64_t(fine.dims[1]) * z)];
          int16_t& to = c.v[(x >> 1) + uint64_t(c.dims[0]) * ((y >> 1) + uint64_t(c.dims[1]) * (z >> 1))];
          to = min_ ? std::min(to, v) : int16_t(to | v);
        }
    levels_.push_back(std::move(c));
  }
}

template <class Accept>
bool EmptySpace::visit(size_t k, size_t last, const std::array<uint32_t, 3>& b, const std::array<int64_t, 3>& lo,
                       const std::array<int64_t, 3>& hi, const Accept& accept) const {
  const Level& l = levels_[k];
  if (!accept(l.v[b[0] + uint64_t(l.dims[0]) * (b[1] + uint64_t(l.dims[1]) * b[2])])) return false;
  if (k == last) return true;
  // The children (level k - 1) of this block within the box.
  const Dims& cd = levels_[k - 1].dims;
  std::array<uint32_t, 3> c0, c1;
  for (size_t i = 0; i < 3; ++i) {
    c0[i] = std::max(2 * b[i], uint32_t(lo[i] >> (k - 1)));
    c1[i] = std::min({2 * b[i] + 1, uint32_t(hi[i] >> (k - 1)), cd[i] - 1});
  }
  for (uint32_t z = c0[2]; z <= c1[2]; ++z)
    for (uint32_t y = c0[1]; y <= c1[1]; ++y)
      for (uint32_t x = c0[0]; x <= c1[0]; ++x)
        if (visit(k - 1, last, {x, y, z}, lo, hi, accept)) return true;
  return false;
}

template <class Accept>
bool EmptySpace::any(std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, const Accept& accept) const {
  if (levels_.empty()) return true;
  // The box in blocks of the finest level; then the level at which it spans at most two blocks per axis.
  for (size_t i = 0; i < 3; ++i) {
    lo[i] = std::max<int64_t>(lo[i], 0);
    hi[i] = std::min<int64_t>(hi[i], int64_t(n_[i]) - 1);
    if (lo[i] > hi[i]) return false;
    lo[i] >>= base_;
    hi[i] >>= base_;
  }
  size_t k = 0;
  while (k + 1 < levels_.size() &&
         ((hi[0] >> k) - (lo[0] >> k) > 1 || (hi[1] >> k) - (lo[1] >> k) > 1 || (hi[2] >> k) - (lo[2] >> k) > 1))
    ++k;
  // Blocks a quarter of the box's size are as fine as its test needs: the box is already larger than its points.
  const size_t last = k > kDescend ? k - kDescend : 0;
  for (int64_t z = lo[2] >> k; z <= hi[2] >> k; ++z)
    for (int64_t y = lo[1] >> k; y <= hi[1] >> k; ++y)
      for (int64_t x = lo[0] >> k; x <= hi[0] >> k; ++x)
        if (visit(k, last, {uint32_t(x), uint32_t(y), uint32_t(z)}, lo, hi, accept)) return true;
  return false;
}

bool EmptySpace::may_hit_states(std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, uint32_t mask) const {
  return any(lo, hi, [mask](int16_t v) { return (uint32_t(uint16_t(v)) & mask) != 0; });
}

bool EmptySpace::may_hit_field(std::array<int64_t, 3> lo, std::array<int64_t, 3> hi, int64_t threshold,
                               int wb) const {
  // D >= least node * 2^(3 wb), so a block can hold a hit only when its least node <= floor(threshold / 2^(3 wb)).
  const int64_t limit = threshold >> (3 * wb);
  return any(lo, hi, [limit](int16_t v) { return int64_t(v) <= limit; });
}

}  // namespace voxcd::detail
