#include "voxcd/host/pairs/detail/cull.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define VOXCD_CULL_AVX512 1
#endif

namespace voxcd::detail {

namespace {

constexpr double kSlack = 1e-4;

// All three axes of a box in one pass, without branches, the bits gathered in a register.
void cull_portable(const ClusterBoxes& b, const double (&M)[3][3], const double (&aM)[3][3], const double (&lo)[3],
                   const double (&hi)[3], uint64_t* __restrict bits) {
  const double* __restrict cx = b.centre[0];
  const double* __restrict cy = b.centre[1];
  const double* __restrict cz = b.centre[2];
  const double* __restrict hx = b.half[0];
  const double* __restrict hy = b.half[1];
  const double* __restrict hz = b.half[2];
  for (size_t w = 0; w * 64 < b.n; ++w) {
    uint64_t word = 0;
    const size_t end = std::min(b.n, w * 64 + 64);
    for (size_t k = w * 64; k < end; ++k) {
      bool in = true;
      for (int i = 0; i < 3; ++i) {
        const double c = M[i][0] * cx[k] + M[i][1] * cy[k] + M[i][2] * cz[k];
        const double h = aM[i][0] * hx[k] + aM[i][1] * hy[k] + aM[i][2] * hz[k];
        in &= (c + h >= lo[i]) & (c - h < hi[i]);
      }
      word |= uint64_t(in) << (k & 63);
    }
    bits[w] = word;
  }
}

#ifdef VOXCD_CULL_AVX512
bool have_avx512f() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f");
}

// Eight boxes a step (the portable loop was a tenth of a frame of `voxcd simulate`).
__attribute__((target("avx512f"))) void cull_avx512(const ClusterBoxes& b, const double (&M)[3][3],
                                                    const double (&aM)[3][3], const double (&lo)[3],
                                                    const double (&hi)[3], uint64_t* __restrict bits) {
  __m512d m[3][3], a[3][3], vlo[3], vhi[3];
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) m[i][k] = _mm512_set1_pd(M[i][k]), a[i][k] = _mm512_set1_pd(aM[i][k]);
    vlo[i] = _mm512_set1_pd(lo[i]);
    vhi[i] = _mm512_set1_pd(hi[i]);
  }
  std::fill(bits, bits + (b.n + 63) / 64, uint64_t(0));
  for (size_t k = 0; k < b.n; k += 8) {
    const __mmask8 live = b.n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (b.n - k)) - 1);
    __m512d c[3], h[3];
    for (int i = 0; i < 3; ++i) {
      c[i] = _mm512_maskz_loadu_pd(live, b.centre[i] + k);
      h[i] = _mm512_maskz_loadu_pd(live, b.half[i] + k);
    }
    __mmask8 in = live;
    for (int i = 0; i < 3; ++i) {
      const __m512d ci = _mm512_fmadd_pd(m[i][2], c[2], _mm512_fmadd_pd(m[i][1], c[1], _mm512_mul_pd(m[i][0], c[0])));
      const __m512d hi_ = _mm512_fmadd_pd(a[i][2], h[2], _mm512_fmadd_pd(a[i][1], h[1], _mm512_mul_pd(a[i][0], h[0])));
      in = _mm512_mask_cmp_pd_mask(in, _mm512_add_pd(ci, hi_), vlo[i], _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, _mm512_sub_pd(ci, hi_), vhi[i], _CMP_LT_OQ);
    }
    bits[k >> 6] |= uint64_t(in) << (k & 63);
  }
}
#endif

}  // namespace

bool cull_is_vector() {
#ifdef VOXCD_CULL_AVX512
  static const bool have = have_avx512f();
  return have;
#else
  return false;
#endif
}

void cull_clusters(const ClusterBoxes& boxes, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
                   const double (&n)[3], uint64_t* bits, bool vector) {
  double lo[3], hi[3];
  for (int i = 0; i < 3; ++i) lo[i] = -kSlack - t[i], hi[i] = n[i] + kSlack - t[i];
#ifdef VOXCD_CULL_AVX512
  if (vector && cull_is_vector()) return cull_avx512(boxes, M, aM, lo, hi, bits);
#else
  (void)vector;
#endif
  cull_portable(boxes, M, aM, lo, hi, bits);
}

namespace {

// One box: cleared from `bits` when its voxels can hold no hit.
void cull_box(const ClusterBoxes& b, size_t k, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
              const HitTest& test, uint64_t* bits);

#ifdef VOXCD_CULL_AVX512
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
// cull_empty's common case eight boxes a step: a mask of surface and interior states, each box cut to the grid, its
// centre voxel's distance to the nearest such block (EmptySpace::Near) read by one gather.
__attribute__((target("avx512f,avx512dq,avx512vl"))) void cull_near_avx512(
    const ClusterBoxes& b, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
    const HitTest& test, const EmptySpace::Near& near, uint64_t* bits) {
  __m512d m[3][3], a[3][3], vt[3], vn[3];
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) m[i][k] = _mm512_set1_pd(M[i][k]), a[i][k] = _mm512_set1_pd(aM[i][k]);
    vt[i] = _mm512_set1_pd(t[i]);
    vn[i] = _mm512_set1_pd(test.n[i]);
  }
  const __m512d slack = _mm512_set1_pd(kSlack), zero = _mm512_setzero_pd(), half = _mm512_set1_pd(0.5);
  const __m512d onep = _mm512_set1_pd(1);
  const __m128i base = _mm_cvtsi32_si128(near.base);
  const __m256i bx = _mm256_set1_epi32(int32_t(near.dims[0])), by = _mm256_set1_epi32(int32_t(near.dims[1]));
  const __m256i round = _mm256_set1_epi32((1 << near.base) - 1), one = _mm256_set1_epi32(1);
  const __m256i byte = _mm256_set1_epi32(0xff);
  for (size_t k = 0; k < b.n; k += 8) {
    const __mmask8 live = __mmask8(bits[k >> 6] >> (k & 63));
    if (!live) continue;
    __m512d mid[3], reach = zero;
    const __m512d c[3] = {_mm512_maskz_loadu_pd(live, b.centre[0] + k), _mm512_maskz_loadu_pd(live, b.centre[1] + k),
                          _mm512_maskz_loadu_pd(live, b.centre[2] + k)};
    const __m512d h[3] = {_mm512_maskz_loadu_pd(live, b.half[0] + k), _mm512_maskz_loadu_pd(live, b.half[1] + k),
                          _mm512_maskz_loadu_pd(live, b.half[2] + k)};
    for (int i = 0; i < 3; ++i) {
      const __m512d ci = _mm512_add_pd(_mm512_fmadd_pd(m[i][2], c[2], _mm512_fmadd_pd(m[i][1], c[1], _mm512_mul_pd(m[i][0], c[0]))), vt[i]);
      const __m512d hi = _mm512_add_pd(_mm512_fmadd_pd(a[i][2], h[2], _mm512_fmadd_pd(a[i][1], h[1], _mm512_mul_pd(a[i][0], h[0]))), slack);
      // The box cut to the grid: its centre's voxel (in the grid) and half-extent.
      const __m512d l = _mm512_max_pd(_mm512_sub_pd(ci, hi), zero), u = _mm512_min_pd(_mm512_add_pd(ci, hi), vn[i]);
      const __m512d m0 = _mm512_roundscale_pd(_mm512_mul_pd(_mm512_add_pd(l, u), half), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
      mid[i] = _mm512_min_pd(_mm512_max_pd(m0, zero), _mm512_sub_pd(vn[i], onep));
      reach = _mm512_max_pd(reach, _mm512_mul_pd(_mm512_max_pd(_mm512_sub_pd(u, l), zero), half));
    }
    // r = floor(reach) + 1 voxels, in blocks ceil(r / 2^base); the centre's block.
    const __m256i r = _mm256_add_epi32(_mm512_cvttpd_epi32(reach), one);
    const __m256i rb = _mm256_sra_epi32(_mm256_add_epi32(r, round), base);
    const __m256i ix = _mm256_sra_epi32(_mm512_cvttpd_epi32(mid[0]), base);
    const __m256i iy = _mm256_sra_epi32(_mm512_cvttpd_epi32(mid[1]), base);
    const __m256i iz = _mm256_sra_epi32(_mm512_cvttpd_epi32(mid[2]), base);
    const __m256i idx = _mm256_maskz_mov_epi32(live, _mm256_add_epi32(ix, _mm256_mullo_epi32(bx, _mm256_add_epi32(iy, _mm256_mullo_epi32(by, iz)))));
    const __m256i d = _mm256_and_si256(
        _mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), live, idx, reinterpret_cast<const int*>(near.d), 1), byte);
    const __mmask8 far = _mm256_mask_cmpgt_epi32_mask(live, d, rb);
    bits[k >> 6] &= ~(uint64_t(far) << (k & 63));
  }
}
#pragma GCC diagnostic pop
#endif

void cull_box(const ClusterBoxes& b, size_t k, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
              const HitTest& test, uint64_t* bits) {
  {
    {
      std::array<int64_t, 3> lo, hi, mid;
      double reach = 0;
      for (int i = 0; i < 3; ++i) {
        const double c = M[i][0] * b.centre[0][k] + M[i][1] * b.centre[1][k] + M[i][2] * b.centre[2][k] + t[i];
        const double h = aM[i][0] * b.half[0][k] + aM[i][1] * b.half[1][k] + aM[i][2] * b.half[2][k] + kSlack;
        lo[size_t(i)] = int64_t(std::floor(c - h));
        hi[size_t(i)] = int64_t(std::floor(c + h));
        // The box cut to the grid (points outside it are no lookup): its centre and half-extent.
        const double l = std::max(c - h, 0.0), u = std::min(c + h, test.n[i]);
        mid[size_t(i)] = std::clamp<int64_t>(int64_t(std::floor(0.5 * (l + u))), 0, int64_t(test.n[i]) - 1);
        reach = std::max(reach, 0.5 * std::max(u - l, 0.0));
      }
      // For a mask of surface and interior states: one read of the distance to the nearest such voxel from the voxel
      // of the cut box's centre (every voxel a point of the box can land in is within floor(h) + 1 of it per axis).
      bool may;
      if (!test.field && (test.mask & ~6u) == 0)
        may = test.space->may_hit_near(mid, int64_t(reach) + 1);
      else
        may = test.field ? test.space->may_hit_field(lo, hi, test.threshold, test.wb)
                         : test.space->may_hit_states(lo, hi, test.mask);
      if (!may) bits[k >> 6] &= ~(uint64_t{1} << (k & 63));
    }
  }
}

}  // namespace

void cull_empty(const ClusterBoxes& b, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
                const HitTest& test, uint64_t* bits) {
  if (!test.space || test.space->empty()) return;
#ifdef VOXCD_CULL_AVX512
  const EmptySpace::Near near = test.space->near();
  if (cull_is_vector() && near.d && !test.field && (test.mask & ~6u) == 0)
    return cull_near_avx512(b, M, aM, t, test, near, bits);
#endif
  for (size_t w = 0; w * 64 < b.n; ++w)
    for (uint64_t x = bits[w]; x; x &= x - 1) cull_box(b, w * 64 + size_t(__builtin_ctzll(x)), M, aM, t, test, bits);
}

}  // namespace voxcd::detail
