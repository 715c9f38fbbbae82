// Sparse maps and shells (docs/contract.md, "Sparse voxmaps and shells"): the layout of a sparse map's table and
// bricks, and the points a sparse shell's words generate. The stage functions that read a sparse map are in
// ref/pipeline.h; the encoders here are the host's and the vector generator's way to write the layout.
#pragma once

#include <cstdint>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// A distance brick's levels: 0 (the voxel grid) .. kMaxLevel (sub-cells of 2^-kMaxLevel voxel).
constexpr int kMaxLevel = 3;
// A shell brick is kShellBrick^3 points of the shell's grid, one bit of a 64-bit mask each.
constexpr int kShellBrick = 4;

// Table codes. A 2-bit map's: a uniform state (kEmpty, kSurface, kInterior) or kCodeBrick. A distance map's:
// uniform qmax or qmin, or a brick of level l (kCodeLevel0 + l); codes above kCodeLevel0 + kMaxLevel read as
// kCodeFar.
constexpr uint8_t kCodeBrick = 3;
constexpr uint8_t kCodeFar = 0, kCodeDeep = 1, kCodeLevel0 = 2;

// CW: the bits of a code, 2 on a 2-bit device, 4 on a distance one.
int code_bits(const DeviceConfig& cfg);
// CPW: the codes in a table word (its low MEMW/2 bits; the high MEMW/2 bits are the word's rank).
uint64_t table_cells_per_word(const DeviceConfig& cfg);
// B = 2^BL: a coarse cell's (a brick's) voxels per axis.
inline uint64_t brick_edge(const DeviceConfig& cfg) { return uint64_t{1} << cfg.BL; }

// The coarse cells of a job's map, ceil(n_i / B) per axis.
struct CoarseDims {
  uint64_t c[3] = {1, 1, 1};
  uint64_t cells() const { return c[0] * c[1] * c[2]; }
};
CoarseDims coarse_dims(const DeviceConfig& cfg, const Job& job);
// The table's words: ceil(cells / CPW).
uint64_t table_words(const DeviceConfig& cfg, const Job& job);

// UW: the words of a unit of brick memory (a 2-bit brick; a distance brick of level 0).
uint64_t unit_words(const DeviceConfig& cfg);
// A distance brick of level l: H_l = B 2^(l-1) + 1 half-grid positions per axis, W_l words, U_l units (a 2-bit
// brick: one unit).
uint64_t level_half_extent(const DeviceConfig& cfg, int level);
uint64_t level_words(const DeviceConfig& cfg, int level);
uint64_t level_units(const DeviceConfig& cfg, int level);
// The level of a code's brick, or -1 for a uniform code (and a code read as uniform).
int code_level(const DeviceConfig& cfg, uint8_t code);
// The units a code's brick takes (0 for a uniform code).
uint64_t code_units(const DeviceConfig& cfg, uint8_t code);
// The brick words a job may read: [brick_base, brick_base + brick_units * UW).
inline uint64_t brick_words(const DeviceConfig& cfg, const Job& job) {
  return uint64_t(job.brick_units) * unit_words(cfg);
}

// The table of a map whose cells (in table order, t = cx + Cx (cy + Cy cz)) have `codes`: each word's codes and its
// rank (the units of every brick before the word). std::invalid_argument when a code is not one of the device's, or
// a rank does not fit MEMW/2 bits.
std::vector<uint64_t> table_image(const DeviceConfig& cfg, const std::vector<uint8_t>& codes);
// The units of every brick of `codes` (the brick_units of a job on that table).
uint64_t table_units(const DeviceConfig& cfg, const std::vector<uint8_t>& codes);

// ---- Shell bricks ----

// A shell word as the 3 PW-bit value W = x | y << PW | z << 2 PW (each coordinate's PW bits).
unsigned __int128 shell_bits(const DeviceConfig& cfg, const ShellWord& w);
ShellWord shell_word_of_bits(const DeviceConfig& cfg, unsigned __int128 bits);
// W[3PW-1]: an origin word (else a brick word).
bool is_origin_word(const DeviceConfig& cfg, const ShellWord& w);
// An origin word setting the brick origin to o (each coordinate in the shell words' units; z must fit PW-1 bits,
// x and y PW bits: std::invalid_argument otherwise).
ShellWord origin_word(const DeviceConfig& cfg, int64_t x, int64_t y, int64_t z);
// A brick word: the origin moves by step[i] * 4 * 2^PF (step[i] in -2..1, else std::invalid_argument), then the set
// bits of mask are its points.
ShellWord brick_word(const DeviceConfig& cfg, uint64_t mask, const int step[3]);
// A brick word's mask and steps (garbage for an origin word).
uint64_t brick_mask(const DeviceConfig& cfg, const ShellWord& w);
void brick_step(const DeviceConfig& cfg, const ShellWord& w, int step[3]);

// The points a sparse-shell job's words generate, in order (the job's point k is element k), as the device
// generates them: the origin 0 at the job's start, set by an origin word, moved by a brick word's step, a point
// o + d * 2^PF + h per set bit (PW-bit wrapping sums). `word_points`, when given, gets each word's point count. The
// job must be valid for the shell memory (validate_job).
std::vector<ShellWord> shell_points(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job,
                                    std::vector<uint32_t>* word_points = nullptr);

}  // namespace voxcd
