// voxcd_ram: one write port, one synchronous read port with a read enable (a block RAM).
//
// Contract: a write of wdata_i to waddr_i takes effect at the clock edge where we_i is high. When re_i is high at
// a clock edge, rdata_o shows mem[raddr_i] from the next cycle on and holds it while re_i is low (the RAM output
// register has a clock enable, so a stalled pipeline keeps its data). Latency: 1 cycle. Reading an address in the
// cycle it is written is not used by the device (memories are loaded before jobs run).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_ram #(
  parameter int unsigned Width = 8,
  parameter int unsigned AddrW = 4
) (
  input  logic             clk_i,
  input  logic             we_i,
  input  logic [AddrW-1:0] waddr_i,
  input  logic [Width-1:0] wdata_i,
  input  logic             re_i,
  input  logic [AddrW-1:0] raddr_i,
  output logic [Width-1:0] rdata_o
);

  logic [Width-1:0] mem_q [2**AddrW];

  always_ff @(posedge clk_i) begin
    if (we_i) mem_q[waddr_i] <= wdata_i;
  end

  always_ff @(posedge clk_i) begin
    if (re_i) rdata_o <= mem_q[raddr_i];
  end

  `VOXCD_ASSERT_INIT(WidthAtLeastOne, Width >= 1)
  `VOXCD_ASSERT_INIT(AddrAtLeastOne, AddrW >= 1)

endmodule
