// voxcd_shell_expand: the next slot of a shell brick word (docs/contract.md, "Shell bricks"): the lowest LANES set
// bits of what is left of its 64-bit mask, lane i taking the i-th, lowest first.
//
// Contract (combinational): lanes_o has a bit for each lane that takes a point (the lowest min(LANES, set bits of
// rem_i) lanes); lane i's point is bit bit_o[6*i +: 6] of the mask, whose offset in the 4 x 4 x 4 shell brick is
// (b & 3, (b >> 2) & 3, b >> 4); rem_o is rem_i without the bits taken, so a word whose rem_o is 0 has no later slot.
// Latency: 0 (a prefix count of the mask, then a one-hot match per lane).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_shell_expand #(
  parameter int unsigned LANES = 4
) (
  input  logic [63:0]        rem_i,
  output logic [LANES-1:0]   lanes_o,
  output logic [6*LANES-1:0] bit_o,
  output logic [63:0]        rem_o
);

  // rank[b]: the set bits of rem_i below bit b (a prefix count); bit b goes to lane rank[b] when that is below LANES.
  logic [7*64-1:0] rank;
  always_comb begin
    logic [6:0] count;
    count = '0;
    for (int b = 0; b < 64; b++) begin
      rank[7*b +: 7] = count;
      count          = count + 7'(rem_i[b]);
    end
  end
  for (genvar b = 0; b < 64; b++) begin : g_left
    assign rem_o[b] = rem_i[b] && 32'(rank[7*b +: 7]) >= LANES;
  end
  // Lane l: the one-hot match of its rank among the set bits, and that bit's index.
  for (genvar l = 0; l < LANES; l++) begin : g_lane
    logic [63:0] sel;
    logic [5:0]  index;
    always_comb begin
      index = '0;
      for (int b = 0; b < 64; b++) begin
        sel[b] = rem_i[b] && rank[7*b +: 7] == 7'(l);
        if (sel[b]) index = index | 6'(b);
      end
    end
    assign bit_o[6*l +: 6] = index;
    assign lanes_o[l]      = |sel;
  end

  `VOXCD_ASSERT_INIT(LanesInRange, LANES >= 1 && LANES <= 64)

endmodule
