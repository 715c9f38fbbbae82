// voxcd_params.svh: the device's parameter list, written once (after lowRISC's prim_assert.sv: a guarded include).
//
// A lane takes the widths it computes with (VOXCD_LANE_PARAMS); the device and its AXI top take the whole list
// (VOXCD_DEVICE_PARAMS); the _MAP macros pass a module's own values down to the module it instantiates. They stay
// module parameters, so `-G NAME=` (Verilator) and `chparam -set NAME` (yosys) set them by name; their defaults are
// voxcd_arch_pkg's. rtl/voxcd.f lists this file before the modules, so every tool that reads the list defines the
// macros once; a module read on its own includes it (`ifndef VOXCD_PARAMS_SVH around the include: with the list
// read first, no include path is needed).
`ifndef VOXCD_PARAMS_SVH
`define VOXCD_PARAMS_SVH

`define VOXCD_LANE_PARAMS \
  parameter int unsigned PW    = voxcd_arch_pkg::PW, \
  parameter int unsigned PF    = voxcd_arch_pkg::PF, \
  parameter int unsigned MW    = voxcd_arch_pkg::MW, \
  parameter int unsigned MF    = voxcd_arch_pkg::MF, \
  parameter int unsigned TW    = voxcd_arch_pkg::TW, \
  parameter int unsigned DW    = voxcd_arch_pkg::DW, \
  parameter int unsigned MEMW  = voxcd_arch_pkg::MEMW, \
  parameter int unsigned MAW   = voxcd_arch_pkg::MAW, \
  parameter int unsigned SB    = voxcd_arch_pkg::SB, \
  parameter int unsigned WB    = voxcd_arch_pkg::WB, \
  parameter int unsigned Depth = voxcd_arch_pkg::Depth, \
  parameter int unsigned BL    = voxcd_arch_pkg::BL, \
  parameter int unsigned TX    = voxcd_arch_pkg::TX
// BANKS 0: a voxmap copy per lane; B: one voxmap in B shared banks. Depth: register stages added to every lane. BL:
// a sparse device's coarse cells (0: a dense device). TX: the lanes' transform (1: brick lanes, no lane multiplies).
`define VOXCD_DEVICE_PARAMS \
  `VOXCD_LANE_PARAMS, \
  parameter int unsigned LANES = voxcd_arch_pkg::LANES, \
  parameter int unsigned SAW   = voxcd_arch_pkg::SAW, \
  parameter int unsigned TAGW  = voxcd_arch_pkg::TAGW, \
  parameter int unsigned BANKS = voxcd_arch_pkg::BANKS
`define VOXCD_LANE_PARAM_MAP \
  .PW(PW), .PF(PF), .MW(MW), .MF(MF), .TW(TW), .DW(DW), .MEMW(MEMW), .MAW(MAW), .SB(SB), .WB(WB), .Depth(Depth), \
  .BL(BL), .TX(TX)
`define VOXCD_DEVICE_PARAM_MAP \
  `VOXCD_LANE_PARAM_MAP, .LANES(LANES), .SAW(SAW), .TAGW(TAGW), .BANKS(BANKS)

`endif  // VOXCD_PARAMS_SVH
