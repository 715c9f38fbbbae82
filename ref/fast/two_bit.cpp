// FastRunner's 2-bit kernels: a block of a job's points looked up in a dense 2-bit voxmap on each arithmetic path
// (the fused double kernel, AVX-512 by hand, AVX2 or baseline chosen at run time; int64; ref/'s wide stages), from a
// dense shell or a sparse shell's generated points.
#include "voxcd/ref/fast/fast.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>

#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/emit.h"
#include "voxcd/ref/fast/detail/point_blocks.h"
#include "voxcd/ref/fast/detail/runner.h"
#include "voxcd/ref/fast/detail/sparse_shell.h"

namespace voxcd {

namespace {

using detail::kBlock;

// The whole lookup of a block on the double path, for maps of fewer than 2^31 voxels: transform, floor,
// bounds, linear address, word fetch, state select and hit test. Outputs per point state | hit << 2 and, for hits,
// the voxel (cx, cy, cz); returns the number of hits. Outside points read the map's first word and are masked.
// Compiled twice (AVX2 with FMA, baseline; a processor with AVX-512 takes block_avx512) and chosen once at run time.
#define VOXCD_BLOCK_DOUBLE_FETCH_BODY                                                                           \
  {                                                                                                             \
    const double m0 = mp[0], m1 = mp[1], m2 = mp[2], m3 = mp[3], m4 = mp[4], m5 = mp[5], m6 = mp[6],            \
                 m7 = mp[7], m8 = mp[8];                                                                        \
    const double t0 = tp[0], t1 = tp[1], t2 = tp[2];                                                            \
    const double nx = dp[0], ny = dp[1], nz = dp[2];                                                            \
    const int32_t slot_mask = (int32_t{1} << slot_bits) - 1;                                                    \
    uint32_t count = 0;                                                                                         \
    for (size_t k = 0; k < n; ++k) {                                                                            \
      const double px = double(x[k]), py = double(y[k]), pz = double(z[k]);                                      \
      const double ax = std::floor(m0 * px + m1 * py + m2 * pz + t0);                                           \
      const double ay = std::floor(m3 * px + m4 * py + m5 * pz + t1);                                           \
      const double az = std::floor(m6 * px + m7 * py + m8 * pz + t2);                                           \
      const bool inside = (ax >= 0) & (ax < nx) & (ay >= 0) & (ay < ny) & (az >= 0) & (az < nz);                \
      const double vx = inside ? ax : 0.0, vy = inside ? ay : 0.0, vz = inside ? az : 0.0;                      \
      const int32_t li = int32_t(vx + nx * (vy + ny * vz));                                                     \
      const uint32_t st = uint32_t(map[li >> slot_bits] >> (2 * (li & slot_mask))) & 3u;                        \
      const uint32_t hit = uint32_t(inside) & (mask >> st) & 1u;                                                \
      cx[k] = int32_t(vx);                                                                                      \
      cy[k] = int32_t(vy);                                                                                      \
      cz[k] = int32_t(vz);                                                                                      \
      state[k] = uint8_t(st | (hit << 2));                                                                      \
      count += hit;                                                                                             \
    }                                                                                                           \
    return count;                                                                                               \
  }
#define VOXCD_BLOCK_DOUBLE_FETCH_ARGS                                                                           \
  const Coord *__restrict x, const Coord *__restrict y, const Coord *__restrict z, size_t n,                    \
      const double *__restrict mp, const double *__restrict tp, const double *__restrict dp,                    \
      const uint64_t *__restrict map, int slot_bits, uint32_t mask, int32_t *__restrict cx,                     \
      int32_t *__restrict cy, int32_t *__restrict cz, uint8_t *__restrict state

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
bool have_avx512() { return detail::cpu_has_avx512(); }

// The block lookup on AVX-512, written by hand, eight points at a time: it tests the bounds on the exact accumulator
// (for an integer n, floor(a) is in [0, n) exactly when a is, and for such an a truncation is the floor, so it needs
// no floor instruction), computes y and z only where a point is inside along x, skips the fetch for eight points none
// of which is inside, and fetches the words of the others with one gather instruction (measured by CPU time, faster
// than eight scalar loads and than the compiler's vectorisation of the generic body, in and out of cache). Outputs
// as the generic body for the hits; a point that is no hit has state 0 and an unspecified voxel.
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t block_avx512(
    const int32_t* __restrict x, const int32_t* __restrict y, const int32_t* __restrict z, size_t n,
    const double* __restrict mp, const double* __restrict tp, const double* __restrict dp,
    const uint64_t* __restrict map, int slot_bits, uint32_t mask, int32_t* __restrict cx, int32_t* __restrict cy,
    int32_t* __restrict cz, uint8_t* __restrict state) {
  const __m512d m0 = _mm512_set1_pd(mp[0]), m1 = _mm512_set1_pd(mp[1]), m2 = _mm512_set1_pd(mp[2]);
  const __m512d m3 = _mm512_set1_pd(mp[3]), m4 = _mm512_set1_pd(mp[4]), m5 = _mm512_set1_pd(mp[5]);
  const __m512d m6 = _mm512_set1_pd(mp[6]), m7 = _mm512_set1_pd(mp[7]), m8 = _mm512_set1_pd(mp[8]);
  const __m512d t0 = _mm512_set1_pd(tp[0]), t1 = _mm512_set1_pd(tp[1]), t2 = _mm512_set1_pd(tp[2]);
  const __m512d nx = _mm512_set1_pd(dp[0]), ny = _mm512_set1_pd(dp[1]), nz = _mm512_set1_pd(dp[2]);
  const __m512d zero = _mm512_setzero_pd();
  const __m256i inx = _mm256_set1_epi32(int32_t(dp[0])), iny = _mm256_set1_epi32(int32_t(dp[1]));
  const __m256i slot_mask = _mm256_set1_epi32((int32_t{1} << slot_bits) - 1);
  const __m128i word_shift = _mm_cvtsi32_si128(slot_bits);
  const __m512i hit_mask = _mm512_set1_epi64(int64_t(mask)), three = _mm512_set1_epi64(3);
  const __m512i one = _mm512_set1_epi64(1), four = _mm512_set1_epi64(4);
  uint32_t count = 0;
  for (size_t k = 0; k < n; k += 8) {
    const __mmask8 live = n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - k)) - 1);
    const __m512d px = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, x + k));
    const __m512d py = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, y + k));
    const __m512d pz = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, z + k));
    const __m512d ax = _mm512_fmadd_pd(m0, px, _mm512_fmadd_pd(m1, py, _mm512_fmadd_pd(m2, pz, t0)));
    __mmask8 in = _mm512_mask_cmp_pd_mask(live, ax, zero, _CMP_GE_OQ);
    in = _mm512_mask_cmp_pd_mask(in, ax, nx, _CMP_LT_OQ);
    __m512d ay = zero, az = zero;
    if (in != 0) {  // y and z only where a point is inside along x
      ay = _mm512_fmadd_pd(m3, px, _mm512_fmadd_pd(m4, py, _mm512_fmadd_pd(m5, pz, t1)));
      az = _mm512_fmadd_pd(m6, px, _mm512_fmadd_pd(m7, py, _mm512_fmadd_pd(m8, pz, t2)));
      in = _mm512_mask_cmp_pd_mask(in, ay, zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, ay, ny, _CMP_LT_OQ);
      in = _mm512_mask_cmp_pd_mask(in, az, zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, az, nz, _CMP_LT_OQ);
    }
    if (in == 0) {
      _mm_mask_storeu_epi8(state + k, live, _mm_setzero_si128());
      continue;
    }
    // Inside lanes: below 2^31 voxels, so the index fits int32; outside lanes are masked from here on.
    const __m256i ix = _mm512_cvttpd_epi32(ax), iy = _mm512_cvttpd_epi32(ay), iz = _mm512_cvttpd_epi32(az);
    const __m256i li = _mm256_maskz_mov_epi32(
        in, _mm256_add_epi32(ix, _mm256_mullo_epi32(inx, _mm256_add_epi32(iy, _mm256_mullo_epi32(iny, iz)))));
    const __m512i word = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), in, _mm256_srl_epi32(li, word_shift),
                                                     reinterpret_cast<const long long*>(map), 8);
    const __m512i shift = _mm512_slli_epi64(_mm512_cvtepi32_epi64(_mm256_and_si256(li, slot_mask)), 1);
    const __m512i st = _mm512_and_si512(_mm512_srlv_epi64(word, shift), three);
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

template <class Coord>
struct BlockKernel {
  using Fn = uint32_t (*)(VOXCD_BLOCK_DOUBLE_FETCH_ARGS);
  static uint32_t base(VOXCD_BLOCK_DOUBLE_FETCH_ARGS) VOXCD_BLOCK_DOUBLE_FETCH_BODY
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __attribute__((target("arch=haswell"))) static uint32_t avx2(VOXCD_BLOCK_DOUBLE_FETCH_ARGS)
      VOXCD_BLOCK_DOUBLE_FETCH_BODY
#endif
  struct Choice {
    Fn fn;
    const char* name;
  };
  static Choice choose() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init();
    const std::string want = detail::kernel_override();
    if (have_avx512() && (want.empty() || want == "avx512")) return {block_avx512, "avx512"};
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && want != "baseline") return {avx2, "avx2"};
#endif
    return {base, "baseline"};
  }
};

// Coordinates are int32 on the double path: DeviceConfig::validate keeps PW within 2..32.
const BlockKernel<int32_t>::Choice block_fetch = BlockKernel<int32_t>::choose();

void block_int64(const int64_t* x, const int64_t* y, const int64_t* z, size_t n, const Job& j, int tf,
                 int64_t* lin) {
  const int64_t nx = j.nx, ny = j.ny, nz = j.nz;
  for (size_t k = 0; k < n; ++k) {
    const int64_t ix = (j.M[0][0] * x[k] + j.M[0][1] * y[k] + j.M[0][2] * z[k] + j.t[0]) >> tf;
    const int64_t iy = (j.M[1][0] * x[k] + j.M[1][1] * y[k] + j.M[1][2] * z[k] + j.t[1]) >> tf;
    const int64_t iz = (j.M[2][0] * x[k] + j.M[2][1] * y[k] + j.M[2][2] * z[k] + j.t[2]) >> tf;
    const bool inside = uint64_t(ix) < uint64_t(nx) && uint64_t(iy) < uint64_t(ny) && uint64_t(iz) < uint64_t(nz);
    lin[k] = inside ? ix + nx * (iy + ny * iz) : -1;
  }
}

using detail::emit_cells;
using detail::emit_hits;

// The voxels of n points' linear indices (-1: outside the map) fetched, selected and tested without branches
// (outside points read the map's first word and are masked): state[k] bits 1:0 the state, bit 2 the hit; the hits.
inline uint32_t fetch_states(const uint64_t* map, int slot_bits, uint32_t hit_mask, const int64_t* lin, size_t n,
                             uint8_t* state) {
  const uint64_t slot_mask = (uint64_t{1} << slot_bits) - 1;
  uint32_t count = 0;
  for (size_t k = 0; k < n; ++k) {
    const bool inside = lin[k] >= 0;
    const uint64_t li = inside ? uint64_t(lin[k]) : 0;
    const uint32_t st = uint32_t(map[li >> slot_bits] >> (2 * (li & slot_mask))) & 3u;
    const uint32_t hit = uint32_t(inside) & (hit_mask >> st) & 1u;
    state[k] = uint8_t(st | (hit << 2));
    count += hit;
  }
  return count;
}

}  // namespace

const char* FastRunner::double_kernel() { return block_fetch.name; }

detail::ShellArrays FastRunner::Impl::shell_arrays() const {
  detail::ShellArrays a{shell_.data(), nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
  if (path_ == Path::Double) a.sx = sx_.data(), a.sy = sy_.data(), a.sz = sz_.data();
  if (keep_int64_) a.ix = ix_.data(), a.iy = iy_.data(), a.iz = iz_.data();
  return a;
}

namespace {

// The 2-bit lookups of a block of a job's points on a dense map, on every path: the fused kernel (transform to state in
// one loop) where the doubles are exact and the map below 2^31 voxels, else the linear indices (int64 or ref/'s
// 128-bit stages) and then the fetch. Returns true when FIRST has its hit.
struct TwoBitBlocks {
  const DeviceConfig& cfg;
  const Job& j;
  FastRunner::Path path;
  bool fused;
  int slot_bits;
  const uint64_t* map;
  HitColumns& hits;
  uint32_t& hit_count;
  double ms[9], ts[3], dims[3];
  int64_t lin[kBlock];
  int32_t cx[kBlock], cy[kBlock], cz[kBlock];
  uint8_t state[kBlock];  // bits 1:0 the state, bit 2 the hit

  TwoBitBlocks(const DeviceConfig& c, const Job& job, FastRunner::Path p, double tf_scale, int bits,
               const uint64_t* memory, HitColumns& h, uint32_t& count)
      : cfg(c), j(job), path(p), fused(p == FastRunner::Path::Double && job.voxels() < (uint64_t{1} << 31)),
        slot_bits(bits), map(memory + job.map_base), hits(h), hit_count(count),
        dims{double(job.nx), double(job.ny), double(job.nz)} {
    // The fused kernel takes M and t already scaled by 2^-TF: scaling by a power of two is exact, and so is every
    // product and sum after it (multiples of 2^-TF below 2^(53-TF)).
    if (!fused) return;
    for (int i = 0; i < 9; ++i) ms[i] = double(job.M[i / 3][i % 3]) * tf_scale;
    for (int i = 0; i < 3; ++i) ts[i] = double(job.t[i]) * tf_scale;
  }
  // The forms of the points the path reads (detail::PointBlocks::Need).
  unsigned need() const {
    return fused ? detail::PointBlocks::kInt32
                 : path == FastRunner::Path::Wide ? detail::PointBlocks::kWords : detail::PointBlocks::kInt64;
  }

  bool operator()(uint32_t b, size_t n, const detail::BlockCoords& c) {
    if (fused) {
      const uint32_t count = block_fetch.fn(c.x, c.y, c.z, n, ms, ts, dims, map, slot_bits, j.hit_mask, cx, cy, cz,
                                            state);
      if (count == 0) return false;
      if (j.mode == Mode::Count) return hit_count += count, false;
      return emit_cells(j, b, n, cx, cy, cz, state, count, hits, hit_count);
    }
    if (path == FastRunner::Path::Wide) {
      for (size_t k = 0; k < n; ++k) {
        const Located l = locate(cfg, j, transform(cfg, j, c.w[k]));
        lin[k] = l.inside ? int64_t(l.linear) : -1;
      }
    } else {  // int64, or the double path's maps of 2^31 voxels or more (the accumulator fits 53 bits)
      block_int64(c.ix, c.iy, c.iz, n, j, cfg.TF(), lin);
    }
    // Then walk only the hits.
    const uint32_t count = fetch_states(map, slot_bits, j.hit_mask, lin, n, state);
    if (count == 0) return false;
    if (j.mode == Mode::Count) return hit_count += count, false;
    return emit_hits(j, b, n, lin, state, count, hits, hit_count);
  }
};

}  // namespace

void FastRunner::Impl::run_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& hit_count,
                           const detail::ShellCursor* at) const {
  if (j.sparse_map()) return run_sparse_chunk(j, begin, end, hits, hit_count, at);
  if (cfg_.distance()) return run_distance_chunk(j, begin, end, hits, hit_count, at);
  if (j.sparse_shell()) return run_sparse_shell_chunk(j, begin, end, hits, hit_count, at);
  TwoBitBlocks block(cfg_, j, path_, tf_scale_, slot_bits_, map_.data(), hits, hit_count);
  // A dense shell's words where the path keeps them (a batch may hold many small jobs: nothing more per block).
  detail::BlockCoords c;
  size_t n = 0;
  for (uint32_t b = begin; b < end; b += uint32_t(n)) {
    n = std::min<size_t>(kBlock, end - b);
    const size_t base = size_t(j.shell_base) + b;
    if (block.fused) c.x = &sx_[base], c.y = &sy_[base], c.z = &sz_[base];
    else if (path_ == Path::Wide) c.w = &shell_[base];
    else c.ix = &ix_[base], c.iy = &iy_[base], c.iz = &iz_[base];
    if (block(b, n, c)) return;
  }
}

void FastRunner::Impl::run_sparse_shell_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits,
                                        uint32_t& hit_count, const detail::ShellCursor* at) const {
  TwoBitBlocks block(cfg_, j, path_, tf_scale_, slot_bits_, map_.data(), hits, hit_count);
  detail::sparse_shell_blocks(cfg_, shell_arrays(), j, begin, end, at, block.need(), kBlock, block);
}

}  // namespace voxcd
