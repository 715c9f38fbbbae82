// voxcd_stage: a pipeline register that a parameter can leave out (the lanes' optional stages, voxcd_lane).
//
// Contract: with Enable, q_o shows d_i as it was at the last clock edge where en_i was high (no reset: the
// pipeline reads a stage's data only where its slot is valid); without Enable, q_o is d_i. Latency: 1 cycle with
// Enable, 0 without.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_stage #(
  parameter int unsigned Width  = 1,
  parameter bit          Enable = 1'b1
) (
  input  logic             clk_i,
  input  logic             en_i,
  input  logic [Width-1:0] d_i,
  output logic [Width-1:0] q_o
);

  if (Enable) begin : g_reg
    always_ff @(posedge clk_i) begin
      if (en_i) q_o <= d_i;
    end
  end else begin : g_wire
    assign q_o = d_i;
    logic unused_clock;  // a left-out stage registers nothing
    assign unused_clock = clk_i ^ en_i;
  end

  `VOXCD_ASSERT_INIT(WidthAtLeastOne, Width >= 1)

endmodule
