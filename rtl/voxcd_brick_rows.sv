// voxcd_brick_rows: where a point's sub-cell lies in its distance brick (docs/contract.md, "Distance bricks and
// levels"; ref/pipeline.h, sub_cell and brick_node_address): the rows of its 8 corner nodes, one in each parity bank,
// and its weights.
//
// Contract (combinational): a_i = (fine_i, frac_i) is the point's position in its cell on axis i, fine_i = index_i %
// 2^BL voxels and frac_i the top WB + 3 fraction bits of its coordinate. At level level_i the sub-cell is X_i = a_i >>
// (TF - l) and its weight f_i = (a_i >> (TF - l - WB)) & (2^WB - 1) (weight_o, {fz, fy, fx}). The brick's nodes lie
// as a dense distance map's of H = 2^(BL-1+l) + 1 half-grid positions per axis from word first_i (a multiple of 8):
// bank p (parities p of the node) holds the cell's corner node of its parity at half-index h_p = (X>>1) + d_x +
// H ((Y>>1) + d_y + H ((Z>>1) + d_z)), d = the sub-cell's parities & ~p, in row first_i / 8 + h_p / NPW (row_o, RowW
// bits a bank) and slot h_p % NPW (slot_o); par_o = the sub-cell's parities {Z, Y, X} & 1. The products by H are a
// shift and an add. Latency: 0.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_brick_rows #(
  parameter int unsigned MEMW = 64,
  parameter int unsigned MAW  = 18,
  parameter int unsigned SB   = 8,
  parameter int unsigned WB   = 8,
  parameter int unsigned BL   = 3,
  // Derived (leave them at their defaults): a row of one parity bank, a node slot in a word.
  parameter int unsigned RowW = MAW > 3 ? MAW - 3 : 1,
  parameter int unsigned NslW = (MEMW / SB) > 1 ? $clog2(MEMW / SB) : 1
) (
  input  logic [3*BL-1:0]       fine_i,    // {z, y, x}
  input  logic [3*(WB+3)-1:0]   frac_i,    // {z, y, x}
  input  logic [1:0]            level_i,
  input  logic [MAW-1:0]        first_i,
  output logic [8*RowW-1:0]     row_o,
  output logic [8*NslW-1:0]     slot_o,
  output logic [2:0]            par_o,
  output logic [3*WB-1:0]       weight_o
);

  localparam int unsigned NPW   = MEMW / SB;
  localparam int unsigned NpwLg = $clog2(NPW);
  localparam int unsigned FxW   = WB + 3;
  localparam int unsigned AW    = BL + FxW;       // a_i
  localparam int unsigned XW    = BL + 3;         // X_i < 2^(BL+3), H <= 2^(BL+2) + 1
  localparam int unsigned HW    = 3 * XW + 1;     // a half-index h < H^3

  // v * H at level l: (v << (BL - 1 + l)) + v.
  function automatic logic [HW-1:0] times_h(input logic [HW-1:0] v, input logic [1:0] l);
    times_h = (v << (BL - 1 + 32'(l))) + v;
  endfunction

  logic [3*XW-1:0] x;   // X_i, i = 0, 1, 2
  logic [HW-1:0]   h_yz, h_base, h_step_y, h_step_z;
  always_comb begin
    for (int i = 0; i < 3; i++) begin
      logic [AW-1:0] a;
      a = {fine_i[BL*i +: BL], frac_i[FxW*i +: FxW]};
      x[XW*i +: XW]        = XW'(a >> (FxW - 32'(level_i)));
      weight_o[WB*i +: WB] = WB'(a >> (3 - 32'(level_i)));
    end
    h_yz     = (HW'(x[XW*1 +: XW]) >> 1) + times_h(HW'(x[XW*2 +: XW]) >> 1, level_i);
    h_base   = (HW'(x[XW*0 +: XW]) >> 1) + times_h(h_yz, level_i);
    h_step_y = times_h(HW'(1), level_i);      // H
    h_step_z = times_h(h_step_y, level_i);    // H^2
    par_o    = {x[XW*2], x[XW*1], x[XW*0]};
    for (int p = 0; p < 8; p++) begin
      logic [2:0]    d;
      logic [HW-1:0] h;
      d = par_o & ~3'(p);
      h = h_base + HW'(d[0]) + (d[1] ? h_step_y : '0) + (d[2] ? h_step_z : '0);
      // A valid job's brick lies in loaded words, so the RowW-bit sum is exact.
      row_o[p*RowW +: RowW]  = RowW'(first_i >> 3) + RowW'(64'(h) >> NpwLg);
      slot_o[p*NslW +: NslW] = NslW'(h & HW'(NPW - 1));  // 0 when a word holds one node
    end
  end

  logic unused_first;  // a brick starts on a bank boundary
  assign unused_first = ^first_i[2:0];

  `VOXCD_ASSERT_INIT(BrickLevelsKnown, BL >= 2 && BL <= 4 && SB > 2)

endmodule
