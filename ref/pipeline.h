// The lookup pipeline, one pure function per stage, over the same fixed-width values as the RTL; and a job
// runner for ALL, FIRST and COUNT. This is the specification: nothing in it is clever.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/error.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

using Acc = __int128;  // wide enough for any valid DeviceConfig (acc_width() <= 67)

// Stage 1, transform: acc_i = sum_j M[i][j] * p[j] + t[i], exact, TF fraction bits.
struct Transformed {
  Acc acc[3];
};
Transformed transform(const DeviceConfig& cfg, const Job& job, const ShellWord& p);

// Stage 2, floor, bounds and linear address: index_i = acc_i >> TF (arithmetic: floor); inside when
// 0 <= index_i < n_i on every axis, compared at full width; linear = x + nx * (y + ny * z);
// word = map_base + linear / (MEMW/2), slot = linear % (MEMW/2). linear, word and slot are 0 when outside, and on a
// sparse map (whose table_ref follows).
struct Located {
  int64_t index[3];
  bool inside;
  uint64_t linear;
  uint64_t word;
  uint32_t slot;
};
Located locate(const DeviceConfig& cfg, const Job& job, const Transformed& t);

// Stage 3, word fetch and state select: bits [2*slot+1 : 2*slot] of map word `word`. Only for inside points.
uint8_t fetch_state(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Located& l);

// Stage 4, hit test: inside and the mask has the state's bit.
bool hit_test(uint8_t hit_mask, bool inside, uint8_t state);

// ---- Distance voxmaps (SB > 2, docs/contract.md "Distance voxmaps") ----

// Where node (X, Y, Z) of a map of n_i cells per axis is stored: bank p = parity, half-index
// h = (X>>1) + Hx*((Y>>1) + Hy*(Z>>1)) with H_i = (n_i>>1) + 1, word = map_base + 8*(h / NPW) + p,
// slot h % NPW (bits [SB*slot + SB-1 : SB*slot]).
struct NodeAddress {
  uint64_t word;
  uint32_t slot;
};
NodeAddress node_address(const DeviceConfig& cfg, const Job& job, uint64_t X, uint64_t Y, uint64_t Z);

// Words a job's map takes from map_base: ceil(voxels / (MEMW/2)) for states, 8 * ceil(Hx*Hy*Hz / NPW) for distances;
// a sparse map's table words (its bricks are at brick_base: ref/sparse.h, brick_words).
uint64_t map_words(const DeviceConfig& cfg, const Job& job);

// Stage 3 (distance), node fetch: the values of the 8 nodes around an inside point's cell, q[dx | dy<<1 | dz<<2]
// for node (x+dx, y+dy, z+dz), each SB-bit two's complement.
struct Nodes {
  int64_t q[8];
};
Nodes fetch_nodes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const Located& l);

// The weights' fractions: f_i = (acc_i >> (TF - WB)) & (2^WB - 1).
struct Fractions {
  int64_t f[3];
};
Fractions fractions(const DeviceConfig& cfg, const Transformed& t);

// Stage 4a (distance), interpolation: D = sum q(dx,dy,dz) * wx(dx) * wy(dy) * wz(dz), w(1) = f, w(0) = 2^WB - f;
// exact, IW = SB + 3*WB bits signed.
int64_t interpolate(const DeviceConfig& cfg, const Nodes& n, const Fractions& f);

// Stage 4b (distance), hit test: inside and D <= threshold.
bool distance_hit(int64_t threshold, bool inside, int64_t dist);

// ---- Sparse maps (BL > 0, docs/contract.md "Sparse voxmaps and shells"; layout: ref/sparse.h) ----

// Stage 2 (sparse map): the table word and the code's slot of an inside point's coarse cell.
struct TableRef {
  uint64_t word;
  uint32_t slot;
};
TableRef table_ref(const DeviceConfig& cfg, const Job& job, const Located& l);

// Stage 3a (sparse map), the table read: the cell's code (a brick reference past the job's brick_units reads as
// code 0), its brick's level (-1: a uniform cell) and the brick's first word.
struct Cell {
  uint8_t code;
  int level;
  uint64_t first;
};
Cell read_cell(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const TableRef& r);

// Stage 3b (sparse 2-bit map), the brick read: where an inside point's voxel is in its cell's brick (level >= 0),
// and its state (the uniform code's, or the brick's).
struct BrickRef {
  uint64_t word;
  uint32_t slot;
};
BrickRef brick_ref(const DeviceConfig& cfg, const Cell& c, const Located& l);
uint8_t sparse_state(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Cell& c, const Located& l);

// Stage 3b (sparse distance map): an inside point's sub-cell in its cell's brick at the brick's level (X, the
// sub-cell's corner node; f, its weights, as `fractions` gives a dense map's), the address of node X + (dx, dy, dz)
// of the brick, and the 8 node values (a uniform cell's value at every node).
struct SubCell {
  uint64_t X[3];
  Fractions f;
};
SubCell sub_cell(const DeviceConfig& cfg, const Cell& c, const Located& l, const Transformed& t);
NodeAddress brick_node_address(const DeviceConfig& cfg, const Cell& c, uint64_t X, uint64_t Y, uint64_t Z);
Nodes brick_nodes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Cell& c, const SubCell& s);

// What a point looks up, every stage composed: whether it is inside, its voxel, its state (2-bit) and D
// (distance), on any map (dense or sparse). `p` is the point as the shell word (or the sparse shell) gives it.
struct Lookup {
  Located loc;
  uint8_t state = 0;
  int64_t dist = 0;
  bool hit = false;
};
Lookup look_up(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& job, const ShellWord& p);

// The points of a job in order: its shell words, or the points its sparse shell generates (ref/sparse.h).
std::vector<ShellWord> job_points(const DeviceConfig& cfg, const std::vector<ShellWord>& shell, const Job& job);

// The rules of validate_job a job breaks, one bit each (0: a valid job). The AXI top (rtl/voxcd_axi.sv) checks the
// same rules in hardware and reports them in its error records (docs/contract.md, "Refused jobs"); bit 0 is the
// descriptor's own format (its reserved bytes), which a Job does not have.
enum JobFault : uint32_t {
  kFaultMode = 1u << 1,       // mode not ALL, FIRST or COUNT, a hit mask above 15, or sparse bits other than 1, 2
  kFaultTag = 1u << 2,        // the tag does not fit TAGW bits
  kFaultShell = 1u << 3,      // shell_base does not fit SAW, or [shell_base, + shell_count) leaves the loaded words,
                              // or a sparse shell on a dense device
  kFaultDims = 1u << 4,       // nx, ny or nz outside 1..2^DW
  kFaultMap = 1u << 5,        // map_base does not fit MAW, a distance map is off a bank boundary, or (with valid
                              // dimensions) the map's words leave the loaded words; a sparse map on a dense device,
                              // its bricks' words not loaded or off a bank boundary; a dense map's brick fields not 0
  kFaultPose = 1u << 6,       // an entry of M does not fit MW bits, or of t TW bits
  kFaultThreshold = 1u << 7,  // a distance job's threshold does not fit IW bits; a 2-bit job's is not 0
};
uint32_t job_faults(const DeviceConfig& cfg, const Job& job, uint64_t shell_words, uint64_t loaded_map_words);

// Throws JobError unless every field fits its format under cfg and the job reads only loaded words:
// shell words [shell_base, shell_base + shell_count) < shell_words, map words
// [map_base, map_base + map_words(cfg, job)) < loaded_map_words; a distance map starts on a bank boundary
// (map_base % 8 == 0) and its threshold fits IW bits; a 2-bit job's threshold is 0. A sparse map or shell needs a
// sparse device; a sparse map's brick words [brick_base, brick_base + brick_words) are loaded (a distance map's
// brick_base a multiple of 8); a dense map has brick_base and brick_units 0.
void validate_job(const DeviceConfig& cfg, const Job& job, uint64_t shell_words, uint64_t loaded_map_words);

// Throws JobError unless the memory image fits cfg: at most 2^SAW shell words with PW-bit coordinates, at most
// 2^MAW map words of MEMW bits.
void validate_memory(const DeviceConfig& cfg, const DeviceMemory& mem);

// Runs one job (which must be valid) and appends its records: hits in ascending point order (ALL), the lowest
// one (FIRST) or none (COUNT), then the completion record without cycles.
void run_job(const DeviceConfig& cfg, const DeviceMemory& mem, const Job& job, std::vector<Record>& out);

// Validates the memory and every job, then runs the jobs in order. Cycles are left empty: see ref/timing.h.
std::vector<Record> run_stream(const DeviceConfig& cfg, const DeviceMemory& mem, const std::vector<Job>& jobs);

}  // namespace voxcd
