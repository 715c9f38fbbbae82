// A shell's blocks as sparse shell words (host/pairs/detail/shell_order.h): the pair tests' image of a centre shell on
// a sparse device.
#include <algorithm>
#include <stdexcept>

#include "voxcd/host/pairs/detail/shell_order.h"
#include "voxcd/ref/sparse.h"

namespace voxcd::detail {

namespace {

constexpr uint32_t kBrick = kShellBrick;  // 4: a shell brick's cells per axis

// A cell's brick within its block (0..7, x fastest) and its bit within the brick (x fastest), as one sort key.
uint32_t brick_key(const std::array<uint32_t, 3>& c) {
  const uint32_t in_block = (c[0] / kBrick % 2) | (c[1] / kBrick % 2) << 1 | (c[2] / kBrick % 2) << 2;
  const uint32_t bit = c[0] % kBrick + kBrick * (c[1] % kBrick + kBrick * (c[2] % kBrick));
  return in_block << 6 | bit;
}

// Appends one block's words: an origin word at its first brick, then a brick word per brick (the bricks of a block
// are neighbours: steps of -1..1). `slots` are the block's points, sorted by brick_key.
void block_words(const std::vector<std::array<uint32_t, 3>>& cells, const uint32_t* slots, size_t n,
                 const DeviceConfig& cfg, std::vector<ShellWord>& out) {
  const int64_t unit = int64_t{kBrick} << cfg.PF;  // a brick in shell words' units
  std::array<int64_t, 3> prev{};
  for (size_t k = 0; k < n;) {
    const size_t brick_first = k;
    const std::array<uint32_t, 3>& c = cells[slots[k]];
    const std::array<int64_t, 3> b = {c[0] / kBrick, c[1] / kBrick, c[2] / kBrick};
    const uint32_t brick = brick_key(c) >> 6;
    uint64_t mask = 0;
    for (uint32_t key; k < n && ((key = brick_key(cells[slots[k]])) >> 6) == brick; ++k)
      mask |= uint64_t{1} << (key & 63);
    int step[3] = {0, 0, 0};
    if (brick_first == 0)  // the block's first brick: the origin moves there
      out.push_back(origin_word(cfg, b[0] * unit, b[1] * unit, b[2] * unit));
    else
      for (int i = 0; i < 3; ++i) step[i] = int(b[i] - prev[i]);
    out.push_back(brick_word(cfg, mask, step));
    prev = b;
  }
}

}  // namespace

ShellOrder sparse_block_order(const std::vector<std::array<uint32_t, 3>>& cells, const DeviceConfig& cfg) {
  if (!cfg.sparse() || cfg.PF < 1)
    throw std::invalid_argument("sparse_block_order: the device (" + cfg.to_string() +
                                ") holds no sparse shells of cell centres (BL > 0 and PF >= 1 needed)");
  ShellOrder o = block_order(cells);
  o.block_word.reserve(o.block_first.size());
  for (size_t b = 0; b + 1 < o.block_first.size(); ++b) {
    uint32_t* first = o.point.data() + o.block_first[b];
    const size_t n = o.block_first[b + 1] - o.block_first[b];
    std::sort(first, first + n, [&](uint32_t a, uint32_t c) { return brick_key(cells[a]) < brick_key(cells[c]); });
    o.block_word.push_back(uint32_t(o.words.size()));
    block_words(cells, first, n, cfg, o.words);
  }
  o.block_word.push_back(uint32_t(o.words.size()));
  return o;
}

}  // namespace voxcd::detail
