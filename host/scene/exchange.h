// What the ranks of a distributed simulation tell each other each frame (docs/scale.md, "Distributed simulate"):
// every rank keeps every body's state and integrates it the same way, tests only the pairs of its slab on its own
// device, and gets every other rank's outcomes so that all ranks apply the same responses in the same order.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/host/scene/partition.h"

namespace voxcd {

// One tested pair's outcome: what the response needs, and the frame's counts.
struct PairOutcome {
  uint32_t a = 0, b = 0;  // bodies, a < b
  uint64_t hits = 0, lookups = 0, contacts = 0, cycles = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // sum of A's outward contact normals minus B's
};

// One rank's counts of a frame.
struct RankCounts {
  uint64_t pairs = 0;   // broadphase pairs it owns
  uint64_t tested = 0;  // of those, tested on its device
  uint64_t cycles = 0;  // its device's cycles for the frame
};

class FrameExchange {
 public:
  virtual ~FrameExchange() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Called by every rank once a frame with the frame's slabs, its own outcomes (in pair order) and counts; returns
  // every rank's outcomes merged in pair order, with `total` the sums of pairs and tested and the largest cycles.
  // Throws std::runtime_error naming the rank and its slab when a rank fails or says nothing in time.
  virtual std::vector<PairOutcome> exchange(uint64_t frame, const Slabs& slabs, const std::vector<PairOutcome>& mine,
                                            const RankCounts& own, RankCounts& total) = 0;
};

// Merges per-rank outcome lists (each in pair order, no pair in two) into one in pair order.
std::vector<PairOutcome> merge_outcomes(const std::vector<std::vector<PairOutcome>>& per_rank);

// "slab 2 of 3 (y in [31.4, 66.1))", for messages.
std::string slab_text(const Slabs& s, int rank);

// The bytes of a rank's message (frame, counts, outcomes) and back; std::runtime_error for a message that is not one.
std::string encode_outcomes(uint64_t frame, const RankCounts& counts, const std::vector<PairOutcome>& outcomes);
void decode_outcomes(const std::string& bytes, uint64_t& frame, RankCounts& counts, std::vector<PairOutcome>& outcomes);

}  // namespace voxcd
