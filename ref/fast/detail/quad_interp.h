// Internal to FastRunner's distance kernels on node quads (detail/node_quads.h, detail/sparse_copy.h): a cell's eight
// node bytes (stored as q + 2^(SB-1)) to doubles and their trilinear interpolation, each linear step
// u0 (2^WB - f) + u1 f (one multiply, one fused multiply-add), exact on integers below 2^53.
#pragma once

#include <cstdint>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>

namespace voxcd::detail {

// The byte shuffle that moves byte b of every 64-bit lane to the lane's lowest byte and zeroes the rest (a shuffle
// works within 128 bits: two lanes, bytes 0-7 and 8-15).
inline int64_t shuffle_lo(int b) { return int64_t(0x8080808080808000ull | uint64_t(b)); }
inline int64_t shuffle_hi(int b) { return int64_t(0x8080808080808000ull | uint64_t(8 + b)); }

// u0 (2^WB - f) + u1 f.
__attribute__((target("avx512f,fma"), always_inline)) inline __m512d step512(__m512d u0, __m512d u1, __m512d f,
                                                                             __m512d g) {
  return _mm512_fmadd_pd(u1, f, _mm512_mul_pd(u0, g));
}
__attribute__((target("avx2,fma"), always_inline)) inline __m256d step256(__m256d u0, __m256d u1, __m256d f,
                                                                          __m256d g) {
  return _mm256_fmadd_pd(u1, f, _mm256_mul_pd(u0, g));
}

// The interpolated (biased) distances of eight cells from their eight-byte node words w, weights f and 2^WB - f.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"), always_inline)) inline __m512d interpolate512(
    __m512i w, const __m512i (&sel)[8], const __m512d (&f)[3], const __m512d (&g)[3]) {
  __m512d u[8];
#pragma GCC unroll 8
  for (int b = 0; b < 8; ++b) u[b] = _mm512_cvtepi64_pd(_mm512_shuffle_epi8(w, sel[b]));
  const __m512d a0 = step512(u[0], u[4], f[0], g[0]), a1 = step512(u[1], u[5], f[0], g[0]);
  const __m512d a2 = step512(u[2], u[6], f[0], g[0]), a3 = step512(u[3], u[7], f[0], g[0]);
  return step512(step512(a0, a1, f[1], g[1]), step512(a2, a3, f[1], g[1]), f[2], g[2]);
}

// The hits of mask h among four points: their cells (c) and distances (d less the bias); returns their number.
__attribute__((target("avx2,fma"))) inline uint32_t put_hits4(int h, __m256d d, const __m256d* c, double bias,
                                                               int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  alignas(32) double dd[4];
  alignas(16) int32_t xs[3][4];
  _mm256_store_pd(dd, d);
  for (int i = 0; i < 3; ++i) _mm_store_si128(reinterpret_cast<__m128i*>(xs[i]), _mm256_cvttpd_epi32(c[i]));
  uint32_t count = 0;
  for (int i = 0; i < 4; ++i) {
    if (!(h >> i & 1)) continue;
    cx[i] = xs[0][i], cy[i] = xs[1][i], cz[i] = xs[2][i], dist[i] = dd[i] - bias;
    ++count;
  }
  return count;
}

}  // namespace voxcd::detail
#endif
