// The distance voxmap's block kernel (detail/distance_kernel.h): transform, floor, bounds, the eight node values
// from their parity banks (docs/contract.md, "Distance voxmaps"), the trilinear interpolation and the threshold test,
// eight points at a time in AVX-512 registers (four with AVX2), the node words by gather instructions. Every
// intermediate value is an integer below 2^53, so the doubles (and fused multiply-adds) are exact.
#include "voxcd/ref/fast/detail/distance_kernel.h"

#include <cmath>
#include <cstdlib>
#include <string>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define VOXCD_DISTANCE_X86 1
#endif

namespace voxcd::detail {

namespace {

// One point, for the baseline and the vector kernels' tails.
inline uint32_t distance_point(const int32_t* x, const int32_t* y, const int32_t* z, size_t k, const DistanceJob& J,
                               uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  const double px = x[k], py = y[k], pz = z[k];
  const double W = J.weight;
  const double s[3] = {std::floor(J.m[0] * px + J.m[1] * py + J.m[2] * pz + J.t[0]),
                       std::floor(J.m[3] * px + J.m[4] * py + J.m[5] * pz + J.t[1]),
                       std::floor(J.m[6] * px + J.m[7] * py + J.m[8] * pz + J.t[2])};
  double c[3], f[3];
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    c[i] = std::floor(s[i] * J.inv_weight);
    f[i] = s[i] - c[i] * W;
    inside &= c[i] >= 0 && c[i] < J.n[i];
  }
  hit[k] = 0;
  if (!inside) return 0;
  const int32_t X = int32_t(c[0]), Y = int32_t(c[1]), Z = int32_t(c[2]);
  const int32_t slot_mask = (int32_t{1} << J.npw_bits) - 1;
  const uint64_t vmask = (uint64_t{1} << J.sb) - 1, sign = uint64_t{1} << (J.sb - 1);
  double q[8];
  for (int n = 0; n < 8; ++n) {
    const int32_t Xc = X + (n & 1), Yc = Y + (n >> 1 & 1), Zc = Z + (n >> 2 & 1);
    const int32_t h = (Xc >> 1) + J.hx * ((Yc >> 1) + J.hy * (Zc >> 1));
    const int32_t bank = (Xc & 1) | (Yc & 1) << 1 | (Zc & 1) << 2;
    const uint64_t raw = (J.map[8 * (h >> J.npw_bits) + bank] >> (J.sb * (h & slot_mask))) & vmask;
    q[n] = double(int64_t(raw ^ sign) - int64_t(sign));
  }
  const double a0 = q[0] * W + (q[1] - q[0]) * f[0], a1 = q[2] * W + (q[3] - q[2]) * f[0];
  const double a2 = q[4] * W + (q[5] - q[4]) * f[0], a3 = q[6] * W + (q[7] - q[6]) * f[0];
  const double b0 = a0 * W + (a1 - a0) * f[1], b1 = a2 * W + (a3 - a2) * f[1];
  const double d = b0 * W + (b1 - b0) * f[2];
  if (!(d <= J.threshold)) return 0;
  hit[k] = 1, cx[k] = X, cy[k] = Y, cz[k] = Z, dist[k] = d;
  return 1;
}

uint32_t distance_base(const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const DistanceJob& J,
                       uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  uint32_t count = 0;
  for (size_t k = 0; k < n; ++k) count += distance_point(x, y, z, k, J, hit, cx, cy, cz, dist);
  return count;
}

#ifdef VOXCD_DISTANCE_X86
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// a * 2^WB + (b - a) * f, exact on integers below 2^53.
__attribute__((target("avx512f,fma"), always_inline)) inline __m512d lerp512(__m512d a, __m512d b, __m512d f,
                                                                             __m512d W) {
  return _mm512_fmadd_pd(_mm512_sub_pd(b, a), f, _mm512_mul_pd(a, W));
}
__attribute__((target("avx2,fma"), always_inline)) inline __m256d lerp256(__m256d a, __m256d b, __m256d f, __m256d W) {
  return _mm256_fmadd_pd(_mm256_sub_pd(b, a), f, _mm256_mul_pd(a, W));
}

// The eight node values of eight cells (in lanes `in`) from their parity banks, per axis the cells' two halves and
// two parities given: per (dy, dz) the half-index's y and z part and the bank's y and z bits, then per corner one add
// and one or, the word by a gather, the node's bits shifted down and sign-extended.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"), always_inline)) inline void nodes512(
    const DistanceJob& J, __mmask8 in, const __m256i (&half)[3][2], const __m256i (&par)[3][2], __m256i hx,
    __m256i hxy, __m256i slot_mask, __m128i npw, __m128i sb_shift, __m512i vmask, __m512i sign, __m512d (&q)[8]) {
  __m256i row[4], rbank[4];
  for (int r = 0; r < 4; ++r) {
    row[r] = _mm256_add_epi32(_mm256_mullo_epi32(hx, half[1][r & 1]), _mm256_mullo_epi32(hxy, half[2][r >> 1]));
    rbank[r] = _mm256_or_si256(par[1][r & 1], par[2][r >> 1]);
  }
#pragma GCC unroll 8
  for (int cn = 0; cn < 8; ++cn) {
    const __m256i h = _mm256_add_epi32(half[0][cn & 1], row[cn >> 1]);
    const __m256i word = _mm256_or_si256(_mm256_slli_epi32(_mm256_sra_epi32(h, npw), 3),
                                         _mm256_or_si256(par[0][cn & 1], rbank[cn >> 1]));
    const __m256i slot = _mm256_sll_epi32(_mm256_and_si256(h, slot_mask), sb_shift);
    const __m512i w = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), in, word,
                                                  reinterpret_cast<const long long*>(J.map), 8);
    const __m512i raw = _mm512_and_si512(_mm512_srlv_epi64(w, _mm512_cvtepu32_epi64(slot)), vmask);
    q[cn] = _mm512_cvtepi64_pd(_mm512_sub_epi64(_mm512_xor_si512(raw, sign), sign));
  }
}

// Eight points a step. The node of corner (dx, dy, dz) of cell (X, Y, Z) is in bank (X+dx)&1 | ... at half-index
// ((X+dx)>>1) + hx ((Y+dy)>>1) + hx hy ((Z+dz)>>1): per axis two halves and two parities, combined per corner.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t distance_avx512(
    const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const DistanceJob& J, uint8_t* hit, int32_t* cx,
    int32_t* cy, int32_t* cz, double* dist) {
  __m512d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm512_set1_pd(J.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm512_set1_pd(J.t[i]), nn[i] = _mm512_set1_pd(J.n[i]);
  const __m512d W = _mm512_set1_pd(J.weight), iW = _mm512_set1_pd(J.inv_weight), thr = _mm512_set1_pd(J.threshold);
  const __m512d zero = _mm512_setzero_pd();
  const __m256i hx = _mm256_set1_epi32(J.hx), hxy = _mm256_set1_epi32(J.hx * J.hy), one = _mm256_set1_epi32(1);
  const __m256i slot_mask = _mm256_set1_epi32((1 << J.npw_bits) - 1);
  const __m128i npw = _mm_cvtsi32_si128(J.npw_bits), sb_shift = _mm_cvtsi32_si128(J.sb_bits);
  const __m512i vmask = _mm512_set1_epi64(int64_t((uint64_t{1} << J.sb) - 1));
  const __m512i sign = _mm512_set1_epi64(int64_t(uint64_t{1} << (J.sb - 1)));
  uint32_t count = 0;
  for (size_t k = 0; k < n; k += 8) {
    const __mmask8 live = n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - k)) - 1);
    const __m512d p[3] = {_mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, x + k)),
                          _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, y + k)),
                          _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, z + k))};
    __m512d c[3], f[3];
    __mmask8 in = live;
    for (int i = 0; i < 3; ++i) {
      const __m512d a = _mm512_fmadd_pd(m[3 * i], p[0], _mm512_fmadd_pd(m[3 * i + 1], p[1], _mm512_fmadd_pd(m[3 * i + 2], p[2], t[i])));
      const __m512d s = _mm512_roundscale_pd(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
      c[i] = _mm512_roundscale_pd(_mm512_mul_pd(s, iW), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
      f[i] = _mm512_fnmadd_pd(c[i], W, s);
      in = _mm512_mask_cmp_pd_mask(in, c[i], zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, c[i], nn[i], _CMP_LT_OQ);
    }
    if (in == 0) {
      _mm_mask_storeu_epi8(hit + k, live, _mm_setzero_si128());
      continue;
    }
    __m256i X[3], half[3][2], par[3][2];
    for (int i = 0; i < 3; ++i) {
      X[i] = _mm256_maskz_mov_epi32(in, _mm512_cvttpd_epi32(c[i]));
      half[i][0] = _mm256_srai_epi32(X[i], 1);
      half[i][1] = _mm256_srai_epi32(_mm256_add_epi32(X[i], one), 1);
      par[i][0] = _mm256_slli_epi32(_mm256_and_si256(X[i], one), i);
      par[i][1] = _mm256_xor_si256(par[i][0], _mm256_set1_epi32(1 << i));
    }
    __m512d q[8];
    nodes512(J, in, half, par, hx, hxy, slot_mask, npw, sb_shift, vmask, sign, q);
    // a * 2^WB + (b - a) * f, x then y then z: exact integers.
    const __m512d a0 = lerp512(q[0], q[1], f[0], W), a1 = lerp512(q[2], q[3], f[0], W);
    const __m512d a2 = lerp512(q[4], q[5], f[0], W), a3 = lerp512(q[6], q[7], f[0], W);
    const __m512d d = lerp512(lerp512(a0, a1, f[1], W), lerp512(a2, a3, f[1], W), f[2], W);
    const __mmask8 h = _mm512_mask_cmp_pd_mask(in, d, thr, _CMP_LE_OQ);
    count += uint32_t(__builtin_popcount(h));
    _mm_mask_storeu_epi8(hit + k, live, _mm512_cvtepi64_epi8(_mm512_maskz_set1_epi64(h, 1)));
    if (h == 0) continue;
    _mm256_mask_storeu_epi32(cx + k, h, X[0]);
    _mm256_mask_storeu_epi32(cy + k, h, X[1]);
    _mm256_mask_storeu_epi32(cz + k, h, X[2]);
    _mm512_mask_storeu_pd(dist + k, h, d);
  }
  return count;
}

// nodes512 for four cells with AVX2 (outside lanes read word 0 of the map: their cells were made 0).
__attribute__((target("avx2,fma"), always_inline)) inline void nodes256(
    const DistanceJob& J, const __m128i (&half)[3][2], const __m128i (&par)[3][2], __m128i hx, __m128i hxy,
    __m128i slot_mask, __m128i npw, __m128i sb_shift, __m256i vmask, __m128i sign, __m256i low32, __m256d (&q)[8]) {
  __m128i row[4], rbank[4];
  for (int r = 0; r < 4; ++r) {
    row[r] = _mm_add_epi32(_mm_mullo_epi32(hx, half[1][r & 1]), _mm_mullo_epi32(hxy, half[2][r >> 1]));
    rbank[r] = _mm_or_si128(par[1][r & 1], par[2][r >> 1]);
  }
#pragma GCC unroll 8
  for (int cn = 0; cn < 8; ++cn) {
    const __m128i h = _mm_add_epi32(half[0][cn & 1], row[cn >> 1]);
    const __m128i word = _mm_or_si128(_mm_slli_epi32(_mm_sra_epi32(h, npw), 3), _mm_or_si128(par[0][cn & 1], rbank[cn >> 1]));
    const __m128i slot = _mm_sll_epi32(_mm_and_si128(h, slot_mask), sb_shift);
    // Four scalar loads: AVX2's gather is no faster here and slower on some processors.
    alignas(16) int32_t wi[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(wi), word);
    const __m256i w = _mm256_set_epi64x(int64_t(J.map[wi[3]]), int64_t(J.map[wi[2]]), int64_t(J.map[wi[1]]),
                                        int64_t(J.map[wi[0]]));
    const __m256i raw = _mm256_and_si256(_mm256_srlv_epi64(w, _mm256_cvtepu32_epi64(slot)), vmask);
    // The node value fits 16 bits: its low 32 bits, sign-extended from SB bits.
    const __m128i r32 = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(raw, low32));
    q[cn] = _mm256_cvtepi32_pd(_mm_sub_epi32(_mm_xor_si128(r32, sign), sign));
  }
}

// Four points a step; the tail (fewer than four) one at a time.
__attribute__((target("avx2,fma"))) uint32_t distance_avx2(const int32_t* x, const int32_t* y, const int32_t* z,
                                                            size_t n, const DistanceJob& J, uint8_t* hit,
                                                            int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  __m256d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm256_set1_pd(J.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm256_set1_pd(J.t[i]), nn[i] = _mm256_set1_pd(J.n[i]);
  const __m256d W = _mm256_set1_pd(J.weight), iW = _mm256_set1_pd(J.inv_weight), thr = _mm256_set1_pd(J.threshold);
  const __m256d zero = _mm256_setzero_pd();
  const __m128i hx = _mm_set1_epi32(J.hx), hxy = _mm_set1_epi32(J.hx * J.hy), one = _mm_set1_epi32(1);
  const __m128i slot_mask = _mm_set1_epi32((1 << J.npw_bits) - 1);
  const __m128i npw = _mm_cvtsi32_si128(J.npw_bits), sb_shift = _mm_cvtsi32_si128(J.sb_bits);
  const __m256i vmask = _mm256_set1_epi64x(int64_t((uint64_t{1} << J.sb) - 1));
  const __m128i sign = _mm_set1_epi32(int32_t(1) << (J.sb - 1));
  const __m256i low32 = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
  uint32_t count = 0;
  size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    const __m256d p[3] = {_mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x + k))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(y + k))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(z + k)))};
    __m256d c[3], f[3], in = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for (int i = 0; i < 3; ++i) {
      const __m256d a = _mm256_fmadd_pd(m[3 * i], p[0], _mm256_fmadd_pd(m[3 * i + 1], p[1], _mm256_fmadd_pd(m[3 * i + 2], p[2], t[i])));
      const __m256d s = _mm256_floor_pd(a);
      c[i] = _mm256_floor_pd(_mm256_mul_pd(s, iW));
      f[i] = _mm256_fnmadd_pd(c[i], W, s);
      in = _mm256_and_pd(in, _mm256_and_pd(_mm256_cmp_pd(c[i], zero, _CMP_GE_OQ), _mm256_cmp_pd(c[i], nn[i], _CMP_LT_OQ)));
    }
    if (_mm256_movemask_pd(in) == 0) {
      for (int i = 0; i < 4; ++i) hit[k + size_t(i)] = 0;
      continue;
    }
    __m128i X[3], half[3][2], par[3][2];
    for (int i = 0; i < 3; ++i) {
      X[i] = _mm256_cvttpd_epi32(_mm256_and_pd(c[i], in));  // outside lanes: cell 0
      half[i][0] = _mm_srai_epi32(X[i], 1);
      half[i][1] = _mm_srai_epi32(_mm_add_epi32(X[i], one), 1);
      par[i][0] = _mm_slli_epi32(_mm_and_si128(X[i], one), i);
      par[i][1] = _mm_xor_si128(par[i][0], _mm_set1_epi32(1 << i));
    }
    __m256d q[8];
    nodes256(J, half, par, hx, hxy, slot_mask, npw, sb_shift, vmask, sign, low32, q);
    const __m256d a0 = lerp256(q[0], q[1], f[0], W), a1 = lerp256(q[2], q[3], f[0], W);
    const __m256d a2 = lerp256(q[4], q[5], f[0], W), a3 = lerp256(q[6], q[7], f[0], W);
    const __m256d d = lerp256(lerp256(a0, a1, f[1], W), lerp256(a2, a3, f[1], W), f[2], W);
    const int h = _mm256_movemask_pd(_mm256_and_pd(in, _mm256_cmp_pd(d, thr, _CMP_LE_OQ)));
    alignas(32) double dd[4];
    alignas(16) int32_t xs[3][4];
    _mm256_store_pd(dd, d);
    for (int i = 0; i < 3; ++i) _mm_store_si128(reinterpret_cast<__m128i*>(xs[i]), X[i]);
    for (int i = 0; i < 4; ++i) {
      const size_t kk = k + size_t(i);
      hit[kk] = uint8_t(h >> i & 1);
      if (!(h >> i & 1)) continue;
      cx[kk] = xs[0][i], cy[kk] = xs[1][i], cz[kk] = xs[2][i], dist[kk] = dd[i];
      ++count;
    }
  }
  for (; k < n; ++k) count += distance_point(x, y, z, k, J, hit, cx, cy, cz, dist);
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
#ifdef VOXCD_DISTANCE_X86
    case KernelWidth::Avx512: return {distance_avx512, "avx512"};
    case KernelWidth::Avx2: return {distance_avx2, "avx2"};
#endif
    default: return {distance_base, "baseline"};
  }
}

const Choice kChoice = choose();

}  // namespace

bool cpu_has_avx512() {
#ifdef VOXCD_DISTANCE_X86
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw");
#else
  return false;
#endif
}

KernelWidth widest_kernel() {
#ifdef VOXCD_DISTANCE_X86
  __builtin_cpu_init();
  const std::string want = kernel_override();
  if (cpu_has_avx512() && (want.empty() || want == "avx512")) return KernelWidth::Avx512;
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && want != "baseline") return KernelWidth::Avx2;
#endif
  return KernelWidth::Baseline;
}

std::string kernel_override() {
  const char* v = std::getenv("VOXCD_KERNEL");
  return v ? std::string(v) : std::string();
}

DistanceBlockFn distance_block() { return kChoice.fn; }
const char* distance_block_name() { return kChoice.name; }

}  // namespace voxcd::detail
