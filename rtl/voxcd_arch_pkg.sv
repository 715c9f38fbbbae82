// voxcd_arch_pkg: the device's default widths, counter width, pipeline depths and enums.
//
// Every width is also a module parameter of the same name (voxcd_device, voxcd_axi), defaulting to the value
// here, so one RTL source builds any configuration; the parameter lists are written once, as the macros of
// voxcd_params.svh, which every top, wrapper and lane declares and passes on. The file's name sorts before every module's,
// so a tool that reads rtl/*.sv in name order declares the package before its first use (rtl.lint_glob). The names
// and defaults are those of the C++ DeviceConfig (ref/config.h); tests/rtl/test_pkg.cpp parses this file and fails
// when the two disagree.
package voxcd_arch_pkg;

  // ---- Widths (DeviceConfig) ----
  // Defaults of the module parameters of the same names: a build that overrides one leaves it unread (voxcd.vlt).
  localparam int unsigned PW    = 24;  // shell point coordinate width, signed
  localparam int unsigned PF    = 8;   // shell point fraction bits
  localparam int unsigned MW    = 18;  // matrix entry width, signed
  localparam int unsigned MF    = 16;  // matrix fraction bits
  localparam int unsigned TW    = 48;  // translation width, signed, TF = MF + PF fraction bits
  localparam int unsigned DW    = 10;  // map dimensions 1 .. 2^DW per axis
  localparam int unsigned MEMW  = 64;  // voxmap memory word: MEMW/2 voxel states
  localparam int unsigned LANES = 4;   // parallel lookup lanes (a power of two)
  localparam int unsigned SAW   = 16;  // shell memory depth 2^SAW points
  localparam int unsigned MAW   = 18;  // voxmap memory depth 2^MAW words
  localparam int unsigned TAGW  = 16;  // job tag width, unsigned
  localparam int unsigned SB    = 2;   // voxmap value width: 2 = voxel states; 4, 8, 16 = signed node distances
  localparam int unsigned WB    = 8;   // interpolation weight bits (distance voxmaps)
  localparam int unsigned BANKS = 0;   // 0: a voxmap copy per lane; B: one voxmap in B shared banks (2-bit devices)
  localparam int unsigned Depth = 0;   // register stages added to every lane, 0 .. MaxDepth (DeviceConfig::depth)
  localparam int unsigned BL    = 0;   // 0: dense maps and shells only; 2..4: a sparse device (cells of 2^BL voxels)
  localparam int unsigned TX    = 0;   // 0: lanes that multiply; 1: brick lanes (sparse devices; docs/contract.md)

  // ---- Counters in completion records ----
  localparam int unsigned CW = 32;  // cycles and stall counters

  // ---- Pipeline ----
  // Slots in flight between the issue stage and the hit-test stage (registers R0 .. R5); ref/timing.h has the
  // same number as kPipelineSlots, and the cycle model is exact only while they agree.
  localparam int unsigned PipeSlots = 6;
  // A distance device (SB > 2) has three more (R6 node select and x interpolation, R7 y, R8 z): ref/timing.h's
  // kDistanceSlots.
  localparam int unsigned DistSlots = 3;
  // A sparse device (BL > 0) has three more (the shell word register W before R0; the entry E and the brick word K
  // after R5), a sparse distance device four (the rows F between E and K): ref/timing.h's kSparseSlots and
  // kSparseDistanceSlots.
  localparam int unsigned SparseSlots     = 3;
  localparam int unsigned SparseDistSlots = 4;
  // Depth adds one slot register per unit, each a register stage in every lane (voxcd_lane), so a device has
  // PipeSlots + Depth (+ DistSlots) slot registers. The stages in the order Depth adds them (a stage of rank r is
  // there when Depth > r); MaxDepth, the deepest pipeline, has all of them (ref/config.h: kMaxDepth):
  //   RankIn    registered multiplier inputs (the point after the shell banks' rotation, and M): DSP input registers
  //   RankAddr  the linear index x + nx*(y + ny*z) (or a distance map's half-index) before the word address
  //   RankRead  the voxmap word's state (a distance map's 8 node values) selected into a register before the hit test
  //   RankSum   a level of the transform's sum tree: (M0*p0 + t) and (M1*p1 + M2*p2) before their sum
  //   RankFloor the floor and bounds test before the (y + ny*z) product
  localparam int unsigned MaxDepth  = 5;
  localparam int unsigned RankIn    = 0;
  localparam int unsigned RankAddr  = 1;
  localparam int unsigned RankRead  = 2;
  localparam int unsigned RankSum   = 3;
  localparam int unsigned RankFloor = 4;

  typedef enum logic [1:0] {
    ModeAll   = 2'd0,
    ModeFirst = 2'd1,
    ModeCount = 2'd2
  } mode_e;

  typedef enum logic [1:0] {
    StateEmpty    = 2'd0,
    StateSurface  = 2'd1,
    StateInterior = 2'd2,
    StateReserved = 2'd3
  } state_e;

endpackage
