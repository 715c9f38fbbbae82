// The order in which the pair tests place a shell in device memory (host/pairs/collide.cpp): its points grouped by
// blocks of kBlock^3 cells of the shell's grid, so that consecutive points lie close together and a cluster of them
// has a small box that culling can leave out as a whole; and the ranks that put the hits of such an order back in
// ascending point order, which the contacts keep.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxcd/ref/types.h"

namespace voxcd::detail {

struct ShellOrder {
  static constexpr uint32_t kBlock = 8;
  std::vector<uint32_t> point;        // slot k of the device's copy holds shell point point[k]
  std::vector<uint32_t> block_first;  // per non-empty block its first slot, then the number of points
};

// The block order of a shell whose point k lies in cell cells[k] (cells in ascending linear order, as a PointShell
// keeps them): blocks in linear order of the block grid, each block's points in ascending point order.
ShellOrder block_order(const std::vector<std::array<uint32_t, 3>>& cells);

// The hit records of one job of a direction: recs[0, n), their slots first + rec.point, and where each one's place
// among the direction's contacts goes.
struct HitSpan {
  const Record* recs;
  uint32_t* dest;
  size_t n;
  uint32_t first;
};

class RankBits;

// Which hit records of one direction make contacts, and their places: ALL every record, in ascending point order from
// `base`; FIRST (first_only, each span holding its job's first hit first) only the record of the lowest point. Sets
// each span's n to the records it keeps and their dest; returns the records kept.
size_t keep_direction(HitSpan* spans, size_t n, bool first_only, const uint32_t* order, size_t points, uint32_t base,
                      RankBits& bits);

// Bits over a shell's points, for ranking the points of a direction's hits.
class RankBits {
 public:
  // Gives every record of `spans` (the hits of one direction, each point once) base + its rank among them in
  // ascending point order (order: slot -> point; `points`: the shell's size).
  void place(const HitSpan* spans, size_t n, const uint32_t* order, size_t points, uint32_t base);

 private:
  std::vector<uint64_t> bits_;
  std::vector<uint32_t> below_;  // per word, the bits set in the words before it
};

}  // namespace voxcd::detail
