// Internal to host/object (the sparse shell): the order of shell bricks along chains of neighbours. A device moves
// from one brick to the next by a step of -2..1 bricks per axis (docs/contract.md, "Shell bricks"); every other move
// costs an origin word, so the chains should be few and long.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace voxcd::detail {

using BrickPos = std::array<uint16_t, 3>;

// A step from brick a to brick b a brick word can take: every axis's difference in -2..1.
inline bool chain_step(const BrickPos& a, const BrickPos& b) {
  for (int i = 0; i < 3; ++i) {
    const int d = int(b[i]) - int(a[i]);
    if (d < -2 || d > 1) return false;
  }
  return true;
}

// An order of `bricks` (distinct, sorted by z, then y, then x) as chains: a walk that moves to an unvisited brick one
// step away while it can (Warnsdorff's rule: the one with the fewest unvisited bricks a step away from it; ties: the
// lowest index), and else starts again at the lowest unvisited brick. Returns indices into `bricks`. Deterministic.
std::vector<uint32_t> chain_order(const std::vector<BrickPos>& bricks);

}  // namespace voxcd::detail
