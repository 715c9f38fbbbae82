// The space decomposition of a distributed simulation (docs/scale.md, "Distributed simulate"): slabs along one axis
// that hold equal numbers of bodies, recomputed every frame from the bodies' bounds so that they follow the bodies;
// which bodies a rank's broadphase sees and which rank tests a pair.
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/host/broadphase/broadphase.h"

namespace voxcd {

struct Slabs {
  int axis = 0;               // 0, 1, 2: x, y, z
  std::vector<double> cuts;   // ascending, ranks - 1 of them: slab r is [cuts[r-1], cuts[r]) (unbounded at the ends)
  int ranks() const { return int(cuts.size()) + 1; }
  // The slab holding coordinate v along the axis.
  int slab_of(double v) const;
};

// Slabs for `ranks` ranks: along the axis over which the bodies' sphere centres spread widest, cut halfway between
// the centres that split them into equal counts. Deterministic: every rank computes the same slabs from the same
// bounds.
Slabs split_slabs(const std::vector<BodyBounds>& bodies, int ranks);

// The bodies that reach into slab r (touching counts) with their enclosing sphere or their box, ascending: the
// bodies rank r's broadphase sees.
std::vector<uint32_t> slab_bodies(const Slabs& s, int r, const std::vector<BodyBounds>& bodies);

// The rank that tests the pair: the slab of the lower end of the overlap of the two bodies' extents (sphere and box)
// along the axis. For a pair whose spheres or boxes overlap both bodies reach into it, so its broadphase finds the
// pair, and no other rank tests it.
int pair_owner(const Slabs& s, const BodyBounds& a, const BodyBounds& b);

}  // namespace voxcd
