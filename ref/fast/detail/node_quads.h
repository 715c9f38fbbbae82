// Internal to FastRunner's distance path: a second copy of a distance voxmap (SB <= 8) in an order that puts the
// eight nodes of a cell in eight consecutive bytes, so that one 8-byte read (one gather lane) serves a point instead
// of eight reads from the eight parity banks (docs/contract.md, "Distance voxmaps"; docs/device-speed.md).
//
// Layout ("node quads"): entry e(X, Y, Z) = X + (nx + 1) * (Y + ny * Z) for X in [0, nx], Y in [0, ny), Z in [0, nz)
// is 4 bytes, the nodes (X, Y, Z), (X, Y + 1, Z), (X, Y, Z + 1), (X, Y + 1, Z + 1) in that order, each stored as
// q + 2^(SB-1) (so 0 .. 2^SB - 1, no sign to extend). The 8 bytes at entry e(x, y, z) of cell (x, y, z) are its eight
// nodes: byte b is node (x + (b >> 2), y + (b & 1), z + (b >> 1 & 1)). 4 bytes per cell (plus one row of entries
// per (Y, Z)): 4 times the parity banks' bytes at SB = 8, 8 times at SB = 4.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>

namespace voxcd::detail {

struct NodeQuads {
  struct Free {
    void operator()(uint32_t* p) const { std::free(p); }
  };
  uint64_t map_base = 0;   // the map's first word and its words [map_base, map_end) in the voxmap memory
  uint64_t map_end = 0;
  uint32_t nx = 0, ny = 0, nz = 0;
  // (nx + 1) * ny * nz entries; beyond 2 MiB on 2 MiB pages where the system gives them (madvise): a lookup reads
  // anywhere in the copy, and with 4 KiB pages a large one misses the TLB on almost every point.
  std::unique_ptr<uint32_t[], Free> entries;
  size_t count = 0;
  uint64_t bytes() const { return uint64_t(count) * sizeof(uint32_t); }
};

// The copy's size in bytes for a map of nx x ny x nz cells (no allocation).
uint64_t node_quad_bytes(uint32_t nx, uint32_t ny, uint32_t nz);

// Room for n entries (freed by NodeQuads::Free), on 2 MiB pages when they take at least one.
uint32_t* allocate_quads(size_t n);

// Writes the copy of the map of nx x ny x nz cells at `map` (its first word) with SB-bit nodes, nodes_per_word of
// them in a word, into out[0, (nx + 1) ny nz): the layout above. A sparse map's distance brick of level l is laid out as
// such a map of B 2^l cells per axis (docs/contract.md), so its copy is this too (detail/sparse_copy.h).
void fill_node_quads(const uint64_t* map, uint32_t nx, uint32_t ny, uint32_t nz, int sb, int nodes_per_word,
                     uint32_t* out);

// Builds the copy of the map of nx x ny x nz cells at `map` (its first word, the voxmap memory's map_base) with SB-bit
// nodes (SB <= 8), nodes_per_word of them in a word; map_words is the map's length in words (map_words of ref/).
NodeQuads build_node_quads(const uint64_t* map, uint64_t map_base, uint64_t map_words, uint32_t nx, uint32_t ny,
                           uint32_t nz, int sb, int nodes_per_word);

}  // namespace voxcd::detail
