#include "voxcd/host/object/sparse_shell.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "voxcd/host/object/detail/octahedral.h"
#include "voxcd/host/object/detail/shell_chain.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {

namespace {

// Calls fn(cell) for each set bit of a brick's mask, in ascending bit order.
template <class Fn>
void brick_cells(const std::array<uint16_t, 3>& b, uint64_t mask, Fn&& fn) {
  for (uint64_t m = mask; m; m &= m - 1) {
    const uint32_t i = uint32_t(__builtin_ctzll(m));
    fn(std::array<uint32_t, 3>{kShellBrickEdge * b[0] + (i & 3), kShellBrickEdge * b[1] + ((i >> 2) & 3),
                               kShellBrickEdge * b[2] + (i >> 4)});
  }
}

}  // namespace

uint64_t SparseShell::origin_words() const {
  uint64_t n = 0;
  for (size_t k = 0; k < bricks.size(); ++k) n += k == 0 || !detail::chain_step(bricks[k - 1], bricks[k]);
  return n;
}

std::vector<ShellWord> SparseShell::device_words(const DeviceConfig& cfg) const {
  if (3 * cfg.PW < 72 || cfg.PF < 1)
    throw std::invalid_argument("sparse shell: shell words of PW = " + std::to_string(cfg.PW) + ", PF = " +
                                std::to_string(cfg.PF) + " cannot hold shell bricks (3 PW >= 72 and PF >= 1 needed)");
  std::vector<ShellWord> w;
  w.reserve(words());
  const int64_t unit = int64_t{kShellBrickEdge} << cfg.PF;  // a brick in shell word units
  for (size_t k = 0; k < bricks.size(); ++k) {
    int step[3] = {0, 0, 0};
    if (k == 0 || !detail::chain_step(bricks[k - 1], bricks[k]))
      w.push_back(origin_word(cfg, unit * bricks[k][0], unit * bricks[k][1], unit * bricks[k][2]));
    else
      for (int a = 0; a < 3; ++a) step[a] = int(bricks[k][a]) - int(bricks[k - 1][a]);
    w.push_back(brick_word(cfg, masks[k], step));
  }
  return w;
}

std::vector<std::array<uint32_t, 3>> SparseShell::cells() const {
  std::vector<std::array<uint32_t, 3>> c;
  c.reserve(size());
  for (size_t k = 0; k < bricks.size(); ++k) brick_cells(bricks[k], masks[k], [&](const auto& v) { c.push_back(v); });
  return c;
}

Eigen::Vector3d SparseShell::normal(size_t k) const { return detail::decode_normal(normals[k]); }

PointShell SparseShell::to_point_shell() const {
  PointShell s;
  s.grid = grid;
  const std::vector<std::array<uint32_t, 3>> c = cells();
  const uint64_t nx = grid.dims[0], ny = grid.dims[1];
  auto lin = [&](const std::array<uint32_t, 3>& v) { return v[0] + nx * (v[1] + ny * uint64_t(v[2])); };
  std::vector<uint32_t> by(c.size());
  std::iota(by.begin(), by.end(), 0u);
  std::sort(by.begin(), by.end(), [&](uint32_t a, uint32_t b) { return lin(c[a]) < lin(c[b]); });
  s.cells.reserve(c.size());
  s.points.reserve(c.size());
  s.normals.reserve(c.size());
  for (uint32_t k : by) {
    s.cells.push_back(c[k]);
    s.points.push_back(grid.origin + grid.voxel * Eigen::Vector3d(c[k][0] + 0.5, c[k][1] + 0.5, c[k][2] + 0.5));
    s.normals.push_back(normal(k));
  }
  return s;
}

SparseShell SparseShell::from_point_shell(const PointShell& s) {
  if (s.on_surface) throw std::invalid_argument("sparse shell: a shell on the surface has no sparse form");
  // The bricks sorted by z, y, x; each point's brick and bit.
  std::vector<std::pair<uint64_t, uint32_t>> keyed(s.size());  // (brick key, point)
  auto key = [](const std::array<uint32_t, 3>& c) {
    return uint64_t(c[2] / kShellBrickEdge) << 40 | uint64_t(c[1] / kShellBrickEdge) << 20 | (c[0] / kShellBrickEdge);
  };
  for (size_t k = 0; k < s.size(); ++k) keyed[k] = {key(s.cells[k]), uint32_t(k)};
  std::sort(keyed.begin(), keyed.end());
  std::vector<detail::BrickPos> sorted;
  std::vector<uint64_t> masks;
  uint64_t last = UINT64_MAX;
  for (const auto& [kk, k] : keyed) {
    const auto& c = s.cells[k];
    if (kk != last) {
      sorted.push_back({uint16_t(c[0] / 4), uint16_t(c[1] / 4), uint16_t(c[2] / 4)});
      masks.push_back(0);
      last = kk;
    }
    masks.back() |= uint64_t{1} << ((c[0] & 3) | (c[1] & 3) << 2 | (c[2] & 3) << 4);
  }
  SparseShell out;
  out.grid = s.grid;
  // Each voxel's point in s (cells are in linear-index order: a binary search finds it).
  const uint64_t nx = s.grid.dims[0], ny = s.grid.dims[1];
  auto lin = [&](const std::array<uint32_t, 3>& v) { return v[0] + nx * (v[1] + ny * uint64_t(v[2])); };
  for (uint32_t b : detail::chain_order(sorted)) {
    out.bricks.push_back(sorted[b]);
    out.masks.push_back(masks[b]);
    brick_cells(sorted[b], masks[b], [&](const std::array<uint32_t, 3>& v) {
      const auto it = std::lower_bound(s.cells.begin(), s.cells.end(), v,
                                       [&](const std::array<uint32_t, 3>& a, const std::array<uint32_t, 3>& x) {
                                         return lin(a) < lin(x);
                                       });
      out.normals.push_back(detail::encode_normal(s.normals[size_t(it - s.cells.begin())]));
    });
  }
  return out;
}

}  // namespace voxcd
