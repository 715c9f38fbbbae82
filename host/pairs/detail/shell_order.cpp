#include "voxcd/host/pairs/detail/shell_order.h"

#include <algorithm>

namespace voxcd::detail {

ShellOrder block_order(const std::vector<std::array<uint32_t, 3>>& cells) {
  ShellOrder o;
  const size_t n = cells.size();
  std::array<uint32_t, 3> nb = {1, 1, 1};  // blocks per axis
  for (const auto& c : cells)
    for (size_t i = 0; i < 3; ++i) nb[i] = std::max(nb[i], c[i] / ShellOrder::kBlock + 1);
  auto key = [&](const std::array<uint32_t, 3>& c) {
    const uint32_t b = ShellOrder::kBlock;
    return size_t(c[0] / b) + size_t(nb[0]) * (size_t(c[1] / b) + size_t(nb[1]) * size_t(c[2] / b));
  };
  // A counting sort by block, stable: each block's points stay in ascending order.
  std::vector<uint32_t> count(size_t(nb[0]) * nb[1] * nb[2] + 1, 0);
  for (const auto& c : cells) ++count[key(c) + 1];
  for (size_t b = 1; b < count.size(); ++b) {
    if (count[b]) o.block_first.push_back(count[b - 1]);
    count[b] += count[b - 1];
  }
  o.block_first.push_back(uint32_t(n));
  o.point.resize(n);
  for (uint32_t k = 0; k < n; ++k) o.point[count[key(cells[k])]++] = k;
  return o;
}

// Compiled for processors with and without the popcnt instruction (a library call per word without it); one version
// in the fuzz build (VOXCD_NO_IFUNC: CMakeLists.txt says why).
#ifdef VOXCD_NO_IFUNC
#define VOXCD_POPCNT_CLONES
#else
#define VOXCD_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#endif
VOXCD_POPCNT_CLONES void RankBits::place(const HitSpan* spans, size_t n,
                                                                         const uint32_t* order, size_t points,
                                                                         SortedHit* out) {
  // Already in ascending point order (a direction whose hits all lie in one block, or one hit): in place.
  uint32_t prev = 0, k = 0;
  bool ascending = true;
  for (size_t s = 0; s < n && ascending; ++s)
    for (size_t r = 0; r < spans[s].n; ++r, ++k) {
      const uint32_t p = order[spans[s].first + spans[s].point[r]];
      if (k && p <= prev) {
        ascending = false;
        break;
      }
      prev = p;
    }
  if (ascending) {
    k = 0;
    for (size_t s = 0; s < n; ++s)
      for (size_t r = 0; r < spans[s].n; ++r)
        out[k++] = {uint32_t(spans[s].at + r), order[spans[s].first + spans[s].point[r]]};
    return;
  }
  // Else a bit per point: a hit's rank is the bits set below its own.
  const size_t words = (points + 63) / 64;
  if (bits_.size() < words) bits_.assign(words, 0), below_.resize(words);
  size_t lo = words, hi = 0;
  for (size_t s = 0; s < n; ++s)
    for (size_t r = 0; r < spans[s].n; ++r) {
      const uint32_t p = order[spans[s].first + spans[s].point[r]];
      bits_[p >> 6] |= uint64_t{1} << (p & 63);
      lo = std::min<size_t>(lo, p >> 6), hi = std::max<size_t>(hi, p >> 6);
    }
  uint32_t sum = 0;
  for (size_t w = lo; w <= hi; ++w) below_[w] = sum, sum += uint32_t(__builtin_popcountll(bits_[w]));
  for (size_t s = 0; s < n; ++s)
    for (size_t r = 0; r < spans[s].n; ++r) {
      const uint32_t p = order[spans[s].first + spans[s].point[r]];
      const uint32_t rank = below_[p >> 6] + uint32_t(__builtin_popcountll(bits_[p >> 6] & ((uint64_t{1} << (p & 63)) - 1)));
      out[rank] = {uint32_t(spans[s].at + r), p};
    }
  std::fill(bits_.begin() + std::ptrdiff_t(lo), bits_.begin() + std::ptrdiff_t(hi + 1), uint64_t(0));
}

size_t keep_direction(const HitSpan* spans, size_t n, bool first_only, const uint32_t* order, size_t points,
                      SortedHit* out, RankBits& bits) {
  if (first_only) {
    size_t best = n;
    uint32_t lowest = UINT32_MAX;
    for (size_t s = 0; s < n; ++s) {
      if (spans[s].n == 0) continue;
      const uint32_t p = order[spans[s].first + spans[s].point[0]];
      if (p < lowest) lowest = p, best = s;
    }
    if (best == n) return 0;
    out[0] = {uint32_t(spans[best].at), lowest};
    return 1;
  }
  size_t kept = 0;
  for (size_t s = 0; s < n; ++s) kept += spans[s].n;
  if (kept) bits.place(spans, n, order, points, out);
  return kept;
}

}  // namespace voxcd::detail
