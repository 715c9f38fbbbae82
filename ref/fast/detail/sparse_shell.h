// Internal to FastRunner: a sparse shell's points (docs/contract.md, "Shell bricks") generated from its words a block
// at a time, as ref/sparse.h's shell_points gives them, into the coordinate arrays the lookup kernels read; where a
// run of points begins (a cursor), so that the pieces of a job start anywhere; and the job's slots (ref/timing.h,
// JobSlots) from the words' point counts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// Where a run of a sparse shell's points begins: word `word` of the job (relative to shell_base), of which `taken`
// points were generated before, and the brick origin as it is before that word (before its step).
struct ShellCursor {
  uint32_t word = 0;
  uint32_t taken = 0;
  int64_t o[3] = {0, 0, 0};
};

// A job's sparse shell, ready to generate from: its words and the per-bit offsets of a brick's points,
// d * 2^PF + 2^(PF-1) for bit i's d = (i & 3, (i >> 2) & 3, i >> 4).
class ShellBricks {
 public:
  ShellBricks(const DeviceConfig& cfg, const ShellWord* words, uint32_t count);

  // Points [from the cursor) up to `n` of them into x, y, z (each with room for n + 16 values: the vector kernel
  // stores whole registers); the cursor moves past them. Returns how many (fewer than n only at the shell's end).
  size_t generate(ShellCursor& at, size_t n, int32_t* x, int32_t* y, int32_t* z) const;
  // The cursor `n` points after `at` (no points generated).
  void skip(ShellCursor& at, uint64_t n) const;

  // Word k (< count): an origin word; its origin; a brick word's mask and step.
  bool is_origin(uint32_t k) const { return words_[k].z < 0; }  // W[3 PW - 1]: the sign bit of z
  void origin(uint32_t k, int64_t o[3]) const;
  uint64_t mask(uint32_t k) const;
  // Moves `o` by brick word k's step (wrapping at PW bits).
  void step(uint32_t k, int64_t o[3]) const;
  uint32_t count() const { return count_; }

 private:
  // Points of one brick word with origin o (after its step), bits of `mask` only, into x, y, z; returns their
  // number.
  size_t brick_points(uint64_t mask, const int64_t o[3], int32_t* x, int32_t* y, int32_t* z) const;

  const ShellWord* words_;
  uint32_t count_;
  int pw_, pf_;
  int64_t brick_step_;  // 4 * 2^PF
  int64_t off_max_ = 0;  // the largest offset, 3 * 2^PF + 2^(PF-1)
  alignas(64) int32_t off_[3][64];
};

// The walk over a job's words that FastRunner makes before it runs the job: its point count, the cursor at each
// multiple of `chunk` points (cursors[k]: point k * chunk), and, with `slots`, its slots as job_slots gives them.
struct ShellWalk {
  uint64_t points = 0;
  std::vector<ShellCursor> cursors;
};
void walk_shell(const DeviceConfig& cfg, const ShellBricks& shell, uint64_t chunk, ShellWalk& walk, JobSlots* slots);

}  // namespace voxcd::detail
