// A sparse shell's points generated from its words (detail/sparse_shell.h), as ref/sparse.h's shell_points does: the
// origin 0 at the job's start, set by an origin word, moved by a brick word's step, one point o + d * 2^PF + h per set
// bit of a brick word's mask, every sum wrapping at PW bits. Points are int32 (PW <= 32): a sum wraps as the low PW
// bits of the 32-bit sum, sign-extended. With AVX-512 a brick's points are its offsets compressed by its mask, 16 at a
// time.
#include "voxcd/ref/fast/detail/sparse_shell.h"

#include <algorithm>

#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/sparse.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define VOXCD_SHELL_X86 1
#endif

namespace voxcd::detail {

namespace {

// v wrapped to `bits` bits, two's complement (1 <= bits <= 64).
inline int64_t wrap(int64_t v, int bits) { return int64_t(uint64_t(v) << (64 - bits)) >> (64 - bits); }

// The low PW bits of a 32-bit sum, sign-extended (PW <= 32).
inline int32_t wrap32(uint32_t v, int pw) { return int32_t(v << (32 - pw)) >> (32 - pw); }

// The lowest `n` set bits of m cleared.
uint64_t drop_low_bits(uint64_t m, uint32_t n) {
  for (; n && m; --n) m &= m - 1;
  return m;
}

// Only the lowest `n` set bits of m kept.
uint64_t keep_low_bits(uint64_t m, size_t n) {
  if (n >= 64) return m;
  uint64_t kept = 0;
  for (; n && m; --n) kept |= m & (~m + 1), m &= m - 1;
  return kept;
}

// pw: the width to wrap the sums at, or 32 where none wraps (int32 sums are exact).
using BrickFn = size_t (*)(const int32_t (*off)[64], uint64_t mask, const int64_t o[3], int pw, int32_t* x,
                           int32_t* y, int32_t* z);

size_t brick_base(const int32_t (*off)[64], uint64_t mask, const int64_t o[3], int pw, int32_t* x, int32_t* y,
                  int32_t* z) {
  size_t n = 0;
  const uint32_t ox = uint32_t(o[0]), oy = uint32_t(o[1]), oz = uint32_t(o[2]);
  for (; mask; mask &= mask - 1, ++n) {
    const int b = __builtin_ctzll(mask);
    x[n] = wrap32(ox + uint32_t(off[0][b]), pw);
    y[n] = wrap32(oy + uint32_t(off[1][b]), pw);
    z[n] = wrap32(oz + uint32_t(off[2][b]), pw);
  }
  return n;
}

#ifdef VOXCD_SHELL_X86
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// Sixteen bits of the mask at a time: the offsets of its set bits compressed to the front of a register, the origin
// added, the sum wrapped, all 16 lanes stored (the arrays have room) and the cursor moved by the bits' count.
__attribute__((target("avx512f,avx512bw,popcnt"))) size_t brick_avx512(const int32_t (*off)[64], uint64_t mask,
                                                                        const int64_t o[3], int pw, int32_t* x,
                                                                        int32_t* y, int32_t* z) {
  const __m512i ox = _mm512_set1_epi32(int32_t(o[0])), oy = _mm512_set1_epi32(int32_t(o[1]));
  const __m512i oz = _mm512_set1_epi32(int32_t(o[2]));
  const __m128i sh = _mm_cvtsi32_si128(32 - pw);
  size_t n = 0;
  // Every chunk, empty or not: a branch on it would be mispredicted as often as not.
  for (int c = 0; c < 4; ++c) {
    const __mmask16 m = __mmask16(mask >> (16 * c));
    const __m512i dx = _mm512_maskz_compress_epi32(m, _mm512_load_si512(off[0] + 16 * c));
    const __m512i dy = _mm512_maskz_compress_epi32(m, _mm512_load_si512(off[1] + 16 * c));
    const __m512i dz = _mm512_maskz_compress_epi32(m, _mm512_load_si512(off[2] + 16 * c));
    __m512i px = _mm512_add_epi32(dx, ox), py = _mm512_add_epi32(dy, oy), pz = _mm512_add_epi32(dz, oz);
    if (pw < 32) {
      px = _mm512_sra_epi32(_mm512_sll_epi32(px, sh), sh);
      py = _mm512_sra_epi32(_mm512_sll_epi32(py, sh), sh);
      pz = _mm512_sra_epi32(_mm512_sll_epi32(pz, sh), sh);
    }
    _mm512_storeu_si512(x + n, px);
    _mm512_storeu_si512(y + n, py);
    _mm512_storeu_si512(z + n, pz);
    n += size_t(__builtin_popcount(m));
  }
  return n;
}
#pragma GCC diagnostic pop
#endif

BrickFn choose() {
#ifdef VOXCD_SHELL_X86
  if (widest_kernel() == KernelWidth::Avx512) return brick_avx512;
#endif
  return brick_base;
}

const BrickFn kBrick = choose();

}  // namespace

ShellBricks::ShellBricks(const DeviceConfig& cfg, const ShellWord* words, uint32_t count)
    : words_(words), count_(count), pw_(cfg.PW), pf_(cfg.PF), brick_step_(int64_t{kShellBrick} << cfg.PF) {
  if (count == 0) return;  // nothing to generate (a dense shell's runs make one too): no table
  const int64_t half = cfg.PF > 0 ? int64_t{1} << (cfg.PF - 1) : 0;
  off_max_ = (int64_t{kShellBrick - 1} << cfg.PF) + half;
  for (int b = 0; b < 64; ++b) {
    off_[0][b] = int32_t((int64_t(b & 3) << cfg.PF) + half);
    off_[1][b] = int32_t((int64_t((b >> 2) & 3) << cfg.PF) + half);
    off_[2][b] = int32_t((int64_t(b >> 4) << cfg.PF) + half);
  }
}

void ShellBricks::origin(uint32_t k, int64_t o[3]) const {
  o[0] = words_[k].x, o[1] = words_[k].y;
  o[2] = wrap(words_[k].z, pw_ - 1);  // z has PW - 1 bits
}

uint64_t ShellBricks::mask(uint32_t k) const {
  // W = x | y << PW | z << 2 PW (each PW bits); its low 64 bits (3 PW >= 72, and PW <= 32: 2 PW <= 64).
  const ShellWord& w = words_[k];
  const uint64_t m = (uint64_t{1} << pw_) - 1;
  const uint64_t x = uint64_t(w.x) & m, y = uint64_t(w.y) & m;
  return x | y << pw_ | (2 * pw_ < 64 ? uint64_t(w.z) << (2 * pw_) : 0);
}

void ShellBricks::step(uint32_t k, int64_t o[3]) const {
  // Bits 64 .. 69 of W, step i in bits 64 + 2i and 65 + 2i (2-bit signed): z's bits from 64 - 2 PW on.
  const uint64_t s = uint64_t(words_[k].z) >> (64 - 2 * pw_);
  for (int i = 0; i < 3; ++i) {
    const int64_t v = int64_t((s >> (2 * i)) & 3);
    o[i] = wrap(o[i] + (v >= 2 ? v - 4 : v) * brick_step_, pw_);
  }
}

size_t ShellBricks::brick_points(uint64_t m, const int64_t o[3], int32_t* x, int32_t* y, int32_t* z) const {
  // No sum wraps where every coordinate of the origin is at most 2^(PW-1) - 1 - off_max (the offsets are positive).
  const int64_t room = (int64_t{1} << (pw_ - 1)) - 1 - off_max_;
  const int pw = o[0] <= room && o[1] <= room && o[2] <= room ? 32 : pw_;
  return kBrick(off_, m, o, pw, x, y, z);
}

size_t ShellBricks::generate(ShellCursor& at, size_t n, int32_t* x, int32_t* y, int32_t* z) const {
  size_t out = 0;
  while (out < n && at.word < count_) {
    const uint32_t k = at.word;
    if (is_origin(k)) {
      origin(k, at.o);
      ++at.word;
      continue;
    }
    int64_t o[3] = {at.o[0], at.o[1], at.o[2]};
    step(k, o);
    const uint64_t all = mask(k), rest = drop_low_bits(all, at.taken);
    const uint32_t left = uint32_t(__builtin_popcountll(rest));
    if (left > n - out) {  // the block ends inside this word
      const size_t want = n - out;
      out += brick_points(keep_low_bits(rest, want), o, x + out, y + out, z + out);
      at.taken += uint32_t(want);
      return out;
    }
    out += brick_points(rest, o, x + out, y + out, z + out);
    std::copy(o, o + 3, at.o);
    ++at.word;
    at.taken = 0;
  }
  return out;
}

void ShellBricks::skip(ShellCursor& at, uint64_t n) const {
  while (n > 0 && at.word < count_) {
    const uint32_t k = at.word;
    if (is_origin(k)) {
      origin(k, at.o);
      ++at.word;
      continue;
    }
    const uint32_t left = uint32_t(__builtin_popcountll(mask(k))) - at.taken;
    if (left > n) {
      at.taken += uint32_t(n);
      return;
    }
    n -= left;
    step(k, at.o);
    ++at.word;
    at.taken = 0;
  }
}

void walk_shell(const DeviceConfig& cfg, const ShellBricks& shell, uint64_t chunk, ShellWalk& walk, JobSlots* slots) {
  walk.points = 0;
  walk.cursors.assign(1, ShellCursor{});
  const uint64_t lanes = uint64_t(cfg.LANES);
  if (slots) {
    *slots = JobSlots{};
    slots->lanes = lanes;
    slots->starts.clear();
  }
  ShellCursor at;
  uint64_t next = chunk;  // the point of the next cursor
  for (uint32_t k = 0; k < shell.count(); ++k) {
    const uint32_t pop = shell.is_origin(k) ? 0 : uint32_t(__builtin_popcountll(shell.mask(k)));
    // Cursors inside this word (before its points move past them): its origin before the step.
    while (pop && next < walk.points + pop) {
      ShellCursor c = at;
      c.word = k;
      c.taken = uint32_t(next - walk.points);
      walk.cursors.push_back(c);
      next += chunk;
    }
    if (slots) {
      const uint64_t groups = pop == 0 ? 1 : (pop + lanes - 1) / lanes;
      for (uint64_t g = 0; g < groups; ++g)
        slots->starts.push_back(uint32_t(walk.points + std::min<uint64_t>(g * lanes, pop)));
    }
    if (shell.is_origin(k)) shell.origin(k, at.o);
    else shell.step(k, at.o);
    walk.points += pop;
    if (next == walk.points && k + 1 < shell.count()) {
      ShellCursor c = at;
      c.word = k + 1;
      walk.cursors.push_back(c);
      next += chunk;
    }
  }
  if (!slots) return;
  if (slots->starts.empty()) slots->starts.push_back(0);  // an empty job: one empty slot
  slots->groups = slots->starts.size();
  slots->points = walk.points;
  slots->starts.push_back(uint32_t(walk.points));
}

}  // namespace voxcd::detail
