// Internal to FastRunner's distance path (ref/fast/distance.cpp): the block kernel that looks up a block of points
// in a distance voxmap in vector registers (ref/fast/distance_kernel.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace voxcd::detail {

// What the kernel needs of a job: M and t scaled by 2^-(TF - WB) (exact: a power of two), so that floor(M p + t) is
// the accumulator >> (TF - WB), whose low WB bits are the weights and the rest the cell.
struct DistanceJob {
  double m[9], t[3], n[3];
  double weight;      // 2^WB
  double inv_weight;  // 2^-WB
  double threshold;   // the job's, exact (IW <= 51)
  int32_t hx, hy;     // (n_x >> 1) + 1, (n_y >> 1) + 1
  int npw_bits, sb;   // log2 of the nodes per word (a power of two), SB
  int sb_bits;        // log2 SB (a power of two)
  const uint64_t* map;
  // The node-quad kernels' (detail/node_quads.h): the copy, nx + 1, and the threshold and a distance offset by the
  // nodes' bias: with every node stored as q + 2^(SB-1), the interpolation gives D + 2^(SB-1) * 2^(3 WB) (its
  // weights sum to 2^(3 WB)), at most 2^IW in magnitude, so exact.
  const uint32_t* quads = nullptr;
  double nx1 = 0;
  double biased_threshold = 0;  // threshold + bias
  double bias = 0;              // 2^(SB-1) * 2^(3 WB)
};

// Points [0, n) of coordinates x, y, z (the shell's words): per point hit[k] = 1 when it is inside and its
// interpolated distance is at most the threshold, else 0; for hits its cell (cx, cy, cz) and distance (dist, an
// exact integer). Returns the hits. Every value is an integer below 2^53 (the caller checks the widths), so the
// doubles are exact and the result is ref/'s.
using DistanceBlockFn = uint32_t (*)(const int32_t* x, const int32_t* y, const int32_t* z, size_t n,
                                     const DistanceJob& job, uint8_t* hit, int32_t* cx, int32_t* cy, int32_t* cz,
                                     double* dist);

// The kernels FastRunner takes (2-bit and distance) are the widest this processor runs, or, where the environment
// variable VOXCD_KERNEL names a narrower one ("avx2", "baseline"), that one: tests run every kernel the machine has
// through the same paths. Empty when unset.
std::string kernel_override();
// Whether this processor has the AVX-512 subsets the kernels use (F, DQ, VL, BW).
bool cpu_has_avx512();
// The widest kernel family to take: what the processor runs, narrowed by VOXCD_KERNEL.
enum class KernelWidth { Avx512, Avx2, Baseline };
KernelWidth widest_kernel();

// The kernel for this processor: AVX-512, AVX2 with FMA, or the baseline; and its name.
DistanceBlockFn distance_block();
const char* distance_block_name();
// The same on the node-quad copy (job.quads; ref/fast/distance_quad_kernel.cpp): one 8-byte read a point.
DistanceBlockFn distance_quad_block();
const char* distance_quad_block_name();

}  // namespace voxcd::detail
