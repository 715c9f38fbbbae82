// The order in which the pair tests place a shell in device memory (host/pairs/collide.cpp): its points grouped by
// blocks of kBlock^3 cells of the shell's grid, so that consecutive points lie close together and a cluster of them
// has a small box that culling can leave out as a whole; and the ranks that put the hits of such an order back in
// ascending point order, which the contacts keep.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

struct ShellOrder {
  static constexpr uint32_t kBlock = 8;
  std::vector<uint32_t> point;        // slot k of the device's copy holds shell point point[k]
  std::vector<uint32_t> block_first;  // per non-empty block its first slot, then the number of points
  // A sparse shell's device words (docs/contract.md, "Shell bricks": each block an origin word, then its shell bricks),
  // and per block its first word, then the number of words; both empty for a dense shell (a point a word).
  std::vector<ShellWord> words;
  std::vector<uint32_t> block_word;
  bool sparse() const { return !words.empty(); }
};

// The block order of a shell whose point k lies in cell cells[k] (cells in ascending linear order, as a PointShell
// keeps them): blocks in linear order of the block grid, each block's points in ascending point order.
ShellOrder block_order(const std::vector<std::array<uint32_t, 3>>& cells);

// The same blocks as a sparse shell of cfg's device (cell centres only): each block an origin word and the 2 x 2 x 2
// shell bricks of 4^3 cells it holds, in z, y, x order, each a brick word (its mask, its step from the one before);
// slots (the points the words generate) in that order, each brick's cells in ascending bit order, so a block's points
// are no longer in ascending point order. std::invalid_argument when cfg cannot hold sparse shells, or a cell's origin
// does not fit an origin word.
ShellOrder sparse_block_order(const std::vector<std::array<uint32_t, 3>>& cells, const DeviceConfig& cfg);

// The hits of one job of a direction, held in columns (ref/fast/hits.h) from index `at`: their points point[0, n)
// (relative to the job), their slots first + point[r].
struct HitSpan {
  const uint32_t* point;
  size_t n;
  uint32_t first;
  size_t at;
};

// A hit that makes a contact: its index in the columns, and its shell point.
struct SortedHit {
  uint32_t hit;
  uint32_t point;
};

class RankBits;

// The hit records of one direction that make contacts, into out[0, kept) in ascending point order: ALL every record,
// FIRST (first_only; each span holding its job's first hit first) only the record of the lowest point. `out` has room
// for every record of the spans; order: slot -> point; `points`: the shell's size. Returns the records kept.
size_t keep_direction(const HitSpan* spans, size_t n, bool first_only, const uint32_t* order, size_t points,
                      SortedHit* out, RankBits& bits);

// Bits over a shell's points, for ranking the points of a direction's hits.
class RankBits {
 public:
  // Every record of `spans` (the hits of one direction, each point once) into out[its rank among them in ascending
  // point order] (order: slot -> point; `points`: the shell's size).
  void place(const HitSpan* spans, size_t n, const uint32_t* order, size_t points, SortedHit* out);

 private:
  std::vector<uint64_t> bits_;
  std::vector<uint32_t> below_;  // per word, the bits set in the words before it
};

}  // namespace voxcd::detail
