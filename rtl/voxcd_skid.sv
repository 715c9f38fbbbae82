// voxcd_skid: a register slice for a valid/ready stream, with a skid register (a two-entry elastic buffer).
//
// Contract: a beat enters when valid_i and ready_o are high at a clock edge and leaves when valid_o and ready_i
// are; beats leave in order, each exactly once, and data_o holds while valid_o is high and ready_i low.
// Both directions are cut: valid_o and data_o come from the output register and ready_o from the skid register's
// valid bit, so there is no combinational path from any input to any output. ready_o is high unless the skid
// register holds a beat, which happens only when a beat entered in a cycle where the output register was held.
// Latency: 1 cycle (a beat that enters at an edge is on data_o after it when the output register is free, as a
// plain pipeline register would have it): with a consumer that is always ready, the slice behaves as one register
// and never lowers ready_o.
//
// Properties (the VOXCD_ASSERTs below; tests/formal/voxcd_skid_check.sv proves them and the scoreboard's).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_skid #(
  parameter int unsigned Width = 8  // bits per beat
) (
  input  logic             clk_i,
  input  logic             rst_ni,   // asynchronous, active low: empties the slice
  // Producer side.
  input  logic             valid_i,  // data_i holds a beat
  output logic             ready_o,  // the slice takes a beat at this edge; a register's output
  input  logic [Width-1:0] data_i,   // the beat
  // Consumer side.
  output logic             valid_o,  // data_o holds the oldest beat; a register's output
  input  logic             ready_i,  // the consumer takes data_o at this edge
  output logic [Width-1:0] data_o    // the oldest beat; a register's output
);

  logic             out_valid_d, out_valid_q;    // the output register
  logic [Width-1:0] out_data_d, out_data_q;
  logic             skid_valid_d, skid_valid_q;  // the skid register: a beat taken while the output was held
  logic [Width-1:0] skid_data_d, skid_data_q;
  logic             take, out_free;

  assign ready_o  = !skid_valid_q;
  assign valid_o  = out_valid_q;
  assign data_o   = out_data_q;
  assign take     = valid_i && ready_o;
  assign out_free = !out_valid_q || ready_i;  // the output register may load at this edge

  always_comb begin
    out_valid_d  = out_valid_q;
    out_data_d   = out_data_q;
    skid_valid_d = skid_valid_q;
    skid_data_d  = skid_data_q;
    if (out_free) begin
      if (skid_valid_q) begin
        // The skid beat is older than anything offered now (ready_o is low, so nothing is taken).
        out_valid_d  = 1'b1;
        out_data_d   = skid_data_q;
        skid_valid_d = 1'b0;
      end else begin
        out_valid_d = take;
        if (take) out_data_d = data_i;
      end
    end else if (take) begin
      skid_valid_d = 1'b1;
      skid_data_d  = data_i;
    end
  end

  `VOXCD_FF(out_valid_q, out_valid_d, 1'b0)
  `VOXCD_FF(skid_valid_q, skid_valid_d, 1'b0)

  // Data registers have no reset: they are read only while their valid bit is set.
  always_ff @(posedge clk_i) begin
    out_data_q  <= out_data_d;
    skid_data_q <= skid_data_d;
  end

  `VOXCD_ASSERT_INIT(WidthAtLeastOne, Width >= 1)
  `VOXCD_ASSERT(SkidOnlyBehindOutput, !skid_valid_q || out_valid_q)
  `VOXCD_ASSERT(OutputHeldWhileStalled,
                !$past(out_valid_q && !ready_i) || (out_valid_q && out_data_q == $past(out_data_q)))

  // Functional coverage: a beat held in the skid register.
  `VOXCD_COVER(CoverSkidHolds, skid_valid_q)

endmodule
