// The 2-bit sparse map's block kernel on the map's copy with its table resolved (detail/sparse_kernel.h,
// detail/sparse_copy.h): transform, floor and bounds as the dense kernel does, then the cell's entry (its brick's first
// word, or kUniformCell and the cell's state) and the brick word's 32-bit half that holds the voxel's state (half
// 2 w + (i >> 4) of a 64-bit word w, i the voxel's index in its brick, 16 states a half; the low half of a narrower
// word). AVX-512: sixteen points a step in 32-bit lanes, both reads by gathers, software-pipelined (the next group's
// entries gathered before this group's brick words, so that a group's two dependent reads overlap the other's work).
// AVX2: eight points a step, both reads by scalar loads (AVX2's gather is no faster here and slower on some
// processors). Elsewhere one point at a time.
#include <cmath>

#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/sparse_copy.h"
#include "voxcd/ref/fast/detail/sparse_kernel.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define VOXCD_ENTRY_X86 1
#endif

namespace voxcd::detail {

namespace {

// The half-word of voxel index i in the brick that starts at word e, and the state's shift in it.
struct Halves {
  int word_shift, half_shift;  // half = 2 e + ((i >> word_shift) << half_shift)
  uint32_t slot_mask;          // state shift = 2 (i & slot_mask)
  explicit Halves(const SparseJob& S)
      : word_shift(S.spw_bits == 5 ? 4 : S.spw_bits), half_shift(S.spw_bits == 5 ? 0 : 1),
        slot_mask(S.spw_bits == 5 ? 15u : (1u << S.spw_bits) - 1) {}
};

// One point (the baseline, and the AVX2 kernel's tail).
inline uint32_t entry_point(const SparseJob& S, const Halves& H, const int32_t* x, const int32_t* y,
                            const int32_t* z, size_t k, int32_t* cx, int32_t* cy, int32_t* cz, uint8_t* state) {
  const double px = x[k], py = y[k], pz = z[k];
  const double ax = std::floor(S.m[0] * px + S.m[1] * py + S.m[2] * pz + S.t[0]);
  const double ay = std::floor(S.m[3] * px + S.m[4] * py + S.m[5] * pz + S.t[1]);
  const double az = std::floor(S.m[6] * px + S.m[7] * py + S.m[8] * pz + S.t[2]);
  state[k] = 0;
  if (!(ax >= 0 && ax < S.n[0] && ay >= 0 && ay < S.n[1] && az >= 0 && az < S.n[2])) return 0;
  const int32_t ix = int32_t(ax), iy = int32_t(ay), iz = int32_t(az), b = (1 << S.bl) - 1;
  const uint32_t e = S.entries[(ix >> S.bl) + S.cx * ((iy >> S.bl) + S.cy * (iz >> S.bl))];
  const uint32_t i = uint32_t((ix & b) | (iy & b) << S.bl | (iz & b) << (2 * S.bl));
  const uint32_t* halves = reinterpret_cast<const uint32_t*>(S.map);
  const uint32_t st = e & kUniformCell ? e & 3u
                                       : (halves[2 * e + ((i >> H.word_shift) << H.half_shift)] >>
                                          (2 * (i & H.slot_mask))) & 3u;
  const uint32_t hit = (S.hit_mask >> st) & 1u;
  state[k] = uint8_t(st | hit << 2);
  cx[k] = ix, cy[k] = iy, cz[k] = iz;
  return hit;
}

uint32_t entry_base(const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const SparseJob& S, int32_t* cx,
                    int32_t* cy, int32_t* cz, uint8_t* state) {
  const Halves H(S);
  uint32_t count = 0;
  for (size_t k = 0; k < n; ++k) count += entry_point(S, H, x, y, z, k, cx, cy, cz, state);
  return count;
}

#ifdef VOXCD_ENTRY_X86
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// The entry kernel's constants: shifts and masks of the layout. A state is read from the 32-bit half of its word:
// half 2 w + (i >> 4) of a 64-bit word w (i the voxel's index in its brick, 16 states a half), or the low half 2 w of a
// narrower word (MEMW / 2 <= 16 states).
struct EntryConsts {
  __m128i bl, bl2, word_shift, half_shift;
  __m512i cx, cy, brick_mask, slot_mask, three, hit_mask, one, four;
};

EntryConsts entry_consts(const SparseJob& S) __attribute__((target("avx512f")));
EntryConsts entry_consts(const SparseJob& S) {
  const bool halves = S.spw_bits == 5;  // a 64-bit word holds 32 states: two halves of 16
  return {_mm_cvtsi32_si128(S.bl),
          _mm_cvtsi32_si128(2 * S.bl),
          _mm_cvtsi32_si128(halves ? 4 : S.spw_bits),
          _mm_cvtsi32_si128(halves ? 0 : 1),
          _mm512_set1_epi32(S.cx),
          _mm512_set1_epi32(S.cy),
          _mm512_set1_epi32((1 << S.bl) - 1),
          _mm512_set1_epi32(halves ? 15 : (1 << S.spw_bits) - 1),
          _mm512_set1_epi32(3),
          _mm512_set1_epi32(int32_t(S.hit_mask)),
          _mm512_set1_epi32(1),
          _mm512_set1_epi32(4)};
}

// One group of sixteen points between the two reads: which are live and inside, their voxels and their cells' entries.
struct Group {
  __mmask16 live, in;
  __m512i v[3], e;
};

// The first half of a group: the transform and the bounds in two halves of eight doubles (as the dense kernel,
// ref/fast/fast.cpp's block_avx512), the voxels and the cells in 32-bit lanes, the entries by one gather.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"), always_inline)) inline void group_entries(
    const SparseJob& S, const EntryConsts& K, const __m512d (&m)[9], const __m512d (&t)[3], const __m512d (&nn)[3],
    const int32_t* x, const int32_t* y, const int32_t* z, size_t k, size_t n, Group& g) {
  g.live = n - k >= 16 ? __mmask16(0xffff) : __mmask16((1u << (n - k)) - 1);
  g.in = 0;
  const __m512d zero = _mm512_setzero_pd();
  for (int h = 0; h < 2; ++h) {
    const __mmask8 lh = __mmask8(g.live >> (8 * h));
    const __m512d px = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(lh, x + k + 8 * h));
    const __m512d py = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(lh, y + k + 8 * h));
    const __m512d pz = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(lh, z + k + 8 * h));
    __m512d a[3];
    __mmask8 ih = lh;
    for (int i = 0; i < 3; ++i) {
      a[i] = _mm512_fmadd_pd(m[3 * i], px, _mm512_fmadd_pd(m[3 * i + 1], py, _mm512_fmadd_pd(m[3 * i + 2], pz, t[i])));
      ih = _mm512_mask_cmp_pd_mask(ih, a[i], zero, _CMP_GE_OQ);
      ih = _mm512_mask_cmp_pd_mask(ih, a[i], nn[i], _CMP_LT_OQ);
    }
    g.in |= __mmask16(ih) << (8 * h);
    for (int i = 0; i < 3; ++i)  // inside lanes: truncation is the floor; the others voxel 0
      g.v[i] = h == 0 ? _mm512_castsi256_si512(_mm512_maskz_cvttpd_epi32(ih, a[i]))
                      : _mm512_inserti64x4(g.v[i], _mm512_maskz_cvttpd_epi32(ih, a[i]), 1);
  }
  const __m512i c = _mm512_add_epi32(
      _mm512_srl_epi32(g.v[0], K.bl),
      _mm512_mullo_epi32(K.cx, _mm512_add_epi32(_mm512_srl_epi32(g.v[1], K.bl),
                                                _mm512_mullo_epi32(K.cy, _mm512_srl_epi32(g.v[2], K.bl)))));
  g.e = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), g.in, c, S.entries, 4);
}

// The second half: the 32-bit halves of the brick words of the lanes whose cell is a brick (an entry without
// kUniformCell is its brick's first word) by a second gather, the states, the hit test and the outputs.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw"), always_inline)) inline uint32_t group_states(
    const SparseJob& S, const EntryConsts& K, const Group& g, uint8_t* state, int32_t* cx, int32_t* cy, int32_t* cz) {
  if (g.in == 0) {
    _mm_mask_storeu_epi8(state, g.live, _mm_setzero_si128());
    return 0;
  }
  const __mmask16 brick = g.in & ~_mm512_movepi32_mask(g.e);
  __m512i st = g.e;
  if (brick) {
    const __m512i i = _mm512_ternarylogic_epi32(
        _mm512_and_si512(g.v[0], K.brick_mask), _mm512_sll_epi32(_mm512_and_si512(g.v[1], K.brick_mask), K.bl),
        _mm512_sll_epi32(_mm512_and_si512(g.v[2], K.brick_mask), K.bl2), 0xfe);
    const __m512i half = _mm512_add_epi32(_mm512_slli_epi32(g.e, 1),
                                          _mm512_sll_epi32(_mm512_srl_epi32(i, K.word_shift), K.half_shift));
    const __m512i w = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), brick, half, S.map, 4);
    st = _mm512_mask_srlv_epi32(st, brick, w, _mm512_slli_epi32(_mm512_and_si512(i, K.slot_mask), 1));
  }
  st = _mm512_and_si512(st, K.three);
  const __mmask16 hit = _mm512_mask_test_epi32_mask(g.in, _mm512_srlv_epi32(K.hit_mask, st), K.one);
  _mm_mask_storeu_epi8(state, g.live, _mm512_cvtepi32_epi8(_mm512_maskz_or_epi32(hit, st, K.four)));
  _mm512_mask_storeu_epi32(cx, hit, g.v[0]);
  _mm512_mask_storeu_epi32(cy, hit, g.v[1]);
  _mm512_mask_storeu_epi32(cz, hit, g.v[2]);
  return uint32_t(__builtin_popcount(hit));
}

// Sixteen points a step, software-pipelined: the next group's entries are gathered before this group's brick words,
// so that the two dependent reads of a group overlap the other group's work.
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t entry_avx512(
    const int32_t* x, const int32_t* y, const int32_t* z, size_t n, const SparseJob& S, int32_t* cx, int32_t* cy,
    int32_t* cz, uint8_t* state) {
  __m512d m[9], t[3], nn[3];
  for (int i = 0; i < 9; ++i) m[i] = _mm512_set1_pd(S.m[i]);
  for (int i = 0; i < 3; ++i) t[i] = _mm512_set1_pd(S.t[i]), nn[i] = _mm512_set1_pd(S.n[i]);
  const EntryConsts K = entry_consts(S);
  uint32_t count = 0;
  if (n == 0) return 0;
  Group cur, next;
  group_entries(S, K, m, t, nn, x, y, z, 0, n, cur);
  for (size_t k = 0; k < n; k += 16) {
    if (k + 16 < n) group_entries(S, K, m, t, nn, x, y, z, k + 16, n, next);
    count += group_states(S, K, cur, state + k, cx + k, cy + k, cz + k);
    cur = next;
  }
  return count;
}

__attribute__((target("avx2,fma"), always_inline)) inline __m256i load8_u32(const uint32_t* base, __m256i idx) {
  alignas(32) uint32_t i[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(i), idx);
  return _mm256_setr_epi32(int32_t(base[i[0]]), int32_t(base[i[1]]), int32_t(base[i[2]]), int32_t(base[i[3]]),
                           int32_t(base[i[4]]), int32_t(base[i[5]]), int32_t(base[i[6]]), int32_t(base[i[7]]));
}

// Eight points' voxels (int32; outside lanes 0) and the mask of those inside (all ones a lane), from two halves of
// four doubles.
__attribute__((target("avx2,fma"), always_inline)) inline __m256i voxels8(const SparseJob& S, const int32_t* x,
                                                                          const int32_t* y, const int32_t* z, size_t k,
                                                                          __m256i (&v)[3]) {
  __m128i h[2][3], m[2];
  const __m256i low32 = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);  // a 64-bit lane's low half
  for (int q = 0; q < 2; ++q) {
    const size_t o = k + 4 * size_t(q);
    const __m256d p[3] = {_mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(x + o))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(y + o))),
                          _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(z + o)))};
    __m256d a[3], inside = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for (int i = 0; i < 3; ++i) {
      a[i] = _mm256_fmadd_pd(_mm256_set1_pd(S.m[3 * i]), p[0],
                             _mm256_fmadd_pd(_mm256_set1_pd(S.m[3 * i + 1]), p[1],
                                             _mm256_fmadd_pd(_mm256_set1_pd(S.m[3 * i + 2]), p[2],
                                                             _mm256_set1_pd(S.t[i]))));
      inside = _mm256_and_pd(inside, _mm256_and_pd(_mm256_cmp_pd(a[i], _mm256_setzero_pd(), _CMP_GE_OQ),
                                                   _mm256_cmp_pd(a[i], _mm256_set1_pd(S.n[i]), _CMP_LT_OQ)));
    }
    m[q] = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(inside), low32));
    for (int i = 0; i < 3; ++i) h[q][i] = _mm256_cvttpd_epi32(_mm256_and_pd(a[i], inside));  // inside: the floor
  }
  for (int i = 0; i < 3; ++i) v[i] = _mm256_set_m128i(h[1][i], h[0][i]);
  return _mm256_set_m128i(m[1], m[0]);
}

// Eight points a step, both reads by scalar loads, writing state | hit << 2 for every lane (a lane outside the map:
// no hit, its state unspecified, as emit reads the states of hits only) and the voxels; the tail (fewer than eight)
// one at a time.
__attribute__((target("avx2,fma"))) uint32_t entry_avx2(const int32_t* x, const int32_t* y, const int32_t* z, size_t n,
                                                        const SparseJob& S, int32_t* cx, int32_t* cy, int32_t* cz,
                                                        uint8_t* state) {
  const Halves H(S);
  const __m128i bl = _mm_cvtsi32_si128(S.bl), bl2 = _mm_cvtsi32_si128(2 * S.bl);
  const __m128i ws = _mm_cvtsi32_si128(H.word_shift), hs = _mm_cvtsi32_si128(H.half_shift);
  const __m256i bm = _mm256_set1_epi32((1 << S.bl) - 1), sm = _mm256_set1_epi32(int32_t(H.slot_mask));
  const __m256i three = _mm256_set1_epi32(3), one = _mm256_set1_epi32(1), mask = _mm256_set1_epi32(int32_t(S.hit_mask));
  // Byte 0 of every 32-bit lane to the low 8 bytes: within each 128-bit half, then the halves' low words together.
  const __m256i pack = _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, 0, 4, 8, 12, -1, -1,
                                        -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
  const __m256i join = _mm256_setr_epi32(0, 4, 0, 0, 0, 0, 0, 0);
  uint32_t count = 0;
  size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    __m256i v[3];
    const __m256i in = voxels8(S, x, y, z, k, v);
    const __m256i c = _mm256_add_epi32(
        _mm256_srl_epi32(v[0], bl),
        _mm256_mullo_epi32(_mm256_set1_epi32(S.cx),
                           _mm256_add_epi32(_mm256_srl_epi32(v[1], bl),
                                            _mm256_mullo_epi32(_mm256_set1_epi32(S.cy), _mm256_srl_epi32(v[2], bl)))));
    const __m256i e = load8_u32(S.entries, c);  // outside lanes: cell 0
    const __m256i i = _mm256_or_si256(_mm256_and_si256(v[0], bm),
                                      _mm256_or_si256(_mm256_sll_epi32(_mm256_and_si256(v[1], bm), bl),
                                                      _mm256_sll_epi32(_mm256_and_si256(v[2], bm), bl2)));
    const __m256i uniform = _mm256_srai_epi32(e, 31);  // uniform cells read half 0; their state is their entry's
    const __m256i half = _mm256_andnot_si256(
        uniform, _mm256_add_epi32(_mm256_slli_epi32(e, 1), _mm256_sll_epi32(_mm256_srl_epi32(i, ws), hs)));
    const __m256i w = load8_u32(reinterpret_cast<const uint32_t*>(S.map), half);
    const __m256i st = _mm256_and_si256(
        _mm256_blendv_epi8(_mm256_srlv_epi32(w, _mm256_slli_epi32(_mm256_and_si256(i, sm), 1)), e, uniform), three);
    const __m256i hit = _mm256_and_si256(_mm256_and_si256(_mm256_srlv_epi32(mask, st), one), in);
    const __m256i bytes = _mm256_permutevar8x32_epi32(
        _mm256_shuffle_epi8(_mm256_or_si256(st, _mm256_slli_epi32(hit, 2)), pack), join);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(state + k), _mm256_castsi256_si128(bytes));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(cx + k), v[0]);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(cy + k), v[1]);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(cz + k), v[2]);
    count += uint32_t(__builtin_popcount(unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_slli_epi32(hit, 31))))));
  }
  for (; k < n; ++k) count += entry_point(S, H, x, y, z, k, cx, cy, cz, state);
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
#ifdef VOXCD_ENTRY_X86
    case KernelWidth::Avx512: return {entry_avx512, "avx512"};
    case KernelWidth::Avx2: return {entry_avx2, "avx2"};
#endif
    default: return {entry_base, "baseline"};
  }
}

const Choice kChoice = choose();

}  // namespace

SparseBlockFn sparse_entry_block() { return kChoice.fn; }

}  // namespace voxcd::detail
