// SparseDistanceField: its invariant (codes, bricks and keys that fit one another), the interpolant, counts and the
// sparse device's image; conversions from and to a dense field. The field is built in sparse_build.cpp and
// serialised in sparse_file.cpp.
#include "voxcd/host/object/sparse_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {

namespace {

constexpr uint8_t kMaxCode = 2 + SparseDistanceField::kMaxLevel;

uint64_t brick_nodes(int level) {
  const uint64_t n = brick_side(level);
  return n * n * n;
}

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("SparseDistanceField: " + what); }

}  // namespace

SparseDistanceField::SparseDistanceField(int bits, double step, const std::array<uint32_t, 3>& dims,
                                         std::vector<uint8_t> codes, std::vector<int16_t> nodes,
                                         std::vector<uint64_t> conservative)
    : bits_(bits),
      step_(step),
      dims_(dims),
      codes_(std::move(codes)),
      nodes_(std::move(nodes)),
      conservative_(std::move(conservative)) {
  if (!valid_distance_bits(bits)) bad("bits " + std::to_string(bits) + " is not " + distance_bits_text());
  if (!(std::isfinite(step) && step > 0)) bad("the step must be a positive finite number");
  for (int i = 0; i < 3; ++i) {
    if (dims[size_t(i)] == 0) bad("a grid dimension is 0");
    cells_[size_t(i)] = (dims[size_t(i)] + kEdge - 1) / kEdge;
  }
  if (codes_.size() != uint64_t(cells_[0]) * cells_[1] * cells_[2])
    bad(std::to_string(codes_.size()) + " codes for " + std::to_string(uint64_t(cells_[0]) * cells_[1] * cells_[2]) +
        " cells");
  uint64_t total = 0;
  for (uint64_t t = 0; t < codes_.size(); ++t) {
    if (codes_[t] > kMaxCode) bad("cell " + std::to_string(t) + " has code " + std::to_string(codes_[t]));
    if (codes_[t] >= 2) total += brick_nodes(codes_[t] - 2);
  }
  if (nodes_.size() != total)
    bad(std::to_string(nodes_.size()) + " node values for bricks of " + std::to_string(total) + " nodes");
  for (size_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i] < qmin() || nodes_[i] > qmax())
      bad("node value " + std::to_string(nodes_[i]) + " (at " + std::to_string(i) + ") does not fit " +
          std::to_string(bits) + " bits");
  for (size_t i = 0; i < conservative_.size(); ++i) {
    const uint64_t k = conservative_[i], t = k >> 18;
    const uint64_t side = t < codes_.size() && level(t) >= 0 ? brick_side(level(t)) - 1 : 0;
    if (i > 0 && k <= conservative_[i - 1]) bad("conservative sub-cells are not in increasing order");
    if ((k & 63) >= side || (k >> 6 & 63) >= side || (k >> 12 & 63) >= side)
      bad("conservative sub-cell key " + std::to_string(k) + " is not a sub-cell of a brick");
  }
  index();
}

void SparseDistanceField::index() {
  block_first_.assign((codes_.size() + 63) / 64, 0);
  uint64_t first = 0;
  for (uint64_t t = 0; t < codes_.size(); ++t) {
    if (t % 64 == 0) block_first_[t / 64] = first;
    if (codes_[t] >= 2) first += brick_nodes(codes_[t] - 2);
  }
}

uint64_t SparseDistanceField::brick_first(uint64_t t) const {
  uint64_t first = block_first_[t / 64];
  for (uint64_t u = t - t % 64; u < t; ++u)
    if (codes_[u] >= 2) first += brick_nodes(codes_[u] - 2);
  return first;
}

int SparseDistanceField::at(uint64_t t, uint64_t X, uint64_t Y, uint64_t Z) const {
  const int l = level(t);
  if (l < 0) return codes_[t] == 1 ? qmin() : qmax();
  const uint64_t n = brick_side(l);
  return nodes_[brick_first(t) + X + n * (Y + n * Z)];
}

namespace {

// Where grid point g falls: its cell (as the device picks it, from the voxel's index) and its position in the cell's
// brick at `level` (u, in sub-cells), with the sub-cell X and the fraction f.
struct Place {
  uint64_t c[3];
  uint64_t X[3];
  double f[3];
};

Place place_cell(const std::array<uint32_t, 3>& dims, const Eigen::Vector3d& g) {
  Place p{};
  for (int i = 0; i < 3; ++i) {
    const double n = double(dims[size_t(i)]);
    const double v = std::clamp(g[i], 0.0, n);
    const uint64_t voxel = uint64_t(std::min(std::floor(v), n - 1));
    p.c[i] = voxel >> SparseDistanceField::kBrickLog;
    p.f[i] = v - double(p.c[i] * SparseDistanceField::kEdge);  // position in the cell, voxels
  }
  return p;
}

void place_sub_cell(Place& p, int level) {
  const double side = double(brick_side(level) - 1);
  for (int i = 0; i < 3; ++i) {
    const double u = std::ldexp(p.f[i], level);
    const double X = std::min(std::floor(u), side - 1);
    p.X[i] = uint64_t(X);
    p.f[i] = u - X;
  }
}

}  // namespace

double SparseDistanceField::sample(const Eigen::Vector3d& g, Eigen::Vector3d* gradient) const {
  Place p = place_cell(dims_, g);
  const uint64_t t = cell_index(p.c[0], p.c[1], p.c[2]);
  const int l = level(t);
  if (l < 0) {
    if (gradient) gradient->setZero();
    return at(t, 0, 0, 0) * step_;
  }
  place_sub_cell(p, l);
  const uint64_t n = brick_side(l), first = brick_first(t);
  double v[8];
  for (int k = 0; k < 8; ++k)
    v[k] = nodes_[first + (p.X[0] + (k & 1)) + n * ((p.X[1] + (k >> 1 & 1)) + n * (p.X[2] + (k >> 2 & 1)))] * step_;
  auto lerp = [](double a, double b, double s) { return a + (b - a) * s; };
  const double* f = p.f;
  const double x00 = lerp(v[0], v[1], f[0]), x10 = lerp(v[2], v[3], f[0]);
  const double x01 = lerp(v[4], v[5], f[0]), x11 = lerp(v[6], v[7], f[0]);
  const double y0 = lerp(x00, x10, f[1]), y1 = lerp(x01, x11, f[1]);
  if (gradient) {
    // Per sub-cell, then per voxel: a sub-cell is 2^-l voxel.
    const double s = std::ldexp(1.0, l);
    const double dx0 = lerp(v[1] - v[0], v[3] - v[2], f[1]), dx1 = lerp(v[5] - v[4], v[7] - v[6], f[1]);
    (*gradient)[0] = lerp(dx0, dx1, f[2]) * s;
    (*gradient)[1] = lerp(x10 - x00, x11 - x01, f[2]) * s;
    (*gradient)[2] = (y1 - y0) * s;
  }
  return lerp(y0, y1, f[2]);
}

bool SparseDistanceField::near_conservative(const Eigen::Vector3d& g) const {
  if (conservative_.empty()) return false;
  Place p = place_cell(dims_, g);
  const uint64_t t = cell_index(p.c[0], p.c[1], p.c[2]);
  const int l = level(t);
  if (l < 0) return false;
  place_sub_cell(p, l);
  const int64_t side = int64_t(brick_side(l)) - 1;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int64_t X = int64_t(p.X[0]) + dx, Y = int64_t(p.X[1]) + dy, Z = int64_t(p.X[2]) + dz;
        if (X < 0 || Y < 0 || Z < 0 || X >= side || Y >= side || Z >= side) continue;
        const uint64_t key = conservative_key(t, uint32_t(X), uint32_t(Y), uint32_t(Z));
        if (std::binary_search(conservative_.begin(), conservative_.end(), key)) return true;
      }
  return false;
}

SparseFieldCounts SparseDistanceField::counts() const {
  SparseFieldCounts c;
  for (uint8_t code : codes_) {
    if (code == 0)
      ++c.far;
    else if (code == 1)
      ++c.deep;
    else
      ++c.bricks[size_t(code - 2)];
  }
  c.conservative = conservative_.size();
  c.nodes = nodes_.size();
  return c;
}

uint64_t SparseDistanceField::bytes() const {
  return sizeof(*this) + codes_.size() + nodes_.size() * sizeof(int16_t) +
         (conservative_.size() + block_first_.size()) * sizeof(uint64_t);
}

SparseImage SparseDistanceField::device_image(const DeviceConfig& cfg) const {
  if (!cfg.distance() || cfg.SB != bits_)
    throw std::invalid_argument("device_image: a field of " + std::to_string(bits_) +
                                " bits needs a distance device with SB = " + std::to_string(bits_) +
                                ", not SB = " + std::to_string(cfg.SB));
  if (cfg.BL != kBrickLog)
    throw std::invalid_argument("device_image: bricks of 8 voxels need BL = 3, not BL = " + std::to_string(cfg.BL));
  SparseImage im;
  im.table = table_image(cfg, codes_);
  im.brick_units = table_units(cfg, codes_);
  im.bricks.assign(im.brick_units * unit_words(cfg), 0);
  const uint64_t mask = (uint64_t{1} << cfg.SB) - 1;
  uint64_t unit = 0, first = 0;
  for (uint64_t t = 0; t < codes_.size(); ++t) {
    const int l = level(t);
    if (l < 0) continue;
    const Cell cell{codes_[t], l, unit * unit_words(cfg)};
    const uint64_t n = brick_side(l);
    for (uint64_t Z = 0; Z < n; ++Z)
      for (uint64_t Y = 0; Y < n; ++Y)
        for (uint64_t X = 0; X < n; ++X) {
          const NodeAddress a = brick_node_address(cfg, cell, X, Y, Z);
          im.bricks[a.word] |= (uint64_t(int64_t(nodes_[first + X + n * (Y + n * Z)])) & mask) << (cfg.SB * a.slot);
        }
    unit += level_units(cfg, l);
    first += n * n * n;
  }
  return im;
}

SparseDistanceField sparse_from_dense(const DistanceField& f) {
  const uint32_t e = SparseDistanceField::kEdge;
  std::array<uint32_t, 3> c;
  for (int i = 0; i < 3; ++i) c[size_t(i)] = (f.dims[size_t(i)] + e - 1) / e;
  std::vector<uint8_t> codes;
  std::vector<int16_t> nodes, brick(size_t(brick_nodes(0)));
  for (uint64_t cz = 0; cz < c[2]; ++cz)
    for (uint64_t cy = 0; cy < c[1]; ++cy)
      for (uint64_t cx = 0; cx < c[0]; ++cx) {
        bool far = true, deep = true;
        size_t k = 0;
        for (uint64_t Z = cz * e; Z <= cz * e + e; ++Z)
          for (uint64_t Y = cy * e; Y <= cy * e + e; ++Y)
            for (uint64_t X = cx * e; X <= cx * e + e; ++X) {
              const int q = f.at(std::min<uint64_t>(X, f.dims[0]), std::min<uint64_t>(Y, f.dims[1]),
                                 std::min<uint64_t>(Z, f.dims[2]));
              brick[k++] = int16_t(q);
              far = far && q == f.qmax();
              deep = deep && q == f.qmin();
            }
        codes.push_back(far ? 0 : deep ? 1 : 2);
        if (!far && !deep) nodes.insert(nodes.end(), brick.begin(), brick.end());
      }
  return SparseDistanceField(f.bits, f.step, f.dims, std::move(codes), std::move(nodes), {});
}

DistanceField dense_from_sparse(const SparseDistanceField& s) {
  DistanceField f;
  f.bits = s.bits();
  f.step = s.step();
  f.dims = s.dims();
  f.q.resize(uint64_t(f.dims[0] + 1) * (f.dims[1] + 1) * (f.dims[2] + 1));
  const uint32_t e = SparseDistanceField::kEdge;
  for (uint64_t Z = 0; Z <= f.dims[2]; ++Z)
    for (uint64_t Y = 0; Y <= f.dims[1]; ++Y)
      for (uint64_t X = 0; X <= f.dims[0]; ++X) {
        const uint64_t cx = std::min<uint64_t>(X / e, s.cells()[0] - 1),
                       cy = std::min<uint64_t>(Y / e, s.cells()[1] - 1),
                       cz = std::min<uint64_t>(Z / e, s.cells()[2] - 1);
        const uint64_t t = s.cell_index(cx, cy, cz);
        const int l = std::max(0, s.level(t));
        f.q[f.node_index(X, Y, Z)] = int16_t(s.at(t, (X - cx * e) << l, (Y - cy * e) << l, (Z - cz * e) << l));
      }
  return f;
}

}  // namespace voxcd
