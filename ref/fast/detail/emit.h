// Internal to FastRunner: a 2-bit block kernel's output (per point its state | hit << 2, for hits the voxel) turned
// into hit columns, in point order.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "voxcd/ref/fast/hits.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// Appends the block's `found` hits, voxel(k, v) setting point k's voxel in v; true when FIRST has its answer. Walks
// the states eight at a time: most of a block's points are no hit.
template <class Voxel>
bool emit(const Job& j, uint32_t b, size_t n, const uint8_t* state, uint32_t found, HitColumns& hits, uint32_t& count,
          const Voxel& voxel) {
  hits.reserve_more(found);
  const HitColumns::Rows out = hits.rows();
  size_t w = 0;
  for (size_t k0 = 0; k0 < n; k0 += 8) {
    uint64_t word = 0;  // state k0 + i in byte i, so the lowest set bit is the next hit in point order
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    if (n - k0 >= 8)
      std::memcpy(&word, state + k0, 8);
    else
#endif
      for (size_t i = 0; i < std::min<size_t>(8, n - k0); ++i) word |= uint64_t(state[k0 + i]) << (8 * i);
    for (uint64_t flags = word & 0x0404040404040404ull; flags; flags &= flags - 1) {
      const size_t k = k0 + size_t(__builtin_ctzll(flags) / 8);
      uint32_t v[3];
      voxel(k, v);
      out.point[w] = b + uint32_t(k), out.x[w] = v[0], out.y[w] = v[1], out.z[w] = v[2];
      out.state[w] = uint8_t(state[k] & 3u), out.dist[w] = 0;
      ++w;
      if (j.mode == Mode::First) break;
    }
    if (w && j.mode == Mode::First) break;
  }
  hits.commit(w);
  count += uint32_t(w);
  return w && j.mode == Mode::First;
}

// The voxels given by the kernel.
inline bool emit_cells(const Job& j, uint32_t b, size_t n, const int32_t* cx, const int32_t* cy, const int32_t* cz,
                       const uint8_t* state, uint32_t found, HitColumns& hits, uint32_t& count) {
  return emit(j, b, n, state, found, hits, count, [&](size_t k, uint32_t* v) {
    v[0] = uint32_t(cx[k]), v[1] = uint32_t(cy[k]), v[2] = uint32_t(cz[k]);
  });
}

// A distance block kernel's output (per point hit[k]; for hits the voxel and D, an exact integer in a double) appended
// as hits of points b + k; true when FIRST has its answer.
inline bool emit_distances(const Job& j, uint32_t b, size_t n, uint32_t found, const uint8_t* hit, const int32_t* cx,
                           const int32_t* cy, const int32_t* cz, const double* dist, HitColumns& hits,
                           uint32_t& count) {
  if (found == 0) return false;
  if (j.mode == Mode::Count) return count += found, false;
  hits.reserve_more(found);
  for (size_t k = 0; k < n; ++k) {
    if (!hit[k]) continue;
    ++count;
    hits.put(b + uint32_t(k), uint32_t(cx[k]), uint32_t(cy[k]), uint32_t(cz[k]), 0, int64_t(dist[k]));
    if (j.mode == Mode::First) return true;
  }
  return false;
}

// Quotients by a job's nx and ny without a hardware divide (tens of cycles per hit): a double reciprocal gives the
// quotient within one for dividends below 2^53 (every map that fits memory), and the correction makes it exact.
struct Divider {
  uint64_t d;
  double inv;
  explicit Divider(uint64_t den) : d(den), inv(1.0 / double(den)) {}
  uint64_t operator()(uint64_t v) const {
    uint64_t q = uint64_t(double(v) * inv);
    while (q * d > v) --q;
    while ((q + 1) * d <= v) ++q;
    return q;
  }
};

struct Dividers {
  Divider x, y;
  explicit Dividers(const Job& j) : x(j.nx), y(j.ny) {}
};

// The voxels from their linear indices.
template <class Lin>
bool emit_hits(const Job& j, uint32_t b, size_t n, const Lin* lin, const uint8_t* state, uint32_t found,
               HitColumns& hits, uint32_t& count) {
  const Dividers div(j);
  return emit(j, b, n, state, found, hits, count, [&](size_t k, uint32_t* v) {
    const uint64_t li = uint64_t(lin[k]);
    const uint64_t yz = div.x(li), z = div.y(yz);
    v[0] = uint32_t(li - yz * j.nx);
    v[1] = uint32_t(yz - z * j.ny);
    v[2] = uint32_t(z);
  });
}

}  // namespace voxcd::detail
