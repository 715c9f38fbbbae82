#include "voxcd/host/object/detail/shell_chain.h"

#include <algorithm>

namespace voxcd::detail {

namespace {

// The bricks by row (z, y), each row's bricks by x: the bricks in a box in index order.
class BrickRows {
 public:
  explicit BrickRows(const std::vector<BrickPos>& b) : b_(b) {
    for (const BrickPos& p : b) {
      ny_ = std::max(ny_, int(p[1]) + 1);
      nz_ = std::max(nz_, int(p[2]) + 1);
    }
    start_.assign(size_t(ny_) * size_t(nz_) + 1, 0);
    for (const BrickPos& p : b) ++start_[row(p[1], p[2]) + 1];
    for (size_t r = 0; r + 1 < start_.size(); ++r) start_[r + 1] += start_[r];
  }
  // fn(index) for every brick with x, y, z in the closed ranges, in index order.
  template <class Fn>
  void visit(int x0, int x1, int y0, int y1, int z0, int z1, Fn&& fn) const {
    for (int z = std::max(z0, 0); z <= std::min(z1, nz_ - 1); ++z)
      for (int y = std::max(y0, 0); y <= std::min(y1, ny_ - 1); ++y) {
        const size_t r = row(y, z);
        const auto* first = b_.data() + start_[r];
        const auto* last = b_.data() + start_[r + 1];
        const auto* p = std::lower_bound(first, last, x0, [](const BrickPos& q, int x) { return int(q[0]) < x; });
        for (; p != last && int((*p)[0]) <= x1; ++p) fn(uint32_t(p - b_.data()));
      }
  }

 private:
  size_t row(int y, int z) const { return size_t(y) + size_t(ny_) * size_t(z); }
  const std::vector<BrickPos>& b_;
  int ny_ = 0, nz_ = 0;
  std::vector<uint32_t> start_;
};

}  // namespace

std::vector<uint32_t> chain_order(const std::vector<BrickPos>& bricks) {
  const size_t n = bricks.size();
  const BrickRows rows(bricks);
  // deg[u]: the unvisited bricks a step away from u (u + [-2, 1]^3, u itself aside).
  std::vector<uint8_t> deg(n, 0), visited(n, 0);
  for (uint32_t u = 0; u < n; ++u) {
    const BrickPos& p = bricks[u];
    rows.visit(p[0] - 2, p[0] + 1, p[1] - 2, p[1] + 1, p[2] - 2, p[2] + 1, [&](uint32_t v) { deg[u] += v != u; });
  }
  std::vector<uint32_t> order;
  order.reserve(n);
  auto take = [&](uint32_t v) {
    visited[v] = 1;
    order.push_back(v);
    const BrickPos& p = bricks[v];  // the bricks that reach v in a step: v - [-2, 1]^3
    rows.visit(p[0] - 1, p[0] + 2, p[1] - 1, p[1] + 2, p[2] - 1, p[2] + 2, [&](uint32_t u) { deg[u] -= u != v; });
  };
  size_t lowest = 0;
  while (order.size() < n) {
    while (visited[lowest]) ++lowest;
    uint32_t cur = uint32_t(lowest);
    take(cur);
    for (;;) {
      const BrickPos& p = bricks[cur];
      uint32_t best = UINT32_MAX;
      int best_deg = 256;
      rows.visit(p[0] - 2, p[0] + 1, p[1] - 2, p[1] + 1, p[2] - 2, p[2] + 1, [&](uint32_t v) {
        if (!visited[v] && deg[v] < best_deg) {
          best = v;
          best_deg = deg[v];
        }
      });
      if (best == UINT32_MAX) break;
      take(cur = best);
    }
  }
  return order;
}

}  // namespace voxcd::detail
