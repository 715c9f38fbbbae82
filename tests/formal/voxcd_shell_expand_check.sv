// Formal harness of voxcd_shell_expand: for every 64-bit mask (a free input), the slot it gives is the lowest
// min(LANES, set bits) of the mask's set bits, lane i taking the i-th lowest: the lanes that take a point are the
// lowest ones, as many as the bits taken; every taken bit lies below every bit left; each lane's bit is a taken bit,
// in ascending order lane by lane; nothing but the taken bits leaves the mask.
module voxcd_shell_expand_check #(
  parameter int unsigned LANES = 8
) (
  input logic        clk_i,
  input logic [63:0] rem_i  // the mask left of a word
);
  logic rst_ni;
  assign rst_ni = 1'b1;

  logic [LANES-1:0]   lanes;
  logic [6*LANES-1:0] bits;
  logic [63:0]        rem, taken;
  voxcd_shell_expand #(.LANES(LANES)) u_expand (.rem_i, .lanes_o(lanes), .bit_o(bits), .rem_o(rem));

  function automatic logic [7:0] ones64(input logic [63:0] v);
    ones64 = '0;
    for (int b = 0; b < 64; b++) ones64 = ones64 + 8'(v[b]);
  endfunction

  logic [7:0] want;  // min(LANES, set bits of the mask)
  logic       ascending, lane_bits_taken;
  always_comb begin
    taken = rem_i & ~rem;
    want  = ones64(rem_i) < 8'(LANES) ? ones64(rem_i) : 8'(LANES);
    ascending       = 1'b1;
    lane_bits_taken = 1'b1;
    for (int l = 0; l < LANES; l++) begin
      if (lanes[l]) lane_bits_taken = lane_bits_taken && taken[bits[6*l +: 6]];
      if (l + 1 < LANES && lanes[l + 1]) ascending = ascending && bits[6*l +: 6] < bits[6*(l+1) +: 6];
    end
  end

  `VOXCD_ASSERT(OnlyTakenBitsLeave, (rem & ~rem_i) == '0)
  `VOXCD_ASSERT(TakesTheLowestLanes, (lanes & (lanes + 1'b1)) == '0)
  `VOXCD_ASSERT(TakesMinOfLanesAndBits, 8'(ones64(64'(lanes))) == want && ones64(taken) == want)
  `VOXCD_ASSERT(TakenBelowLeft, rem == '0 || (taken & ~((rem & (~rem + 64'd1)) - 64'd1)) == '0)
  `VOXCD_ASSERT(LaneIBitIsTheIthTaken, lane_bits_taken && ascending)
endmodule
