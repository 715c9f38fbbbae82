// Internal to FastRunner: the coordinates of a run of a job's points, a block at a time, in the forms its kernels read:
// for a dense shell, views into the runner's copies of the shell memory; for a sparse shell, points generated from its
// words (detail/sparse_shell.h) into buffers of the block's size.
#pragma once

#include <cstddef>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/fast/detail/sparse_shell.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// Points [0, n) of a block: x, y, z as int32 (the double path's kernels), ix, iy, iz as int64 (the int64 path's),
// w as shell words (the wide path and the scalar paths); each null unless asked for.
struct BlockCoords {
  const int32_t *x = nullptr, *y = nullptr, *z = nullptr;
  const int64_t *ix = nullptr, *iy = nullptr, *iz = nullptr;
  const ShellWord* w = nullptr;
};

// The runner's copies of the shell memory: its words, and where the path keeps them, as int32 and int64 columns.
struct ShellArrays {
  const ShellWord* words;
  const int32_t *sx, *sy, *sz;
  const int64_t *ix, *iy, *iz;
};

// Points [first, first + n) of a dense shell in the forms of `need` (PointBlocks::Need).
inline BlockCoords dense_block(const ShellArrays& a, size_t first, unsigned need);

class PointBlocks {
 public:
  static constexpr size_t kMax = 256;  // the largest block
  enum Need : unsigned { kInt32 = 1, kInt64 = 2, kWords = 4 };

  // Job j's points from `begin` on (a sparse shell's from the cursor `at` where given, which must be at `begin`),
  // in the forms of `need`.
  PointBlocks(const DeviceConfig& cfg, const ShellArrays& a, const Job& j, uint32_t begin, const ShellCursor* at,
              unsigned need)
      : a_(a), need_(need), next_(size_t(j.shell_base) + begin), sparse_(j.sparse_shell()),
        bricks_(cfg, a.words + j.shell_base, j.sparse_shell() ? j.shell_count : 0) {
    if (!sparse_) return;
    if (at) cursor_ = *at;
    else bricks_.skip(cursor_, begin);
  }

  // The next n (<= kMax) points.
  BlockCoords next(size_t n) {
    BlockCoords c;
    if (!sparse_) {
      const size_t b = next_;
      next_ += n;
      return dense_block(a_, b, need_);
    }
    bricks_.generate(cursor_, n, x_[0], x_[1], x_[2]);
    c.x = x_[0], c.y = x_[1], c.z = x_[2];
    if (need_ & kInt64) {
      for (int i = 0; i < 3; ++i)
        for (size_t k = 0; k < n; ++k) l_[i][k] = x_[i][k];
      c.ix = l_[0], c.iy = l_[1], c.iz = l_[2];
    }
    if (need_ & kWords) {
      for (size_t k = 0; k < n; ++k) w_[k] = ShellWord{x_[0][k], x_[1][k], x_[2][k]};
      c.w = w_;
    }
    return c;
  }

 private:
  ShellArrays a_;
  unsigned need_;
  size_t next_;  // a dense shell's next word
  bool sparse_;
  ShellBricks bricks_;
  ShellCursor cursor_;
  alignas(64) int32_t x_[3][kMax + 16];  // room for the generator's whole-register stores
  int64_t l_[3][kMax];
  ShellWord w_[kMax];
};

inline BlockCoords dense_block(const ShellArrays& a, size_t first, unsigned need) {
  BlockCoords c;
  if (need & PointBlocks::kInt32) c.x = a.sx + first, c.y = a.sy + first, c.z = a.sz + first;
  if (need & PointBlocks::kInt64) c.ix = a.ix + first, c.iy = a.iy + first, c.iz = a.iz + first;
  if (need & PointBlocks::kWords) c.w = a.words + first;
  return c;
}

// Calls block(b, n, coords) for the blocks of points [begin, end) of sparse-shell job j (`size` points each, at most
// PointBlocks::kMax), generated in the forms of `need`, until it returns true (FIRST has its hit). Not inlined: the
// buffers stay off the frames of the dense shells' loops.
template <class Block>
__attribute__((noinline)) void sparse_shell_blocks(const DeviceConfig& cfg, const ShellArrays& a, const Job& j,
                                                   uint32_t begin, uint32_t end, const ShellCursor* at, unsigned need,
                                                   size_t size, Block&& block) {
  PointBlocks points(cfg, a, j, begin, at, need);
  size_t n = 0;
  for (uint32_t b = begin; b < end; b += uint32_t(n)) {
    n = std::min<size_t>(size, end - b);
    if (block(b, n, points.next(n))) return;
  }
}

// The blocks of points [begin, end) of job j, dense or sparse shell alike.
template <class Block>
void for_blocks(const DeviceConfig& cfg, const ShellArrays& a, const Job& j, uint32_t begin, uint32_t end,
                const ShellCursor* at, unsigned need, size_t size, Block&& block) {
  if (j.sparse_shell()) return sparse_shell_blocks(cfg, a, j, begin, end, at, need, size, block);
  size_t n = 0;
  for (uint32_t b = begin; b < end; b += uint32_t(n)) {
    n = std::min<size_t>(size, end - b);
    if (block(b, n, dense_block(a, size_t(j.shell_base) + b, need))) return;
  }
}

}  // namespace voxcd::detail
