// The 2-bit sparse map's block kernel on the table itself (detail/sparse_kernel.h; without the map's copy, whose
// kernels are fast/sparse_entry_kernel.cpp's): transform, floor and bounds as the dense kernel does,
// then the table read and the brick read of docs/contract.md, "Sparse voxmaps and shells": the cell's table word, its
// code, its brick's unit (the word's rank plus the bricks among the codes before the cell: code 3 is the one code whose
// two bits are both set, so those are counted by a popcount of w & w >> 1 below the cell), a reference past the job's
// units read as code 0, and the brick's word. AVX-512: eight points a step, both reads by gathers; elsewhere one point
// at a time (compiled for AVX2 and for the baseline).
#include <cmath>

#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/sparse_kernel.h"
#include "voxcd/ref/sparse.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define VOXCD_SPARSE_X86 1
#endif

namespace voxcd::detail {

namespace {
int log2_of(uint64_t v) {
  int b = 0;
  while ((uint64_t{1} << b) < v) ++b;
  return b;
}
}  // namespace

SparseJob sparse_job(const DeviceConfig& cfg, const Job& j, const uint64_t* map, double scale) {
  SparseJob S;
  for (int i = 0; i < 9; ++i) S.m[i] = double(j.M[i / 3][i % 3]) * scale;
  for (int i = 0; i < 3; ++i) S.t[i] = double(j.t[i]) * scale;
  S.n[0] = j.nx, S.n[1] = j.ny, S.n[2] = j.nz;
  S.map = map;
  S.table = j.map_base;
  S.brick_base = j.brick_base;
  S.brick_units = j.brick_units;
  const CoarseDims c = coarse_dims(cfg, j);
  S.cx = int32_t(c.c[0]), S.cy = int32_t(c.c[1]);
  S.bl = cfg.BL;
  S.cpw_bits = log2_of(table_cells_per_word(cfg));
  S.unit_bits = log2_of(unit_words(cfg));
  S.spw_bits = log2_of(uint64_t(cfg.states_per_word()));
  S.half = cfg.MEMW / 2;
  S.hit_mask = j.hit_mask;
  return S;
}

namespace {

// One inside voxel's state.
inline uint32_t sparse_state_of(const SparseJob& S, int32_t x, int32_t y, int32_t z) {
  const int32_t t = (x >> S.bl) + S.cx * ((y >> S.bl) + S.cy * (z >> S.bl));
  const int32_t b = (1 << S.bl) - 1;
  const uint32_t i = uint32_t((x & b) | (y & b) << S.bl | (z & b) << (2 * S.bl));
  const uint64_t w = S.map[S.table + uint32_t(t >> S.cpw_bits)];
  const int s = 2 * (t & ((1 << S.cpw_bits) - 1));
  const uint32_t code = uint32_t(w >> s) & 3u;
  if (code != kCodeBrick) return code;
  const uint64_t u = (w >> S.half) + uint64_t(__builtin_popcountll(w & (w >> 1) & 0x5555555555555555ull &
                                                                   ((uint64_t{1} << s) - 1)));
  if (u >= S.brick_units) return kEmpty;  // past the job's bricks: code 0
  const uint64_t bw = S.map[S.brick_base + (u << S.unit_bits) + (i >> S.spw_bits)];
  return uint32_t(bw >> (2 * (i & ((1u << S.spw_bits) - 1)))) & 3u;
}

#define VOXCD_SPARSE_BLOCK_BODY                                                                                      \
  {                                                                                                                  \
    uint32_t count = 0;                                                                                              \
    for (size_t k = 0; k < n; ++k) {                                                                                 \
      const double px = x[k], py = y[k], pz = z[k];                                                                  \
      const double ax = std::floor(S.m[0] * px + S.m[1] * py + S.m[2] * pz + S.t[0]);                                \
      const double ay = std::floor(S.m[3] * px + S.m[4] * py + S.m[5] * pz + S.t[1]);                                \
      const double az = std::floor(S.m[6] * px + S.m[7] * py + S.m[8] * pz + S.t[2]);                                \
      const bool inside = ax >= 0 && ax < S.n[0] && ay >= 0 && ay < S.n[1] && az >= 0 && az < S.n[2];                \
      if (!inside) {                                                                                                 \
        state[k] = 0;                                                                                                \
        continue;                                                                                                    \
      }                                                                                                              \
      const int32_t ix = int32_t(ax), iy = int32_t(ay), iz = int32_t(az);                                            \
      const uint32_t st = sparse_state_of(S, ix, iy, iz);                                                            \
      const uint32_t hit = (S.hit_mask >> st) & 1u;                                                                  \
      state[k] = uint8_t(st | hit << 2);                                                                             \
      cx[k] = ix, cy[k] = iy, cz[k] = iz;                                                                            \
      count += hit;                                                                                                  \
    }                                                                                                                \
    return count;                                                                                                    \
  }
#define VOXCD_SPARSE_BLOCK_ARGS                                                                                      \
  const int32_t *__restrict x, const int32_t *__restrict y, const int32_t *__restrict z, size_t n,                  \
      const SparseJob &S, int32_t *__restrict cx, int32_t *__restrict cy, int32_t *__restrict cz,                    \
      uint8_t *__restrict state

uint32_t sparse_base(VOXCD_SPARSE_BLOCK_ARGS) VOXCD_SPARSE_BLOCK_BODY

#ifdef VOXCD_SPARSE_X86
__attribute__((target("arch=haswell"))) uint32_t sparse_avx2(VOXCD_SPARSE_BLOCK_ARGS) VOXCD_SPARSE_BLOCK_BODY

// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// The set bits of each 64-bit lane (at most 16 here): byte counts by a nibble table, summed by vpsadbw.
__attribute__((target("avx512f,avx512bw"), always_inline)) inline __m512i popcount512(__m512i v) {
  const __m512i lut = _mm512_broadcast_i32x4(_mm_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4));
  const __m512i low = _mm512_set1_epi8(0x0f);
  const __m512i c = _mm512_add_epi8(_mm512_shuffle_epi8(lut, _mm512_and_si512(v, low)),
                                    _mm512_shuffle_epi8(lut, _mm512_and_si512(_mm512_srli_epi64(v, 4), low)));
  return _mm512_sad_epu8(c, _mm512_setzero_si512());
}

// The states of eight voxels (lanes `in`) of a sparse map: the table words by one gather, the codes and brick units,
// the brick words of the lanes whose cell is a brick by a second gather.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw"), always_inline)) inline __m512i states512(
    const SparseJob& S, __mmask8 in, __m256i ix, __m256i iy, __m256i iz) {
  const __m128i bl = _mm_cvtsi32_si128(S.bl), bl2 = _mm_cvtsi32_si128(2 * S.bl);
  const __m256i t = _mm256_add_epi32(
      _mm256_sra_epi32(ix, bl),
      _mm256_mullo_epi32(_mm256_set1_epi32(S.cx),
                         _mm256_add_epi32(_mm256_sra_epi32(iy, bl),
                                          _mm256_mullo_epi32(_mm256_set1_epi32(S.cy), _mm256_sra_epi32(iz, bl)))));
  const __m256i tw = _mm256_add_epi32(_mm256_set1_epi32(int32_t(S.table)),
                                      _mm256_srl_epi32(t, _mm_cvtsi32_si128(S.cpw_bits)));
  const __m512i w = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), in, tw,
                                                reinterpret_cast<const long long*>(S.map), 8);
  const __m512i s = _mm512_cvtepu32_epi64(
      _mm256_slli_epi32(_mm256_and_si256(t, _mm256_set1_epi32((1 << S.cpw_bits) - 1)), 1));
  const __m512i three = _mm512_set1_epi64(3);
  const __m512i code = _mm512_and_si512(_mm512_srlv_epi64(w, s), three);
  const __m512i below = _mm512_sub_epi64(_mm512_sllv_epi64(_mm512_set1_epi64(1), s), _mm512_set1_epi64(1));
  const __m512i pairs = _mm512_and_si512(_mm512_and_si512(w, _mm512_srli_epi64(w, 1)),
                                         _mm512_and_si512(below, _mm512_set1_epi64(0x5555555555555555ll)));
  const __m512i u = _mm512_add_epi64(_mm512_srl_epi64(w, _mm_cvtsi32_si128(S.half)), popcount512(pairs));
  const __mmask8 coded = _mm512_mask_cmpeq_epi64_mask(in, code, three);
  const __mmask8 brick = _mm512_mask_cmplt_epu64_mask(coded, u, _mm512_set1_epi64(int64_t(S.brick_units)));
  // Code 3 reads its brick, or as code 0 past the job's bricks; codes 0..2 are the cell's state.
  __m512i st = _mm512_mask_mov_epi64(code, coded, _mm512_setzero_si512());
  if (!brick) return st;
  const __m256i b = _mm256_set1_epi32((1 << S.bl) - 1);
  const __m256i i = _mm256_or_si256(
      _mm256_and_si256(ix, b),
      _mm256_or_si256(_mm256_sll_epi32(_mm256_and_si256(iy, b), bl), _mm256_sll_epi32(_mm256_and_si256(iz, b), bl2)));
  const __m256i bw = _mm256_add_epi32(
      _mm256_add_epi32(_mm256_set1_epi32(int32_t(S.brick_base)),
                       _mm256_sll_epi32(_mm512_cvtepi64_epi32(u), _mm_cvtsi32_si128(S.unit_bits))),
      _mm256_srl_epi32(i, _mm_cvtsi32_si128(S.spw_bits)));
  const __m512i word = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), brick, bw,
                                                   reinterpret_cast<const long long*>(S.map), 8);
  const __m512i slot = _mm512_cvtepu32_epi64(
      _mm256_slli_epi32(_mm256_and_si256(i, _mm256_set1_epi32((1 << S.spw_bits) - 1)), 1));
  return _mm512_mask_mov_epi64(st, brick, _mm512_and_si512(_mm512_srlv_epi64(word, slot), three));
}

// Eight points a step, as the dense AVX-512 kernel (ref/fast/fast.cpp, block_avx512) with states512 for the fetch.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t sparse_avx512(VOXCD_SPARSE_BLOCK_ARGS) {
  __m512d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm512_set1_pd(S.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm512_set1_pd(S.t[i]), nn[i] = _mm512_set1_pd(S.n[i]);
  const __m512d zero = _mm512_setzero_pd();
  const __m512i hit_mask = _mm512_set1_epi64(int64_t(S.hit_mask)), one = _mm512_set1_epi64(1);
  const __m512i four = _mm512_set1_epi64(4);
  uint32_t count = 0;
  for (size_t k = 0; k < n; k += 8) {
    const __mmask8 live = n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - k)) - 1);
    const __m512d px = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, x + k));
    const __m512d py = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, y + k));
    const __m512d pz = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, z + k));
    __m512d a[3];
    __mmask8 in = live;
    for (int i = 0; i < 3; ++i) {
      a[i] = _mm512_fmadd_pd(m[3 * i], px, _mm512_fmadd_pd(m[3 * i + 1], py, _mm512_fmadd_pd(m[3 * i + 2], pz, t[i])));
      in = _mm512_mask_cmp_pd_mask(in, a[i], zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, a[i], nn[i], _CMP_LT_OQ);
    }
    if (in == 0) {
      _mm_mask_storeu_epi8(state + k, live, _mm_setzero_si128());
      continue;
    }
    // Inside lanes: truncation is the floor (the accumulator is in [0, n)); outside lanes are masked from here on.
    const __m256i ix = _mm256_maskz_mov_epi32(in, _mm512_cvttpd_epi32(a[0]));
    const __m256i iy = _mm256_maskz_mov_epi32(in, _mm512_cvttpd_epi32(a[1]));
    const __m256i iz = _mm256_maskz_mov_epi32(in, _mm512_cvttpd_epi32(a[2]));
    const __m512i st = states512(S, in, ix, iy, iz);
    const __mmask8 hit = _mm512_mask_test_epi64_mask(in, _mm512_srlv_epi64(hit_mask, st), one);
    count += uint32_t(__builtin_popcount(hit));
    _mm_mask_storeu_epi8(state + k, live, _mm512_cvtepi64_epi8(_mm512_maskz_or_epi64(hit, st, four)));
    _mm256_mask_storeu_epi32(cx + k, hit, ix);
    _mm256_mask_storeu_epi32(cy + k, hit, iy);
    _mm256_mask_storeu_epi32(cz + k, hit, iz);
  }
  return count;
}
#pragma GCC diagnostic pop
#endif

struct Choice {
  SparseBlockFn fn;
  const char* name;
};

Choice choose() {
  switch (widest_kernel()) {
#ifdef VOXCD_SPARSE_X86
    case KernelWidth::Avx512: return {sparse_avx512, "avx512"};
    case KernelWidth::Avx2: return {sparse_avx2, "avx2"};
#endif
    default: return {sparse_base, "baseline"};
  }
}

const Choice kChoice = choose();

}  // namespace

SparseBlockFn sparse_block() { return kChoice.fn; }
const char* sparse_block_name() { return kChoice.name; }

}  // namespace voxcd::detail
