// Formal harness of voxcd_shell_expand: for every 64-bit mask (a free input), the slot it gives is the lowest
// min(LANES, set bits) of the mask's set bits, lane i taking the i-th lowest: the lanes that take a point are the
// lowest ones; each lane's bit is a set bit of the mask, in ascending order lane by lane (so no bit twice); the bits
// that leave the mask are exactly the lanes' bits, every one of them below every bit left; and bits are left only
// when every lane took one.
module voxcd_shell_expand_check #(
  parameter int unsigned LANES = 2  // the proof's lanes: seconds at 2, minutes at 8 (the cell is one generate for all)
) (
  input logic        clk_i,
  input logic [63:0] rem_i  // the mask left of a word
);
  logic rst_ni;
  assign rst_ni = 1'b1;

  logic [LANES-1:0]   lanes;
  logic [6*LANES-1:0] bits;
  logic [63:0]        rem, taken, lane_bits;
  voxcd_shell_expand #(.LANES(LANES)) u_expand (.rem_i, .lanes_o(lanes), .bit_o(bits), .rem_o(rem));

  logic ascending;
  always_comb begin
    taken     = rem_i & ~rem;
    lane_bits = '0;
    ascending = 1'b1;
    for (int l = 0; l < LANES; l++) begin
      if (lanes[l]) lane_bits = lane_bits | (64'd1 << bits[6*l +: 6]);
      if (l + 1 < LANES && lanes[l + 1]) ascending = ascending && bits[6*l +: 6] < bits[6*(l+1) +: 6];
    end
  end

  `VOXCD_ASSERT(OnlyMaskBitsLeft, (rem & ~rem_i) == '0)
  `VOXCD_ASSERT(TakesTheLowestLanes, (lanes & (lanes + 1'b1)) == '0)
  `VOXCD_ASSERT(LanesTakeTheBitsThatLeave, lane_bits == taken && ascending)
  `VOXCD_ASSERT(TakenBelowLeft, rem == '0 || (taken & ~((rem & (~rem + 64'd1)) - 64'd1)) == '0)
  `VOXCD_ASSERT(BitsLeftOnlyWhenEveryLaneTook, rem == '0 || (&lanes))
endmodule
