// Formal harness of voxcd_skid: the scoreboard of tests/formal/voxcd_fifo_check.sv (beats numbered by a counter,
// free producer and consumer), plus the slice's own promises: ready is a function of the registers (it equals
// "fewer than two beats held", which the scoreboard counts, whatever the inputs do), it is never low while the
// output register is free, and with a consumer that was ready the slice passes a beat through in one cycle.
module voxcd_skid_check #(
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

  voxcd_skid #(.Width(Width)) u_skid (
    .clk_i, .rst_ni, .valid_i(offer_i), .ready_o(ready), .data_i(sent_q),
    .valid_o(valid), .ready_i(take_i), .data_o(data)
  );

  always_ff @(posedge clk_i) begin
    if (offer_i && ready) sent_q <= sent_q + 1'b1;
    if (valid && take_i)  received_q <= received_q + 1'b1;
  end
  assign held = sent_q - received_q;

  `VOXCD_ASSERT(InOrderOnce, !valid || data == received_q)
  `VOXCD_ASSERT(NeverMoreThanTwo, held <= Width'(2))
  `VOXCD_ASSERT(ValidIffHeld, valid == (held != '0))
  `VOXCD_ASSERT(ReadyIsRegistered, ready == (held < Width'(2)))
  `VOXCD_ASSERT(DataHeldWhileStalled, !$past(valid && !take_i) || (valid && data == $past(data)))
  // Pass-through: a beat taken while the output register was free (empty, or emptied at that edge) is on the
  // output one cycle later.
  `VOXCD_ASSERT(NoAddedLatency, !$past(offer_i && ready && (!valid || take_i)) || (valid && data == $past(sent_q)))
endmodule
