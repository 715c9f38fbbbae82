// DeviceConfig: every width of the device, with the names and defaults of rtl/voxcd_arch_pkg.sv.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "voxcd/ref/error.h"

namespace voxcd {

// The deepest pipeline (voxcd_arch_pkg::MaxDepth): DeviceConfig::depth runs from 0 (the datapath of the paper's
// device: transform, floor, bounds and address between five slot registers) to kMaxDepth, where every lane also has
// registered multiplier inputs, a sum tree level, the floor and bounds before the index product, the linear index
// before the word address, and the selected state (node values) before the hit test (docs/hardware.md).
constexpr int kMaxDepth = 5;
// The stages in the order depth adds them (voxcd_arch_pkg's Rank*): the stage of rank r is there when depth > r.
constexpr int kRankIn = 0;     // the multipliers' input registers (the point after the shell banks, and M)
constexpr int kRankAddr = 1;   // the linear index (a distance map's half-index) before the word address
constexpr int kRankRead = 2;   // the selected state (a distance map's 8 node values) before the hit test
constexpr int kRankSum = 3;    // a level of the transform's sum tree
constexpr int kRankFloor = 4;  // the floor and bounds before the index product

struct DeviceConfig {
  int PW = 24;    // shell point coordinate width (signed)
  int PF = 8;     // shell point fraction bits (units: the shell object's own voxel size)
  int MW = 18;    // rotation-scale matrix entry width (signed)
  int MF = 16;    // matrix fraction bits
  int TW = 48;    // translation width (signed), TF = MF + PF fraction bits
  int DW = 10;    // map dimensions are 1 .. 2^DW per axis
  int MEMW = 64;  // voxmap memory word width: MEMW/2 voxel states per word
  int LANES = 4;  // parallel lookup lanes (timing only, never results)
  int SAW = 16;   // shell memory holds 2^SAW points
  int MAW = 18;   // voxmap memory holds 2^MAW words
  int TAGW = 16;  // job tag width (unsigned)
  int SB = 2;     // voxmap value width: 2 = voxel states; 4, 8, 16 = a signed distance per grid node
  int WB = 8;     // interpolation weight bits (distance voxmaps): the top WB fraction bits per coordinate
  int BANKS = 0;  // 0: every lane its own copy of the voxmap; B: the lanes share one voxmap in B banks (word w in
                  // bank w % B; on a distance device each of the 8 parity banks in B, word w in bank w % 8B), with
                  // bank conflicts resolved by the device (timing only, never results)
  int depth = 0;  // register stages added to every lane, 0 .. kMaxDepth (the RTL's Depth; timing only, never
                  // results): each adds one slot register, so one cycle of latency and of a FIRST job's squash
  int BL = 0;     // 0: dense maps and point shells only; 2..4: a sparse device, which also takes sparse maps (a table
                  // of cells of 2^BL voxels per axis, uniform or a brick) and sparse shells (shell bricks of 4^3
                  // points); docs/contract.md, "Sparse voxmaps and shells". More slot registers, never other results
  int TX = 0;     // the lanes' transform: 0, each lane multiplies (M p + t, nine products a lane); 1 (a sparse device
                  // only), brick lanes: no lane multiplies, each adds shifted columns of M for its point's offset in
                  // its shell brick to the slot's base M o + t, which one transform unit of the device computes; a
                  // dense-shell slot then holds one point (docs/contract.md, "Brick lanes"). Timing only

  int TF() const { return MF + PF; }
  int states_per_word() const { return MEMW / 2; }
  // A distance device (SB > 2) holds signed node distances in 8 parity banks (docs/contract.md).
  bool distance() const { return SB > 2; }
  int nodes_per_word() const { return MEMW / SB; }
  // The lanes share one voxmap memory in BANKS banks (docs/contract.md, "Shared voxmap banks").
  bool banked() const { return BANKS > 0; }
  // A sparse device (BL > 0) takes sparse maps and shells besides dense ones (ref/sparse.h).
  bool sparse() const { return BL > 0; }
  // Brick lanes (TX 1): the lanes add shifted matrix columns; one transform unit multiplies (docs/contract.md).
  bool brick_lanes() const { return TX == 1; }
  // Points in one slot of a dense-shell job: LANES, or one on brick lanes (the device's one transform unit).
  int dense_slot_points() const { return brick_lanes() ? 1 : LANES; }
  // Voxmap copies the device holds: LANES, or one when banked.
  int voxmap_copies() const { return banked() ? 1 : LANES; }
  // Width of an interpolated distance, a job's threshold and a hit record's distance: SB + 3*WB.
  int IW() const { return SB + 3 * WB; }
  uint64_t shell_depth() const { return uint64_t{1} << SAW; }
  uint64_t map_depth() const { return uint64_t{1} << MAW; }
  uint64_t max_dim() const { return uint64_t{1} << DW; }
  uint64_t max_tag() const { return (uint64_t{1} << TAGW) - 1; }
  // Width of the exact accumulator sum_j M[i][j]*p[j] + t[i]: it cannot overflow.
  int acc_width() const;
  // Width of a voxel index after the floor: acc_width() - TF().
  int index_width() const { return acc_width() - TF(); }

  // Throws ConfigError naming the parameter and the rule it breaks.
  void validate() const;
  // "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 16 MAW 18 TAGW 16", then "SB 8 WB 8" on a
  // distance device, "BANKS B" on a banked one, "DEPTH D" on a deeper pipeline and "BL B" on a sparse one (a 2-bit
  // device's text is the paper device's, unchanged).
  std::string to_string() const;
  // Same widths (BL among them: it decides which jobs a device takes); LANES, BANKS, depth and TX may differ (they
  // change timing, never results).
  bool same_widths(const DeviceConfig& o) const;
  bool operator==(const DeviceConfig& o) const {
    return same_widths(o) && LANES == o.LANES && BANKS == o.BANKS && depth == o.depth && TX == o.TX;
  }
  bool operator!=(const DeviceConfig& o) const { return !(*this == o); }
};

}  // namespace voxcd
