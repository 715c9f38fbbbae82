// voxcd_axi_records: the AXI top's record sender (voxcd_axi; docs/hardware.md, "The AXI top").
//
// Takes the device's hit and completion records (taking them with take_o, the device's hit and done ready) and a
// refused descriptor's error record {kind 3, tag, faults} once the device is idle (err_emit_o: every earlier job's
// records have left it), one at a time into the record register, in the byte layout of ref/address_map.h (32 bytes,
// little-endian), and sends it on an AXI4-Stream master, RecDw bits a beat (256 / RecDw beats, the lowest bytes
// first, TLAST on the last). It totals the completion records it takes (the registers JOBS_DONE, HITS, POINTS,
// CYCLES, STALLS). Latency: a record is on the stream the cycle after it is taken.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_axi_records #(
  parameter int unsigned DW    = voxcd_arch_pkg::DW,
  parameter int unsigned SAW   = voxcd_arch_pkg::SAW,
  parameter int unsigned TAGW  = voxcd_arch_pkg::TAGW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
  parameter int unsigned WB    = voxcd_arch_pkg::WB,
  parameter int unsigned BL    = voxcd_arch_pkg::BL,
  parameter int unsigned RecDw = 64      // record stream TDATA bits: a power of two, 8 .. 256
) (
  input  logic                                clk_i,
  input  logic                                rst_ni,
  // The device's records (voxcd_device's hit and completion streams; take_o is their ready) and whether it is busy
  input  logic                                dev_busy_i,
  output logic                                take_o,
  input  logic                                hit_valid_i,
  input  logic [TAGW-1:0]                     hit_tag_i,
  input  logic [(BL > 0 ? SAW + 6 : SAW)-1:0] hit_point_i,
  input  logic [DW-1:0]                       hit_x_i,
  input  logic [DW-1:0]                       hit_y_i,
  input  logic [DW-1:0]                       hit_z_i,
  input  logic [1:0]                          hit_state_i,
  input  logic [SB+3*WB-1:0]                  hit_dist_i,
  input  logic                                done_valid_i,
  input  logic [TAGW-1:0]                     done_tag_i,
  input  logic [(BL > 0 ? SAW + 6 : SAW):0]   done_hits_i,
  input  logic [(BL > 0 ? SAW + 6 : SAW):0]   done_points_i,
  input  logic [voxcd_arch_pkg::CW-1:0]       done_cycles_i,
  input  logic [voxcd_arch_pkg::CW-1:0]       done_stalls_i,
  // The checked descriptor (voxcd_axi_jobs): held, its faults (a refused one: not 0) and its tag as sent; its error
  // record enters the record register (err_emit_o)
  input  logic                                checked_i,
  input  logic [7:0]                          faults_i,
  input  logic [31:0]                         tag_i,
  output logic                                err_emit_o,
  // AXI4-Stream master: result records
  output logic                                m_axis_rec_tvalid_o,
  input  logic                                m_axis_rec_tready_i,
  output logic [RecDw-1:0]                    m_axis_rec_tdata_o,
  output logic                                m_axis_rec_tlast_o,
  // A record waits in the register (STATUS, RESULT_COUNT), and the completion records' totals
  output logic                                rec_valid_o,
  output logic [63:0]                         jobs_done_o,
  output logic [63:0]                         hits_o,
  output logic [63:0]                         points_o,
  output logic [63:0]                         cycles_o,
  output logic [63:0]                         stalls_o
);

  localparam int unsigned RecBytes = 32;
  localparam int unsigned RecBeats = 8 * RecBytes / RecDw;
  localparam int unsigned RecBW    = RecBeats > 1 ? $clog2(RecBeats) : 1;

  logic err_emit;  // the checked descriptor's error record enters the record register
  logic rec_take;  // the record register takes a record this cycle

  // ---- Record stream: one record register, sent beat by beat ----
  logic [8*RecBytes-1:0] rec_q, rec_d;
  logic                  rec_valid_q;
  logic [RecBW-1:0]      rbeat_q;
  logic                  rlast;
  logic [63:0]           jobs_done_q, hits_q, points_q, cycles_q, stalls_q;

  assign rlast    = 32'(rbeat_q) == RecBeats - 1;
  assign rec_take = !rec_valid_q || (m_axis_rec_tready_i && rlast);
  // The device is idle (busy_o low) only when it holds no job and no record: the error record follows the
  // records of every job before it.
  assign err_emit = checked_i && faults_i != '0 && !dev_busy_i && rec_take;

  always_comb begin
    rec_d = '0;
    if (err_emit) begin
      rec_d[8*32'h00 +: 8]  = 8'd3;
      rec_d[8*32'h04 +: 32] = tag_i;
      rec_d[8*32'h08 +: 32] = 32'(faults_i);
    end else if (done_valid_i) begin
      rec_d[8*32'h00 +: 8]  = 8'd2;
      rec_d[8*32'h04 +: 32] = 32'(done_tag_i);
      rec_d[8*32'h08 +: 32] = 32'(done_hits_i);
      rec_d[8*32'h0c +: 32] = 32'(done_points_i);
      rec_d[8*32'h10 +: 64] = 64'(done_cycles_i);
      rec_d[8*32'h18 +: 64] = 64'(done_stalls_i);
    end else begin
      rec_d[8*32'h00 +: 8]  = 8'd1;
      rec_d[8*32'h01 +: 8]  = 8'(hit_state_i);
      rec_d[8*32'h04 +: 32] = 32'(hit_tag_i);
      rec_d[8*32'h08 +: 32] = 32'(hit_point_i);
      rec_d[8*32'h0c +: 32] = 32'(hit_x_i);
      rec_d[8*32'h10 +: 32] = 32'(hit_y_i);
      rec_d[8*32'h14 +: 32] = 32'(hit_z_i);
      rec_d[8*32'h18 +: 64] = SB > 2 ? 64'($signed(hit_dist_i)) : 64'd0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rec_valid_q <= 1'b0;
      rbeat_q     <= '0;
      jobs_done_q <= '0;
      hits_q      <= '0;
      points_q    <= '0;
      cycles_q    <= '0;
      stalls_q    <= '0;
    end else begin
      if (m_axis_rec_tvalid_o && m_axis_rec_tready_i) rbeat_q <= rlast ? '0 : rbeat_q + 1'b1;
      if (rec_take) rec_valid_q <= hit_valid_i || done_valid_i || err_emit;
      if (rec_take && done_valid_i) begin
        jobs_done_q <= jobs_done_q + 64'd1;
        hits_q      <= hits_q + 64'(done_hits_i);
        points_q    <= points_q + 64'(done_points_i);
        cycles_q    <= cycles_q + 64'(done_cycles_i);
        stalls_q    <= stalls_q + 64'(done_stalls_i);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (rec_take && (hit_valid_i || done_valid_i || err_emit)) rec_q <= rec_d;
  end

  assign m_axis_rec_tvalid_o = rec_valid_q;
  assign m_axis_rec_tdata_o  = rec_q[32'(rbeat_q) * RecDw +: RecDw];
  assign m_axis_rec_tlast_o  = rlast;

  assign take_o      = rec_take;
  assign err_emit_o  = err_emit;
  assign rec_valid_o = rec_valid_q;
  assign jobs_done_o = jobs_done_q;
  assign hits_o      = hits_q;
  assign points_o    = points_q;
  assign cycles_o    = cycles_q;
  assign stalls_o    = stalls_q;

`ifndef SYNTHESIS
  // ---- Parameter sanity, at elaboration ----
  `VOXCD_ASSERT_INIT(RecordBeatWidthKnown, (RecDw & (RecDw - 1)) == 0 && RecDw >= 8 && RecDw <= 8 * RecBytes)

  // ---- AXI4-Stream rules: a record beat, once valid, stays valid and unchanged until it is taken ----
  `VOXCD_ASSERT(RecStable, m_axis_rec_tvalid_o && !m_axis_rec_tready_i |=>
                           m_axis_rec_tvalid_o && $stable(m_axis_rec_tdata_o) && $stable(m_axis_rec_tlast_o))
  // Inside: the record register is only loaded when it is free.
  `VOXCD_ASSERT(RecNoOverwrite, !(rec_valid_q && !(m_axis_rec_tready_i && rlast) && rec_take))
  // An error record waits for the device to be idle, and leaves only into a free record register.
  `VOXCD_ASSERT(ErrorAfterEarlierRecords, !err_emit || (!dev_busy_i && !hit_valid_i && !done_valid_i))
`endif

endmodule
