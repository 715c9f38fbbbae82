// Internal to ref/vector_gen.cpp: the sparse maps and sparse shells of a sparse device's generated vectors
// (docs/conformance.md, "Generating").
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// Where a generated sparse map lies: its table at map_base, its bricks at brick_base (brick_units units).
struct SparseMapPlan {
  uint32_t map_base = 0, brick_base = 0, brick_units = 0;
  uint32_t nx = 1, ny = 1, nz = 1;
};

// Writes a sparse map of nx x ny x nz voxels filled with `pattern` (0 .. kSparseMapPatterns - 1) into `map` from
// word `next` (the table, a gap, then its bricks, on bank boundaries on a distance device), over words the caller
// filled with garbage; grows `map` up to `limit` words. False (nothing written) when it does not fit.
constexpr int kSparseMapPatterns = 5;
bool add_sparse_map(const DeviceConfig& cfg, std::mt19937_64& rng, uint32_t nx, uint32_t ny, uint32_t nz,
                    int pattern, uint64_t next, uint64_t limit, std::vector<uint64_t>& map, SparseMapPlan& plan);

// `words` shell words of a sparse shell with `pattern` (0 .. kSparseShellPatterns - 1): chains of brick words of
// every density (empty and full masks included) with every step, origin words among them (extreme ones that wrap
// the origin too), and a sphere's surface walked brick by brick.
constexpr int kSparseShellPatterns = 4;
std::vector<ShellWord> sparse_shell_block(const DeviceConfig& cfg, std::mt19937_64& rng, int pattern, size_t words);

}  // namespace voxcd::detail
