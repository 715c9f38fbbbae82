// Formal harness of voxcd_fifo: a scoreboard of two counters. The producer offers beat number `sent_q` (valid
// whenever the free input `offer_i` says so), the consumer takes when the free input `take_i` says so, and every
// beat that leaves must be number `received_q`: no beat lost, duplicated or reordered. The free inputs make the
// proof cover every producer and consumer; Width = 4 bits of beat number are more than the Depth beats in flight.
module voxcd_fifo_check #(
  parameter int unsigned Depth = 3,
  parameter int unsigned Width = 4
) (
  input logic clk_i,
  input logic offer_i,  // the producer offers its next beat
  input logic take_i    // the consumer is ready
);
  logic rst_ni;
  assign rst_ni = 1'b1;  // the initial state (all registers zero, `sat -set-init-zero`) is the reset state

  logic             ready, valid;
  logic [Width-1:0] data, sent_q, received_q, held;

  voxcd_fifo #(.Depth(Depth), .Width(Width)) u_fifo (
    .clk_i, .rst_ni, .valid_i(offer_i), .ready_o(ready), .data_i(sent_q),
    .valid_o(valid), .ready_i(take_i), .data_o(data)
  );

  always_ff @(posedge clk_i) begin
    if (offer_i && ready) sent_q <= sent_q + 1'b1;
    if (valid && take_i)  received_q <= received_q + 1'b1;
  end
  assign held = sent_q - received_q;

  `VOXCD_ASSERT(InOrderOnce, !valid || data == received_q)
  `VOXCD_ASSERT(NeverMoreThanDepth, held <= Width'(Depth))
  `VOXCD_ASSERT(ValidIffHeld, valid == (held != '0))
  `VOXCD_ASSERT(ReadyIffNotFull, ready == (held != Width'(Depth)))
  `VOXCD_ASSERT(DataHeldWhileStalled, !$past(valid && !take_i) || (valid && data == $past(data)))
endmodule
