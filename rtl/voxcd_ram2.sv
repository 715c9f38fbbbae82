// voxcd_ram2: one write port and two synchronous read ports, each with its own read enable (a true dual-port
// block RAM whose port A also writes).
//
// Contract: a write of wdata_i to waddr_i takes effect at the clock edge where we_i is high. When re_a_i (re_b_i) is
// high at a clock edge, rdata_a_o (rdata_b_o) shows mem[raddr_a_i] (mem[raddr_b_i]) from the next cycle on and holds
// it while the enable is low (each read port's output register has a clock enable, so a stalled pipeline keeps its
// data). Latency: 1 cycle on either port. Port A is the write port too: in a cycle with a write it does not read (its
// output holds, a block RAM port's NO_CHANGE mode; the device writes its memories only while it is idle, when it uses
// no word it reads), so the cell maps onto one true dual-port block RAM (port A: write, else read; port B: read) with
// no more storage than voxcd_ram. Reading an address in the cycle it is written is not used.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_ram2 #(
  parameter int unsigned Width = 8,
  parameter int unsigned AddrW = 4
) (
  input  logic             clk_i,
  input  logic             we_i,
  input  logic [AddrW-1:0] waddr_i,
  input  logic [Width-1:0] wdata_i,
  input  logic             re_a_i,
  input  logic [AddrW-1:0] raddr_a_i,
  output logic [Width-1:0] rdata_a_o,
  input  logic             re_b_i,
  input  logic [AddrW-1:0] raddr_b_i,
  output logic [Width-1:0] rdata_b_o
);

  logic [Width-1:0] mem_q [2**AddrW];

  // Port A: one address, a write or else a read (a block RAM port in NO_CHANGE mode).
  logic [AddrW-1:0] addr_a;
  assign addr_a = we_i ? waddr_i : raddr_a_i;
  always_ff @(posedge clk_i) begin
    if (we_i)        mem_q[addr_a] <= wdata_i;
    else if (re_a_i) rdata_a_o <= mem_q[addr_a];
  end

  always_ff @(posedge clk_i) begin
    if (re_b_i) rdata_b_o <= mem_q[raddr_b_i];
  end

  `VOXCD_ASSERT_INIT(WidthAtLeastOne, Width >= 1)
  `VOXCD_ASSERT_INIT(AddrAtLeastOne, AddrW >= 1)

endmodule
