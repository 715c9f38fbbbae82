// voxcd_fifo: a first-in first-out queue of Depth entries of Width bits, valid/ready on both sides.
//
// Contract: a beat enters when valid_i and ready_o are high at a clock edge and leaves when valid_o and ready_i
// are; beats leave in the order they entered, each exactly once. ready_o is high while fewer than Depth beats are
// held and valid_o while at least one is: both are functions of the registers only (no path from valid_i to
// valid_o or from ready_i to ready_o), and a full queue takes no beat even in a cycle where one leaves.
// data_o shows the oldest beat while valid_o is high and holds it until it leaves.
// Latency: 1 cycle (a beat that enters at an edge is on data_o after it; no fall-through).
//
// Properties (the VOXCD_ASSERTs below; tests/formal/voxcd_fifo_check.sv proves them and the scoreboard's):
// the count never exceeds Depth, and the pointers agree with the count.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_fifo #(
  parameter int unsigned Depth = 2,  // entries, at least 1
  parameter int unsigned Width = 8   // bits per entry
) (
  input  logic             clk_i,
  input  logic             rst_ni,   // asynchronous, active low: empties the queue
  // Producer side.
  input  logic             valid_i,  // data_i holds a beat
  output logic             ready_o,  // the queue takes a beat at this edge (not full)
  input  logic [Width-1:0] data_i,   // the beat
  // Consumer side.
  output logic             valid_o,  // data_o holds the oldest beat (not empty)
  input  logic             ready_i,  // the consumer takes data_o at this edge
  output logic [Width-1:0] data_o    // the oldest beat
);

  localparam int unsigned PtrW   = Depth > 1 ? $clog2(Depth) : 1;
  localparam int unsigned CountW = $clog2(Depth + 1);

  logic [Width-1:0]  mem_q [Depth];
  logic [PtrW-1:0]   read_ptr_d, read_ptr_q;    // the oldest entry
  logic [PtrW-1:0]   write_ptr_d, write_ptr_q;  // the next free entry
  logic [CountW-1:0] count_d, count_q;          // entries held
  logic              push, pop;

  assign ready_o = count_q != CountW'(Depth);
  assign valid_o = count_q != '0;
  assign data_o  = mem_q[read_ptr_q];
  assign push    = valid_i && ready_o;
  assign pop     = valid_o && ready_i;

  // Pointers step modulo Depth (any Depth, not only powers of two).
  always_comb begin
    read_ptr_d = read_ptr_q;
    if (pop) read_ptr_d = (read_ptr_q == PtrW'(Depth - 1)) ? '0 : read_ptr_q + 1'b1;
    write_ptr_d = write_ptr_q;
    if (push) write_ptr_d = (write_ptr_q == PtrW'(Depth - 1)) ? '0 : write_ptr_q + 1'b1;
    count_d     = count_q + CountW'(push) - CountW'(pop);
  end

  `VOXCD_FF(read_ptr_q, read_ptr_d, '0)
  `VOXCD_FF(write_ptr_q, write_ptr_d, '0)
  `VOXCD_FF(count_q, count_d, '0)

  // Storage has no reset: an entry is read only after it was written.
  always_ff @(posedge clk_i) begin
    if (push) mem_q[write_ptr_q] <= data_i;
  end

  `VOXCD_ASSERT_INIT(DepthAtLeastOne, Depth >= 1)
  `VOXCD_ASSERT_INIT(WidthAtLeastOne, Width >= 1)
  `VOXCD_ASSERT(CountAtMostDepth, count_q <= CountW'(Depth))
  `VOXCD_ASSERT(PointersAgreeWithCount,
                CountW'((32'(write_ptr_q) + Depth - 32'(read_ptr_q)) % Depth) == count_q % CountW'(Depth))
  `VOXCD_ASSERT(PointersInRange, 32'(read_ptr_q) < Depth && 32'(write_ptr_q) < Depth)

  // Functional coverage: the queue full, and a beat in and one out in the same cycle.
  `VOXCD_COVER(CoverFull, count_q == CountW'(Depth))
  `VOXCD_COVER(CoverPushAndPop, push && pop)

endmodule
