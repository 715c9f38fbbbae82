// The distance voxmap's block kernel on the node-quad copy (detail/node_quads.h): transform, floor, bounds, the cell's
// eight nodes by one 8-byte read (a gather lane), the trilinear interpolation and the threshold test, eight points at
// a time in AVX-512 registers (four with AVX2). The nodes are stored as q + 2^(SB-1), so a byte shuffle gives each
// one without a sign to extend; the interpolation then yields D + bias exactly (its weights sum to 2^(3 WB)), tested
// against threshold + bias. Each linear step is u0 (2^WB - f) + u1 f: one multiply and one fused multiply-add.
// Every intermediate value is an integer of at most IW <= 51 bits, so the doubles are exact and D is ref/'s.
#include <cmath>
#include <cstring>

#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/quad_interp.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define VOXCD_QUAD_X86 1
#endif

namespace voxcd::detail {

namespace {

// One point, for the baseline and the AVX2 kernel's tail.
inline uint32_t quad_point(const int32_t* x, const int32_t* y, const int32_t* z, size_t k, const DistanceJob& J,
                           uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  const double px = x[k], py = y[k], pz = z[k];
  const double W = J.weight;
  const double s[3] = {std::floor(J.m[0] * px + J.m[1] * py + J.m[2] * pz + J.t[0]),
                       std::floor(J.m[3] * px + J.m[4] * py + J.m[5] * pz + J.t[1]),
                       std::floor(J.m[6] * px + J.m[7] * py + J.m[8] * pz + J.t[2])};
  double c[3], f[3], g[3];
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    c[i] = std::floor(s[i] * J.inv_weight);
    f[i] = s[i] - c[i] * W;
    g[i] = W - f[i];
    inside &= c[i] >= 0 && c[i] < J.n[i];
  }
  hit[k] = 0;
  if (!inside) return 0;
  const int32_t X = int32_t(c[0]), Y = int32_t(c[1]), Z = int32_t(c[2]);
  const size_t e = size_t(X) + size_t(J.nx1) * (size_t(Y) + size_t(J.n[1]) * size_t(Z));
  uint64_t w;
  std::memcpy(&w, J.quads + e, sizeof w);
  double u[8];  // byte b: node (X + (b >> 2), Y + (b & 1), Z + (b >> 1 & 1))
  for (int b = 0; b < 8; ++b) u[b] = double((w >> (8 * b)) & 0xffu);
  double a[4];
  for (int b = 0; b < 4; ++b) a[b] = u[b] * g[0] + u[b + 4] * f[0];
  const double b0 = a[0] * g[1] + a[1] * f[1], b1 = a[2] * g[1] + a[3] * f[1];
  const double d = b0 * g[2] + b1 * f[2];
  if (!(d <= J.biased_threshold)) return 0;
  hit[k] = 1, cx[k] = X, cy[k] = Y, cz[k] = Z, dist[k] = d - J.bias;
  return 1;
}

uint32_t quad_base(const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const DistanceJob& J,
                   uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  uint32_t count = 0;
  for (size_t k = 0; k < n; ++k) count += quad_point(x, y, z, k, J, hit, cx, cy, cz, dist);
  return count;
}

#ifdef VOXCD_QUAD_X86
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t quad_avx512(
    const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const DistanceJob& J, uint8_t* hit, int32_t* cx,
    int32_t* cy, int32_t* cz, double* dist) {
  __m512d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm512_set1_pd(J.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm512_set1_pd(J.t[i]), nn[i] = _mm512_set1_pd(J.n[i]);
  const __m512d W = _mm512_set1_pd(J.weight), iW = _mm512_set1_pd(J.inv_weight);
  const __m512d thr = _mm512_set1_pd(J.biased_threshold), bias = _mm512_set1_pd(J.bias);
  const __m512d nx1 = _mm512_set1_pd(J.nx1), zero = _mm512_setzero_pd();
  __m512i sel[8];
  for (int b = 0; b < 8; ++b) sel[b] = _mm512_set_epi64(shuffle_hi(b), shuffle_lo(b), shuffle_hi(b), shuffle_lo(b),
                                                        shuffle_hi(b), shuffle_lo(b), shuffle_hi(b), shuffle_lo(b));
  uint32_t count = 0;
  for (size_t k = 0; k < n; k += 8) {
    const __mmask8 live = n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - k)) - 1);
    const __m512d p[3] = {_mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, x + k)),
                          _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, y + k)),
                          _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, z + k))};
    __m512d c[3], f[3], g[3];
    __mmask8 in = live;
    for (int i = 0; i < 3; ++i) {
      const __m512d a =
          _mm512_fmadd_pd(m[3 * i], p[0], _mm512_fmadd_pd(m[3 * i + 1], p[1], _mm512_fmadd_pd(m[3 * i + 2], p[2], t[i])));
      const __m512d s = _mm512_roundscale_pd(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
      c[i] = _mm512_roundscale_pd(_mm512_mul_pd(s, iW), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
      f[i] = _mm512_fnmadd_pd(c[i], W, s);
      g[i] = _mm512_sub_pd(W, f[i]);
      in = _mm512_mask_cmp_pd_mask(in, c[i], zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, c[i], nn[i], _CMP_LT_OQ);
    }
    if (in == 0) {
      _mm_mask_storeu_epi8(hit + k, live, _mm_setzero_si128());
      continue;
    }
    // Inside lanes: the entry is below 2^31 (the caller checks); outside lanes read nothing.
    const __m256i e = _mm512_cvttpd_epi32(_mm512_fmadd_pd(_mm512_fmadd_pd(c[2], nn[1], c[1]), nx1, c[0]));
    const __m512i w = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), in, e,
                                                  reinterpret_cast<const long long*>(J.quads), 4);
    const __m512d d = interpolate512(w, sel, f, g);
    const __mmask8 h = _mm512_mask_cmp_pd_mask(in, d, thr, _CMP_LE_OQ);
    count += uint32_t(__builtin_popcount(h));
    _mm_mask_storeu_epi8(hit + k, live, _mm512_cvtepi64_epi8(_mm512_maskz_set1_epi64(h, 1)));
    if (h == 0) continue;
    _mm256_mask_storeu_epi32(cx + k, h, _mm512_cvttpd_epi32(c[0]));
    _mm256_mask_storeu_epi32(cy + k, h, _mm512_cvttpd_epi32(c[1]));
    _mm256_mask_storeu_epi32(cz + k, h, _mm512_cvttpd_epi32(c[2]));
    _mm512_mask_storeu_pd(dist + k, h, _mm512_sub_pd(d, bias));
  }
  return count;
}

// Four points a step, the node words by four scalar loads (AVX2's gather is no faster here and slower on some
// processors); a byte in a 64-bit lane becomes a double as the bits of 2^52 + byte, less 2^52. The tail (fewer than
// four) one at a time.
__attribute__((target("avx2,fma"))) uint32_t quad_avx2(const int32_t* x, const int32_t* y, const int32_t* z, size_t n,
                                                       const DistanceJob& J, uint8_t* hit, int32_t* cx, int32_t* cy,
                                                       int32_t* cz, double* dist) {
  __m256d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm256_set1_pd(J.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm256_set1_pd(J.t[i]), nn[i] = _mm256_set1_pd(J.n[i]);
  const __m256d W = _mm256_set1_pd(J.weight), iW = _mm256_set1_pd(J.inv_weight);
  const __m256d thr = _mm256_set1_pd(J.biased_threshold);
  const __m256d nx1 = _mm256_set1_pd(J.nx1), zero = _mm256_setzero_pd();
  const __m256i magic = _mm256_set1_epi64x(0x4330000000000000ll);  // the bits of 2^52
  const __m256d magic_pd = _mm256_castsi256_pd(magic);
  __m256i sel[8];
  for (int b = 0; b < 8; ++b) sel[b] = _mm256_set_epi64x(shuffle_hi(b), shuffle_lo(b), shuffle_hi(b), shuffle_lo(b));
  const char* quads = reinterpret_cast<const char*>(J.quads);
  uint32_t count = 0;
  size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    const __m256d p[3] = {_mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x + k))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(y + k))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(z + k)))};
    __m256d c[3], f[3], g[3], in = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for (int i = 0; i < 3; ++i) {
      const __m256d a =
          _mm256_fmadd_pd(m[3 * i], p[0], _mm256_fmadd_pd(m[3 * i + 1], p[1], _mm256_fmadd_pd(m[3 * i + 2], p[2], t[i])));
      const __m256d s = _mm256_floor_pd(a);
      c[i] = _mm256_floor_pd(_mm256_mul_pd(s, iW));
      f[i] = _mm256_fnmadd_pd(c[i], W, s);
      g[i] = _mm256_sub_pd(W, f[i]);
      in = _mm256_and_pd(in, _mm256_and_pd(_mm256_cmp_pd(c[i], zero, _CMP_GE_OQ), _mm256_cmp_pd(c[i], nn[i], _CMP_LT_OQ)));
    }
    if (_mm256_movemask_pd(in) == 0) {
      std::memset(hit + k, 0, 4);
      continue;
    }
    // Outside lanes read entry 0 (their cells made 0) and are masked below.
    for (int i = 0; i < 3; ++i) c[i] = _mm256_and_pd(c[i], in);
    alignas(16) int32_t e[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(e),
                    _mm256_cvttpd_epi32(_mm256_fmadd_pd(_mm256_fmadd_pd(c[2], nn[1], c[1]), nx1, c[0])));
    int64_t wv[4];
    for (int i = 0; i < 4; ++i) std::memcpy(&wv[i], quads + 4 * size_t(uint32_t(e[i])), 8);
    const __m256i w = _mm256_set_epi64x(wv[3], wv[2], wv[1], wv[0]);
    __m256d u[8];
#pragma GCC unroll 8
    for (int b = 0; b < 8; ++b)
      u[b] = _mm256_sub_pd(_mm256_castsi256_pd(_mm256_or_si256(_mm256_shuffle_epi8(w, sel[b]), magic)), magic_pd);
    const __m256d a0 = step256(u[0], u[4], f[0], g[0]), a1 = step256(u[1], u[5], f[0], g[0]);
    const __m256d a2 = step256(u[2], u[6], f[0], g[0]), a3 = step256(u[3], u[7], f[0], g[0]);
    const __m256d d = step256(step256(a0, a1, f[1], g[1]), step256(a2, a3, f[1], g[1]), f[2], g[2]);
    const int h = _mm256_movemask_pd(_mm256_and_pd(in, _mm256_cmp_pd(d, thr, _CMP_LE_OQ)));
    for (int i = 0; i < 4; ++i) hit[k + size_t(i)] = uint8_t(h >> i & 1);
    if (h) count += put_hits4(h, d, c, J.bias, cx + k, cy + k, cz + k, dist + k);
  }
  for (; k < n; ++k) count += quad_point(x, y, z, k, J, hit, cx, cy, cz, dist);
  return count;
}
#pragma GCC diagnostic pop
#endif

struct Choice {
  DistanceBlockFn fn;
  const char* name;
};

Choice choose() {
  switch (widest_kernel()) {
#ifdef VOXCD_QUAD_X86
    case KernelWidth::Avx512: return {quad_avx512, "avx512"};
    case KernelWidth::Avx2: return {quad_avx2, "avx2"};
#endif
    default: return {quad_base, "baseline"};
  }
}

const Choice kChoice = choose();

}  // namespace

DistanceBlockFn distance_quad_block() { return kChoice.fn; }
const char* distance_quad_block_name() { return kChoice.name; }

}  // namespace voxcd::detail
