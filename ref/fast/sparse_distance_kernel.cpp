// The sparse distance map's block kernel on its node-quad copy (detail/sparse_copy.h): the transform as a =
// acc * 2^-(TF - WB) (exact), the voxel and the bounds, the cell's entry (its brick's level and first quad) by one
// gather, the sub-cell and the weights at the brick's level (floor(a 2^l) = acc >> (TF - WB - l)), the sub-cell's eight
// nodes by a second gather (one 8-byte quad), the interpolation and the threshold test. As ref/'s sub_cell: the
// sub-cell is acc >> (TF - l) within the cell (its low BL + l bits) and its weights the next WB bits. Every value is
// exact in a double (integers below 2^53, and a with TF - WB fraction bits).
#include <cmath>
#include <cstring>

#include "voxcd/ref/fast/detail/sparse_copy.h"
#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/quad_interp.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define VOXCD_BRICK_X86 1
#endif

namespace voxcd::detail {

namespace {

// One point (the baseline, and AVX2 compiled from the same body).
#define VOXCD_BRICK_POINT_BODY                                                                                       \
  {                                                                                                                  \
    const double px = x[k], py = y[k], pz = z[k];                                                                    \
    const double W = J.weight;                                                                                       \
    const double s[3] = {J.m[0] * px + J.m[1] * py + J.m[2] * pz + J.t[0],                                          \
                         J.m[3] * px + J.m[4] * py + J.m[5] * pz + J.t[1],                                           \
                         J.m[6] * px + J.m[7] * py + J.m[8] * pz + J.t[2]};                                          \
    double v[3];                                                                                                     \
    bool inside = true;                                                                                              \
    for (int i = 0; i < 3; ++i) {                                                                                    \
      v[i] = std::floor(std::floor(s[i]) * J.inv_weight);                                                            \
      inside &= v[i] >= 0 && v[i] < J.n[i];                                                                          \
    }                                                                                                                \
    hit[k] = 0;                                                                                                      \
    if (!inside) return 0;                                                                                           \
    const int32_t X = int32_t(v[0]), Y = int32_t(v[1]), Z = int32_t(v[2]);                                           \
    const uint32_t e = J.entries[(X >> J.bl) + J.cx * ((Y >> J.bl) + J.cy * (Z >> J.bl))];                           \
    const int l = int(e >> 30);                                                                                      \
    const int32_t n = J.edge[l];                                                                                     \
    double f[3], g[3];                                                                                               \
    int32_t sub[3];                                                                                                  \
    for (int i = 0; i < 3; ++i) {                                                                                    \
      const double sl = std::floor(s[i] * J.level_scale[l]);                                                         \
      const double c = std::floor(sl * J.inv_weight);                                                                \
      f[i] = sl - c * W, g[i] = W - f[i];                                                                            \
      sub[i] = int32_t(c) & (n - 1);                                                                                 \
    }                                                                                                                \
    uint64_t w;                                                                                                      \
    std::memcpy(&w, J.quads + (e & 0x3fffffffu) + uint32_t(sub[0] + (n + 1) * (sub[1] + n * sub[2])), sizeof w);    \
    double u[8]; /* byte b: node (sub_x + (b >> 2), sub_y + (b & 1), sub_z + (b >> 1 & 1)) */                        \
    for (int b = 0; b < 8; ++b) u[b] = double((w >> (8 * b)) & 0xffu);                                              \
    double a[4];                                                                                                     \
    for (int b = 0; b < 4; ++b) a[b] = u[b] * g[0] + u[b + 4] * f[0];                                                \
    const double b0 = a[0] * g[1] + a[1] * f[1], b1 = a[2] * g[1] + a[3] * f[1];                                     \
    const double d = b0 * g[2] + b1 * f[2];                                                                          \
    if (!(d <= J.biased_threshold)) return 0;                                                                        \
    hit[k] = 1, cx[k] = X, cy[k] = Y, cz[k] = Z, dist[k] = d - J.bias;                                               \
    return 1;                                                                                                        \
  }
#define VOXCD_BRICK_POINT_ARGS                                                                                       \
  const int32_t *x, const int32_t *y, const int32_t *z, size_t k, const BrickQuadJob &J, uint8_t *hit, int32_t *cx, \
      int32_t *cy, int32_t *cz, double *dist

inline uint32_t point_base(VOXCD_BRICK_POINT_ARGS) VOXCD_BRICK_POINT_BODY

uint32_t brick_base(const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const BrickQuadJob& J,
                    uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz, double* dist) {
  uint32_t count = 0;
  for (size_t k = 0; k < n; ++k) count += point_base(x, y, z, k, J, hit, cx, cy, cz, dist);
  return count;
}

#ifdef VOXCD_BRICK_X86
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;

// Four points' quad indices and weights (f, g = 2^WB - f) from their entries (AVX2; their cells' voxels c and the
// accumulators a = acc * 2^-(TF - WB)): every brick of level 0 without the level arithmetic, else per lane.
__attribute__((target("avx2,fma"), always_inline)) inline __m128i quads4(const BrickQuadJob& J, const uint32_t (&e)[4],
                                                                         const __m256d (&a)[3], const __m256d (&c)[3],
                                                                         __m128i (&iv)[3], __m256d (&f)[3],
                                                                         __m256d (&g)[3]) {
  const __m256d W = _mm256_set1_pd(J.weight), iW = _mm256_set1_pd(J.inv_weight);
  const __m128i level = _mm_srli_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(e)), 30);
  __m128i n = _mm_set1_epi32(J.edge[0]), sub[3];
  if (_mm_testz_si128(level, level)) {
    for (int i = 0; i < 3; ++i) {
      f[i] = _mm256_fnmadd_pd(c[i], W, _mm256_floor_pd(a[i]));
      sub[i] = _mm_and_si128(iv[i], _mm_set1_epi32(J.edge[0] - 1));
    }
  } else {
    const uint32_t l[4] = {e[0] >> 30, e[1] >> 30, e[2] >> 30, e[3] >> 30};
    const __m256d scale = _mm256_setr_pd(J.level_scale[l[0]], J.level_scale[l[1]], J.level_scale[l[2]],
                                         J.level_scale[l[3]]);
    n = _mm_setr_epi32(J.edge[l[0]], J.edge[l[1]], J.edge[l[2]], J.edge[l[3]]);
    for (int i = 0; i < 3; ++i) {
      const __m256d sl = _mm256_floor_pd(_mm256_mul_pd(a[i], scale)), cl = _mm256_floor_pd(_mm256_mul_pd(sl, iW));
      f[i] = _mm256_fnmadd_pd(cl, W, sl);
      sub[i] = _mm_and_si128(_mm256_cvttpd_epi32(cl), _mm_sub_epi32(n, _mm_set1_epi32(1)));
    }
  }
  for (int i = 0; i < 3; ++i) g[i] = _mm256_sub_pd(W, f[i]);
  const __m128i off = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(e)), _mm_set1_epi32(0x3fffffff));
  return _mm_add_epi32(_mm_add_epi32(off, sub[0]),
                       _mm_mullo_epi32(_mm_add_epi32(n, _mm_set1_epi32(1)),
                                       _mm_add_epi32(sub[1], _mm_mullo_epi32(n, sub[2]))));
}

// Four points a step, both reads by scalar loads (AVX2's gather is no faster here and slower on some processors);
// the tail (fewer than four) one at a time.
__attribute__((target("avx2,fma"))) uint32_t brick_avx2(const int32_t* x, const int32_t* y, const int32_t* z, size_t n,
                                                        const BrickQuadJob& J, uint8_t* hit, int32_t* cx, int32_t* cy,
                                                        int32_t* cz, double* dist) {
  const __m256d iW = _mm256_set1_pd(J.inv_weight), zero = _mm256_setzero_pd(), thr = _mm256_set1_pd(J.biased_threshold);
  const __m256i magic = _mm256_set1_epi64x(0x4330000000000000ll);  // the bits of 2^52
  const __m128i bl = _mm_cvtsi32_si128(J.bl);
  __m256i sel[8];
  for (int b = 0; b < 8; ++b) sel[b] = _mm256_set_epi64x(shuffle_hi(b), shuffle_lo(b), shuffle_hi(b), shuffle_lo(b));
  const char* quads = reinterpret_cast<const char*>(J.quads);
  uint32_t count = 0;
  size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    __m256d a[3], c[3], in = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    const __m256d p[3] = {_mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x + k))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(y + k))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(z + k)))};
    for (int i = 0; i < 3; ++i) {
      a[i] = _mm256_fmadd_pd(_mm256_set1_pd(J.m[3 * i]), p[0],
                             _mm256_fmadd_pd(_mm256_set1_pd(J.m[3 * i + 1]), p[1],
                                             _mm256_fmadd_pd(_mm256_set1_pd(J.m[3 * i + 2]), p[2],
                                                             _mm256_set1_pd(J.t[i]))));
      c[i] = _mm256_floor_pd(_mm256_mul_pd(_mm256_floor_pd(a[i]), iW));
      in = _mm256_and_pd(in, _mm256_and_pd(_mm256_cmp_pd(c[i], zero, _CMP_GE_OQ),
                                           _mm256_cmp_pd(c[i], _mm256_set1_pd(J.n[i]), _CMP_LT_OQ)));
    }
    if (_mm256_movemask_pd(in) == 0) {
      std::memset(hit + k, 0, 4);
      continue;
    }
    __m128i iv[3];
    for (int i = 0; i < 3; ++i) c[i] = _mm256_and_pd(c[i], in), iv[i] = _mm256_cvttpd_epi32(c[i]);  // outside: 0
    alignas(16) int32_t cell[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(cell),
                    _mm_add_epi32(_mm_srl_epi32(iv[0], bl),
                                  _mm_mullo_epi32(_mm_set1_epi32(J.cx),
                                                  _mm_add_epi32(_mm_srl_epi32(iv[1], bl),
                                                                _mm_mullo_epi32(_mm_set1_epi32(J.cy),
                                                                                _mm_srl_epi32(iv[2], bl))))));
    const uint32_t e[4] = {J.entries[cell[0]], J.entries[cell[1]], J.entries[cell[2]], J.entries[cell[3]]};
    __m256d f[3], g[3];
    alignas(16) int32_t q[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(q), quads4(J, e, a, c, iv, f, g));
    int64_t wv[4];
    for (int i = 0; i < 4; ++i) std::memcpy(&wv[i], quads + 4 * size_t(uint32_t(q[i])), 8);
    const __m256i w = _mm256_set_epi64x(wv[3], wv[2], wv[1], wv[0]);
    __m256d u[8];
#pragma GCC unroll 8
    for (int b = 0; b < 8; ++b)
      u[b] = _mm256_sub_pd(_mm256_castsi256_pd(_mm256_or_si256(_mm256_shuffle_epi8(w, sel[b]), magic)),
                           _mm256_castsi256_pd(magic));
    const __m256d a0 = step256(u[0], u[4], f[0], g[0]), a1 = step256(u[1], u[5], f[0], g[0]);
    const __m256d a2 = step256(u[2], u[6], f[0], g[0]), a3 = step256(u[3], u[7], f[0], g[0]);
    const __m256d d = step256(step256(a0, a1, f[1], g[1]), step256(a2, a3, f[1], g[1]), f[2], g[2]);
    const int h = _mm256_movemask_pd(_mm256_and_pd(in, _mm256_cmp_pd(d, thr, _CMP_LE_OQ)));
    for (int i = 0; i < 4; ++i) hit[k + size_t(i)] = uint8_t(h >> i & 1);
    if (h) count += put_hits4(h, d, c, J.bias, cx + k, cy + k, cz + k, dist + k);
  }
  for (; k < n; ++k) count += point_base(x, y, z, k, J, hit, cx, cy, cz, dist);
  return count;
}


// One group of eight points between the two reads: which are live and inside, their finest steps (acc >> (TF - WB -
// 3)) and voxels, and their cells' entries.
struct Group {
  __mmask8 live, in;
  __m512d a[3];      // acc * 2^-(TF - WB)
  __m256i iv[3], e;  // the voxel (int32; outside lanes 0); the entry
};

// The first half of a group: the transform, the voxels and the bounds, the cells and their entries by one gather.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"), always_inline)) inline void group_entries(
    const BrickQuadJob& J, const __m512d (&m)[9], const __m512d (&t)[3], const __m512d (&nn)[3], const int32_t* x,
    const int32_t* y, const int32_t* z, size_t k, size_t n, Group& g) {
  g.live = n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - k)) - 1);
  const __m512d p[3] = {_mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(g.live, x + k)),
                        _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(g.live, y + k)),
                        _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(g.live, z + k))};
  const __m512d iW = _mm512_set1_pd(J.inv_weight), zero = _mm512_setzero_pd();
  __m512d v[3];
  g.in = g.live;
  for (int i = 0; i < 3; ++i) {
    g.a[i] =
        _mm512_fmadd_pd(m[3 * i], p[0], _mm512_fmadd_pd(m[3 * i + 1], p[1], _mm512_fmadd_pd(m[3 * i + 2], p[2], t[i])));
    v[i] = _mm512_roundscale_pd(_mm512_mul_pd(_mm512_roundscale_pd(g.a[i], kFloor), iW), kFloor);
    g.in = _mm512_mask_cmp_pd_mask(g.in, v[i], zero, _CMP_GE_OQ);
    g.in = _mm512_mask_cmp_pd_mask(g.in, v[i], nn[i], _CMP_LT_OQ);
  }
  const __m128i bl = _mm_cvtsi32_si128(J.bl);
  __m256i c[3];
  for (int i = 0; i < 3; ++i) {
    g.iv[i] = _mm512_maskz_cvttpd_epi32(g.in, v[i]);
    c[i] = _mm256_srl_epi32(g.iv[i], bl);
  }
  const __m256i cell = _mm256_add_epi32(
      c[0], _mm256_mullo_epi32(_mm256_set1_epi32(J.cx),
                               _mm256_add_epi32(c[1], _mm256_mullo_epi32(_mm256_set1_epi32(J.cy), c[2]))));
  g.e = _mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), g.in, cell, J.entries, 4);
}

// The second half: the sub-cells and weights (f, g = 2^WB - f) at each brick's level, the sub-cells' quads by a second
// gather, the interpolation, the threshold test and the outputs; returns the hits.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"), always_inline)) inline uint32_t group_distances(
    const BrickQuadJob& J, const Group& gr, const __m512i (&sel)[8], uint8_t* hit, int32_t* cx, int32_t* cy,
    int32_t* cz, double* dist) {
  if (gr.in == 0) {
    _mm_mask_storeu_epi8(hit, gr.live, _mm_setzero_si128());
    return 0;
  }
  const __m256i level = _mm256_srli_epi32(gr.e, 30);
  const __m512d W = _mm512_set1_pd(J.weight), iW = _mm512_set1_pd(J.inv_weight);
  __m512d f[3], g[3];
  __m256i sub[3], n;
  if (_mm256_testz_si256(level, level)) {  // every brick of level 0: the steps and voxels of the first half
    n = _mm256_set1_epi32(J.edge[0]);
    const __m256i mask = _mm256_set1_epi32(J.edge[0] - 1);
    for (int i = 0; i < 3; ++i) {  // f = floor(a) - 2^WB voxel
      f[i] = _mm512_fnmadd_pd(_mm512_cvtepi32_pd(gr.iv[i]), W, _mm512_roundscale_pd(gr.a[i], kFloor));
      g[i] = _mm512_sub_pd(W, f[i]);
      sub[i] = _mm256_and_si256(gr.iv[i], mask);
    }
  } else {  // level l: the steps of acc * 2^-(TF - WB - l)
    n = _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(J.edge)), level);
    const __m256i mask = _mm256_sub_epi32(n, _mm256_set1_epi32(1));
    const __m512d scale = _mm512_permutexvar_pd(_mm512_cvtepu32_epi64(level), _mm512_loadu_pd(J.level_scale));
    for (int i = 0; i < 3; ++i) {
      const __m512d sl = _mm512_roundscale_pd(_mm512_mul_pd(gr.a[i], scale), kFloor);
      const __m512d cl = _mm512_roundscale_pd(_mm512_mul_pd(sl, iW), kFloor);
      f[i] = _mm512_fnmadd_pd(cl, W, sl);
      g[i] = _mm512_sub_pd(W, f[i]);
      sub[i] = _mm256_and_si256(_mm512_cvttpd_epi32(cl), mask);
    }
  }
  const __m256i q = _mm256_add_epi32(
      _mm256_add_epi32(_mm256_and_si256(gr.e, _mm256_set1_epi32(0x3fffffff)), sub[0]),
      _mm256_mullo_epi32(_mm256_add_epi32(n, _mm256_set1_epi32(1)),
                         _mm256_add_epi32(sub[1], _mm256_mullo_epi32(n, sub[2]))));
  const __m512i w = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), gr.in, q,
                                                reinterpret_cast<const long long*>(J.quads), 4);
  const __m512d d = interpolate512(w, sel, f, g);
  const __mmask8 h = _mm512_mask_cmp_pd_mask(gr.in, d, _mm512_set1_pd(J.biased_threshold), _CMP_LE_OQ);
  _mm_mask_storeu_epi8(hit, gr.live, _mm512_cvtepi64_epi8(_mm512_maskz_set1_epi64(h, 1)));
  if (h == 0) return 0;
  _mm256_mask_storeu_epi32(cx, h, gr.iv[0]);
  _mm256_mask_storeu_epi32(cy, h, gr.iv[1]);
  _mm256_mask_storeu_epi32(cz, h, gr.iv[2]);
  _mm512_mask_storeu_pd(dist, h, _mm512_sub_pd(d, _mm512_set1_pd(J.bias)));
  return uint32_t(__builtin_popcount(h));
}

// Eight points a step, software-pipelined: the next group's entries are gathered before this group's quads, so that
// a group's two dependent reads overlap the other group's work.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t brick_avx512(
    const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const BrickQuadJob& J, uint8_t* hit, int32_t* cx,
    int32_t* cy, int32_t* cz, double* dist) {
  __m512d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm512_set1_pd(J.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm512_set1_pd(J.t[i]), nn[i] = _mm512_set1_pd(J.n[i]);
  __m512i sel[8];
  for (int b = 0; b < 8; ++b) sel[b] = _mm512_set_epi64(shuffle_hi(b), shuffle_lo(b), shuffle_hi(b), shuffle_lo(b),
                                                        shuffle_hi(b), shuffle_lo(b), shuffle_hi(b), shuffle_lo(b));
  if (n == 0) return 0;
  uint32_t count = 0;
  Group g[3];
  group_entries(J, m, t, nn, x, y, z, 0, n, g[0]);
  if (8 < n) group_entries(J, m, t, nn, x, y, z, 8, n, g[1]);
  for (size_t k = 0, i = 0; k < n; k += 8, i = i == 2 ? 0 : i + 1) {
    if (k + 16 < n) group_entries(J, m, t, nn, x, y, z, k + 16, n, g[i == 0 ? 2 : i - 1]);
    count += group_distances(J, g[i], sel, hit + k, cx + k, cy + k, cz + k, dist + k);
  }
  return count;
}
#pragma GCC diagnostic pop
#endif

struct Choice {
  BrickQuadBlockFn fn;
  const char* name;
};

Choice choose() {
  switch (widest_kernel()) {
#ifdef VOXCD_BRICK_X86
    case KernelWidth::Avx512: return {brick_avx512, "avx512"};
    case KernelWidth::Avx2: return {brick_avx2, "avx2"};
#endif
    default: return {brick_base, "baseline"};
  }
}

const Choice kChoice = choose();

}  // namespace

BrickQuadBlockFn brick_quad_block() { return kChoice.fn; }
const char* brick_quad_block_name() { return kChoice.name; }

}  // namespace voxcd::detail
