// voxcd_shell_expand: the next slot of a shell brick word (docs/contract.md, "Shell bricks"): the lowest LANES set
// bits of what is left of its 64-bit mask, lane i taking the i-th, lowest first.
//
// Contract (combinational): lanes_o has a bit for each lane that takes a point (the lowest min(LANES, set bits of
// rem_i) lanes); lane i's point is bit bit_o[6*i +: 6] of the mask, whose offset in the 4 x 4 x 4 shell brick is
// (b & 3, (b >> 2) & 3, b >> 4); rem_o is rem_i without the bits taken, so a word whose rem_o is 0 has no later slot.
// Latency: 0 (a prefix count of the mask, then a match per lane).
module voxcd_shell_expand #(
  parameter int unsigned LANES = 4
) (
  input  logic [63:0]        rem_i,
  output logic [LANES-1:0]   lanes_o,
  output logic [6*LANES-1:0] bit_o,
  output logic [63:0]        rem_o
);

  // rank[b]: the set bits of rem_i below bit b (0..63); bit b goes to lane rank[b] when that is below LANES.
  always_comb begin
    logic [6:0] rank;
    lanes_o = '0;
    bit_o   = '0;
    rem_o   = rem_i;
    rank    = '0;
    for (int b = 0; b < 64; b++) begin
      if (rem_i[b] && 32'(rank) < LANES) begin
        lanes_o[32'(rank)]         = 1'b1;
        bit_o[6*32'(rank) +: 6]    = 6'(b);
        rem_o[b]                   = 1'b0;
      end
      rank = rank + 7'(rem_i[b]);
    end
  end

  `VOXCD_ASSERT_INIT(LanesInRange, LANES >= 1 && LANES <= 64)

endmodule
