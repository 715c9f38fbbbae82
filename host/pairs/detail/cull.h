// Cluster culling of the pair tests (host/pairs/collide.cpp): which boxes of shell points can land in a voxmap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "voxcd/host/pairs/detail/empty_space.h"

namespace voxcd::detail {

// The boxes of a shell's clusters of points: per axis, each box's centre and half-extent in the shell's grid.
struct ClusterBoxes {
  const double* centre[3];
  const double* half[3];
  size_t n;
};

// Bit k of bits[k / 64] = 1 when box k can land in [0, n) through p -> M p + t (aM = |M|): the box of centre
// M c + t and half-extent aM h meets [-1e-4, n + 1e-4) on every axis. The slack covers the double arithmetic (the
// values stay below 2^40, where its rounding is far below 1e-4), so a box with a point in [0, n) is always kept;
// the two kernels could differ only for a box within that rounding of the slack's edge, and then in lookups,
// never in hits. `vector`: the AVX-512 kernel where the processor has it (eight boxes a step, the bits straight
// from the comparison masks); false: the portable loop. Writes (n + 63) / 64 words.
void cull_clusters(const ClusterBoxes& boxes, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
                   const double (&n)[3], uint64_t* bits, bool vector = true);

// What a lookup in a voxmap can hit: on 2-bit states a voxel whose state is in `mask`, on a distance field a point
// whose interpolated distance is at most `threshold` (weights of `wb` bits).
struct HitTest {
  const EmptySpace* space = nullptr;
  bool field = false;
  uint32_t mask = 0;
  int64_t threshold = 0;
  int wb = 0;
  double n[3] = {0, 0, 0};  // the voxmap's voxels per axis
};

// Clears the bit of every box k in [0, boxes.n) whose points (through p -> M p + t, the box of cull_clusters with its
// slack) can land only in voxels where `test` proves no hit: its points are outside the voxmap or in its empty air.
void cull_empty(const ClusterBoxes& boxes, const double (&M)[3][3], const double (&aM)[3][3], const double (&t)[3],
                const HitTest& test, uint64_t* bits);

// Whether cull_clusters(..., true) runs the AVX-512 kernel on this processor.
bool cull_is_vector();

}  // namespace voxcd::detail
