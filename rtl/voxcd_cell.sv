// voxcd_cell: a sparse map's table word read as the coarse cell of one point (docs/contract.md, "The table";
// ref/pipeline.h, read_cell).
//
// Contract (combinational): word_i is the table word, slot_i the cell's code slot in it (CPW = MEMW / (2 CW) codes
// of CW bits, CW = 2 on a 2-bit device, 4 on a distance one; the word's rank in its top MEMW/2 bits). The cell's
// brick starts at unit u = rank + the units of the cells before it in the word (a 2-bit brick: one unit; a distance
// brick of level l: U_l) and word first_o = brick_base + u * UW. brick_o: the code is a brick's and it lies within
// the job's brick_units (u + its units <= brick_units, at full width); else the cell is uniform: on a 2-bit device
// its state is state_o (the code, or 0 for a brick past the job's units); on a distance device every node is qmin
// when deep_o (code 1), else qmax (code 0, codes 6..15, a brick past the units). level_o: a distance brick's level
// (0 on a 2-bit device). Latency: 0.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_cell #(
  parameter int unsigned MEMW = 64,
  parameter int unsigned MAW  = 18,
  parameter int unsigned SB   = 2,
  parameter int unsigned BL   = 3,
  // Derived (leave them at their defaults): the bits of a code slot.
  parameter int unsigned CPW   = MEMW / (SB > 2 ? 8 : 4),
  parameter int unsigned SlotW = CPW > 1 ? $clog2(CPW) : 1
) (
  input  logic [MEMW-1:0]  word_i,
  input  logic [SlotW-1:0] slot_i,
  input  logic [MAW-1:0]   brick_base_i,
  input  logic [MAW:0]     brick_units_i,
  output logic             brick_o,
  output logic [1:0]       level_o,
  output logic [1:0]       state_o,
  output logic             deep_o,
  output logic [MAW-1:0]   first_o
);

  localparam int unsigned CW   = SB > 2 ? 4 : 2;
  localparam int unsigned Half = MEMW / 2;  // the rank's bits
  localparam int unsigned NPW  = SB > 2 ? MEMW / SB : 1;
  // A distance brick of level l: H_l = 2^(BL-1+l) + 1 half-grid positions per axis, W_l = 8 ceil(H_l^3 / NPW) words,
  // U_l = ceil(W_l / W_0) units of UW = W_0 words; a 2-bit brick is one unit of 2 B^3 / MEMW words (ref/sparse.h).
  localparam logic [63:0] H0 = (64'd1 << (BL - 1)) + 64'd1, H1 = (64'd1 << BL) + 64'd1,
                          H2 = (64'd1 << (BL + 1)) + 64'd1, H3 = (64'd1 << (BL + 2)) + 64'd1;
  localparam logic [63:0] W0 = 64'd8 * ((H0 * H0 * H0 + 64'(NPW) - 64'd1) / 64'(NPW)),
                          W1 = 64'd8 * ((H1 * H1 * H1 + 64'(NPW) - 64'd1) / 64'(NPW)),
                          W2 = 64'd8 * ((H2 * H2 * H2 + 64'(NPW) - 64'd1) / 64'(NPW)),
                          W3 = 64'd8 * ((H3 * H3 * H3 + 64'(NPW) - 64'd1) / 64'(NPW));
  localparam logic [63:0] U1 = (W1 + W0 - 64'd1) / W0, U2 = (W2 + W0 - 64'd1) / W0, U3 = (W3 + W0 - 64'd1) / W0;
  localparam logic [63:0] UW = SB > 2 ? W0 : (64'd2 << (3 * BL)) / 64'(MEMW);
  localparam int unsigned SumW  = 16;                // the units of the cells before one: at most CPW * U_3 < 2^16
  localparam int unsigned UnitW = Half + SumW + 1;   // u and u + the cell's units, exact
  localparam int unsigned CmpW  = UnitW > MAW + 1 ? UnitW : MAW + 1;

  // The units of a code (0 for a uniform one and the codes read as uniform).
  function automatic logic [SumW-1:0] units_of(input logic [CW-1:0] code);
    logic [3:0] c;
    c = 4'(code);
    if (SB == 2)        units_of = SumW'(c == 4'd3);
    else if (c == 4'd2) units_of = SumW'(1);
    else if (c == 4'd3) units_of = SumW'(U1);
    else if (c == 4'd4) units_of = SumW'(U2);
    else if (c == 4'd5) units_of = SumW'(U3);
    else                units_of = '0;
  endfunction

  logic [CW-1:0]    code;
  logic [SumW-1:0]  units_before;
  logic [UnitW-1:0] u, end_unit;
  logic             brick_code;
  always_comb begin
    code   = word_i[CW * 32'(slot_i) +: CW];
    units_before = '0;
    for (int j = 0; j < CPW; j++) begin  // the cell's own code and those after it count 0
      if (SlotW'(j) < slot_i) units_before = units_before + units_of(word_i[CW*j +: CW]);
    end
    u          = UnitW'(word_i[MEMW-1 -: Half]) + UnitW'(units_before);
    end_unit   = u + UnitW'(units_of(code));
    brick_code = units_of(code) != '0;
    brick_o    = brick_code && CmpW'(end_unit) <= CmpW'(brick_units_i);
    level_o    = SB > 2 && brick_code ? 2'(code - CW'(2)) : 2'd0;
    state_o    = brick_code ? 2'd0 : 2'(code);
    deep_o     = SB > 2 && code == CW'(1);
    first_o    = brick_base_i + MAW'(MAW'(u) * MAW'(UW));
  end

  `VOXCD_ASSERT_INIT(TableWordHoldsACode, MEMW >= 2 * CW && CPW == MEMW / (2 * CW))
  `VOXCD_ASSERT_INIT(BrickLevelsKnown, BL >= 2 && BL <= 4)

endmodule
