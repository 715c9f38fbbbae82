// voxcd_axi_jobs: the AXI top's job receiver and checker (voxcd_axi; docs/hardware.md, "The AXI top").
//
// Takes job descriptors from an AXI4-Stream slave, JobDw bits a beat (1024 / JobDw beats, the lowest bytes first,
// TLAST on the last), into the descriptor register; a frame whose TLAST is not on its last beat is dropped. A whole
// descriptor moves into the checked register, checked as the reference checks a job (ref/pipeline.h, job_faults;
// the rules of voxcd_axi's header) against the shell and voxmap words loaded (shell_words_i, map_words_i); from
// there a valid one leaves into the device (job_valid_o and the job's fields in the device's widths), a refused
// one as its error record (err_emit_i, from voxcd_axi_records, which takes faults_o and tag_o). TREADY stays low
// until run_i. dropped_o counts the refused descriptors and the frames dropped. Latency: a descriptor is in the
// checked register the cycle after its last beat is taken (when the register is free).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_axi_jobs #(
  parameter int unsigned MW    = voxcd_arch_pkg::MW,
  parameter int unsigned TW    = voxcd_arch_pkg::TW,
  parameter int unsigned DW    = voxcd_arch_pkg::DW,
  parameter int unsigned MEMW  = voxcd_arch_pkg::MEMW,
  parameter int unsigned SAW   = voxcd_arch_pkg::SAW,
  parameter int unsigned MAW   = voxcd_arch_pkg::MAW,
  parameter int unsigned TAGW  = voxcd_arch_pkg::TAGW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
  parameter int unsigned WB    = voxcd_arch_pkg::WB,
  parameter int unsigned BL    = voxcd_arch_pkg::BL,
  parameter int unsigned JobDw = 64      // job stream TDATA bits: a power of two, 8 .. 1024
) (
  input  logic                  clk_i,
  input  logic                  rst_ni,
  // The register file: RUN has been written (the stream opens), and the words loaded in each memory
  input  logic                  run_i,
  input  logic [63:0]           shell_words_i,
  input  logic [63:0]           map_words_i,
  // AXI4-Stream slave: job descriptors
  input  logic                  s_axis_job_tvalid_i,
  output logic                  s_axis_job_tready_o,
  input  logic [JobDw-1:0]      s_axis_job_tdata_i,
  input  logic                  s_axis_job_tlast_i,
  // The checked descriptor: a valid one's job into the device (M {m22, ..., m00} and t {t2, t1, t0} MW and TW bits
  // an entry), its tag as sent, the rules a refused one breaks; its error record leaves (err_emit_i)
  output logic                  job_valid_o,
  input  logic                  job_ready_i,
  output logic [31:0]           tag_o,
  output logic [1:0]            mode_o,
  output logic [3:0]            mask_o,
  output logic [SAW-1:0]        shell_base_o,
  output logic [SAW:0]          shell_count_o,
  output logic [MAW-1:0]        map_base_o,
  output logic [DW:0]           nx_o,
  output logic [DW:0]           ny_o,
  output logic [DW:0]           nz_o,
  output logic [9*MW-1:0]       m_o,
  output logic [3*TW-1:0]       t_o,
  output logic [SB+3*WB-1:0]    thr_o,
  output logic [1:0]            sparse_o,
  output logic [MAW-1:0]        brick_base_o,
  output logic [MAW:0]          brick_units_o,
  output logic                  checked_o,    // the checked register holds a descriptor
  output logic [7:0]            faults_o,
  input  logic                  err_emit_i,
  // For STATUS, STAGED and DROPPED: a descriptor received, a frame being received, the count dropped
  output logic                  desc_full_o,
  output logic                  receiving_o,
  output logic [63:0]           dropped_o
);

  localparam int unsigned IW       = SB + 3 * WB;
  localparam int unsigned JobBytes = 128;
  localparam int unsigned JobBeats = 8 * JobBytes / JobDw;
  localparam int unsigned JobBW    = JobBeats > 1 ? $clog2(JobBeats) : 1;
  // The rules a refused descriptor breaks (the error record's faults; ref/pipeline.h and ref/address_map.h).
  localparam int unsigned FaultW = 8;
  localparam int unsigned FaultReserved = 0, FaultMode = 1, FaultTag = 2, FaultShell = 3, FaultDims = 4,
                          FaultMap = 5, FaultPose = 6, FaultThreshold = 7;

  // The descriptor register and its fields (byte offsets of ref/address_map.h).
  logic [8*JobBytes-1:0] desc_q;
  logic                  desc_full_q;
  logic [31:0]           d_tag, d_shell_base, d_shell_count, d_map_base, d_nx, d_ny, d_nz;
  logic [7:0]            d_mode, d_mask;
  logic [31:0]           d_m [9];
  logic [63:0]           d_t [3];
  logic [63:0]           d_thr;
  logic [7:0]            d_sparse;
  logic [31:0]           d_brick_units, d_brick_base;
  logic [FaultW-1:0]     d_faults;  // the rules the descriptor in desc_q breaks

  always_comb begin
    d_tag         = desc_q[8*32'h00 +: 32];
    d_mode        = desc_q[8*32'h04 +: 8];
    d_mask        = desc_q[8*32'h05 +: 8];
    d_shell_base  = desc_q[8*32'h08 +: 32];
    d_shell_count = desc_q[8*32'h0c +: 32];
    d_map_base    = desc_q[8*32'h10 +: 32];
    d_nx          = desc_q[8*32'h14 +: 32];
    d_ny          = desc_q[8*32'h18 +: 32];
    d_nz          = desc_q[8*32'h1c +: 32];
    for (int i = 0; i < 9; i++) d_m[i] = desc_q[8*(32'h20 + 4*i) +: 32];
    for (int i = 0; i < 3; i++) d_t[i] = desc_q[8*(32'h48 + 8*i) +: 64];
    d_thr         = desc_q[8*32'h60 +: 64];
    d_sparse      = desc_q[8*32'h06 +: 8];
    d_brick_units = desc_q[8*32'h44 +: 32];
    d_brick_base  = desc_q[8*32'h68 +: 32];
  end

  // Whether v, read as signed, fits `w` (1..64) bits signed: the bits from w-1 up all equal.
  function automatic logic fits_signed64(input logic [63:0] v, input int unsigned w);
    logic [63:0] upper;
    upper         = $signed(v) >>> (w - 1);
    fits_signed64 = upper == '0 || upper == '1;
  endfunction

  // The voxmap words a map of the descriptor's dimensions takes (ref/pipeline.h, map_words), for dimensions in
  // 1..2^DW: ceil(nx*ny*nz / (MEMW/2)) voxel states, or 8 * ceil(Hx*Hy*Hz / (MEMW/SB)) node values in 8 banks.
  localparam int unsigned VoxW  = 3 * (DW + 1);
  localparam int unsigned PerLg = SB > 2 ? $clog2(MEMW / SB) : $clog2(MEMW / 2);  // values per word, log2
  logic [DW:0]     d_ex, d_ey, d_ez;  // the extents the map's words count: n_i, or H_i = (n_i >> 1) + 1
  logic [VoxW-1:0] d_values;
  logic [63:0]     d_map_words;
  assign d_ex        = SB > 2 ? (DW + 1)'(d_nx >> 1) + (DW + 1)'(1) : (DW + 1)'(d_nx);
  assign d_ey        = SB > 2 ? (DW + 1)'(d_ny >> 1) + (DW + 1)'(1) : (DW + 1)'(d_ny);
  assign d_ez        = SB > 2 ? (DW + 1)'(d_nz >> 1) + (DW + 1)'(1) : (DW + 1)'(d_nz);
  assign d_values    = VoxW'(d_ex) * VoxW'(d_ey) * VoxW'(d_ez);
  assign d_map_words = (64'(d_values) + 64'((1 << PerLg) - 1)) >> PerLg << (SB > 2 ? 3 : 0);

  // A sparse map's words (ref/sparse.h): its table, ceil(Cx*Cy*Cz / CPW) words from map_base (C_i = ceil(n_i / 2^BL),
  // CPW = MEMW / 4 codes a word on a 2-bit device, MEMW / 8 on a distance one), and its bricks, brick_units * UW words
  // from brick_base (UW: a 2-bit brick's 2^(3BL+1) / MEMW words, or a distance brick's of level 0, 8 ceil(H_0^3 /
  // NPW), H_0 = 2^(BL-1) + 1).
  localparam int unsigned BLW    = BL > 0 ? BL : 1;
  localparam int unsigned CpwLg  = $clog2(MEMW / (SB > 2 ? 8 : 4));
  localparam logic [63:0] H0     = (64'd1 << (BLW - 1)) + 64'd1;
  localparam logic [63:0] NPW    = SB > 2 ? 64'(MEMW) / 64'(SB) : 64'd1;
  localparam logic [63:0] UnitW  = BL == 0 ? 64'd1 : SB > 2 ? 64'd8 * ((H0 * H0 * H0 + NPW - 64'd1) / NPW)
                                                            : (64'd2 << (3 * BLW)) / 64'(MEMW);
  logic [DW:0]     d_cx, d_cy, d_cz;
  logic [VoxW-1:0] d_cells;
  logic [63:0]     d_table_words, d_bricks_end;
  assign d_cx          = (DW + 1)'((d_nx + 32'((1 << BLW) - 1)) >> BLW);
  assign d_cy          = (DW + 1)'((d_ny + 32'((1 << BLW) - 1)) >> BLW);
  assign d_cz          = (DW + 1)'((d_nz + 32'((1 << BLW) - 1)) >> BLW);
  assign d_cells       = VoxW'(d_cx) * VoxW'(d_cy) * VoxW'(d_cz);
  assign d_table_words = (64'(d_cells) + 64'((1 << CpwLg) - 1)) >> CpwLg;
  assign d_bricks_end  = 64'(d_brick_base) + 64'(d_brick_units) * UnitW;

  always_comb begin
    logic dims_ok;
    dims_ok  = d_nx != '0 && d_ny != '0 && d_nz != '0 &&
               d_nx <= (32'd1 << DW) && d_ny <= (32'd1 << DW) && d_nz <= (32'd1 << DW);
    d_faults = '0;
    d_faults[FaultReserved] = d_sparse[7:2] != '0 || desc_q[8*32'h07 +: 8] != '0 ||
                              desc_q[8*JobBytes-1 : 8*32'h6c] != '0;
    d_faults[FaultMode]  = d_mode > 8'd2 || d_mask > 8'd15 || d_sparse > 8'd3;
    d_faults[FaultTag]   = TAGW < 32 && (d_tag >> TAGW) != '0;
    d_faults[FaultShell] = (d_shell_base >> SAW) != '0 || 64'(d_shell_base) + 64'(d_shell_count) > shell_words_i ||
                           (BL == 0 && d_sparse[1]);
    d_faults[FaultDims]  = !dims_ok;
    d_faults[FaultMap]   = (d_map_base >> MAW) != '0 || (SB > 2 && d_map_base[2:0] != 3'd0) ||
                           (dims_ok && 64'(d_map_base) + (d_sparse[0] ? d_table_words : d_map_words) > map_words_i);
    // A sparse map's bricks (any sparse map on a dense device), or a dense map's brick fields.
    if (d_sparse[0]) begin
      d_faults[FaultMap] = d_faults[FaultMap] || BL == 0 || (d_brick_base >> MAW) != '0 ||
                           (SB > 2 && d_brick_base[2:0] != 3'd0) || d_bricks_end > map_words_i;
    end else begin
      d_faults[FaultMap] = d_faults[FaultMap] || d_brick_base != '0 || d_brick_units != '0;
    end
    for (int i = 0; i < 9; i++) d_faults[FaultPose] = d_faults[FaultPose] || !fits_signed64(64'($signed(d_m[i])), MW);
    for (int i = 0; i < 3; i++) d_faults[FaultPose] = d_faults[FaultPose] || !fits_signed64(d_t[i], TW);
    d_faults[FaultThreshold] = SB > 2 ? !fits_signed64(d_thr, IW) : d_thr != '0;
  end

  // ---- The checked descriptor: its job in the device's widths, its tag as sent and its faults ----
  // A descriptor moves here from desc_q when this register is free or leaving; it leaves into the device (no
  // fault), or as an error record once the device is idle (every earlier job's records have left it) and the
  // record register takes a record.
  logic              chk_full_q;
  logic [FaultW-1:0] chk_faults_q;
  logic [31:0]       chk_tag_q;
  logic [1:0]        chk_mode_q;
  logic [3:0]        chk_mask_q;
  logic [SAW-1:0]    chk_shell_base_q;
  logic [SAW:0]      chk_shell_count_q;
  logic [MAW-1:0]    chk_map_base_q;
  logic [DW:0]       chk_nx_q, chk_ny_q, chk_nz_q;
  logic [MW-1:0]     chk_m_q [9];
  logic [TW-1:0]     chk_t_q [3];
  logic [IW-1:0]     chk_thr_q;
  logic [1:0]        chk_sparse_q;
  logic [MAW-1:0]    chk_brick_base_q;
  logic [MAW:0]      chk_brick_units_q;
  logic              chk_leave;  // the checked descriptor leaves (into the device, or as its error record)
  logic              desc_leave; // the descriptor register empties into the checked one

  assign job_valid_o = chk_full_q && chk_faults_q == '0;
  assign chk_leave = chk_full_q && (job_valid_o ? job_ready_i : err_emit_i);
  assign desc_leave = desc_full_q && (!chk_full_q || chk_leave);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      chk_full_q <= 1'b0;
    end else if (desc_leave) begin
      chk_full_q <= 1'b1;
    end else if (chk_leave) begin
      chk_full_q <= 1'b0;
    end
  end
  // Fields: read only while full, no reset.
  always_ff @(posedge clk_i) begin
    if (desc_leave) begin
      chk_faults_q      <= d_faults;
      chk_tag_q         <= d_tag;
      chk_mode_q        <= d_mode[1:0];
      chk_mask_q        <= d_mask[3:0];
      chk_shell_base_q  <= SAW'(d_shell_base);
      chk_shell_count_q <= (SAW + 1)'(d_shell_count);
      chk_map_base_q    <= MAW'(d_map_base);
      chk_nx_q          <= (DW + 1)'(d_nx);
      chk_ny_q          <= (DW + 1)'(d_ny);
      chk_nz_q          <= (DW + 1)'(d_nz);
      for (int i = 0; i < 9; i++) chk_m_q[i] <= MW'(d_m[i]);
      for (int i = 0; i < 3; i++) chk_t_q[i] <= TW'(d_t[i]);
      chk_thr_q         <= IW'(d_thr);
      chk_sparse_q      <= d_sparse[1:0];
      chk_brick_base_q  <= MAW'(d_brick_base);
      chk_brick_units_q <= (MAW + 1)'(d_brick_units);
    end
  end

  // ---- Job stream: beats into the descriptor register ----
  logic [JobBW-1:0] jbeat_q;     // beat of the descriptor being received
  logic             jlong_q;     // it has had more than JobBeats beats
  logic             jtake;
  logic [63:0]      dropped_q;

  assign s_axis_job_tready_o = run_i && (!desc_full_q || desc_leave);
  assign jtake               = s_axis_job_tvalid_i && s_axis_job_tready_o;
  // A TLAST that does not end exactly JobBeats beats: the descriptor is dropped.
  logic jframe_bad;
  assign jframe_bad = jtake && s_axis_job_tlast_i && (jlong_q || 32'(jbeat_q) != JobBeats - 1);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      desc_full_q <= 1'b0;
      jbeat_q     <= '0;
      jlong_q     <= 1'b0;
      dropped_q   <= '0;
    end else begin
      if (desc_leave) desc_full_q <= 1'b0;
      dropped_q <= dropped_q + 64'(err_emit_i) + 64'(jframe_bad);
      if (jtake) begin
        if (s_axis_job_tlast_i) begin
          jbeat_q <= '0;
          jlong_q <= 1'b0;
          if (!jframe_bad) desc_full_q <= 1'b1;
        end else if (32'(jbeat_q) == JobBeats - 1) begin
          jlong_q <= 1'b1;
        end else begin
          jbeat_q <= jbeat_q + 1'b1;
        end
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (jtake && !jlong_q) desc_q[32'(jbeat_q) * JobDw +: JobDw] <= s_axis_job_tdata_i;
  end

  assign tag_o         = chk_tag_q;
  assign mode_o        = chk_mode_q;
  assign mask_o        = chk_mask_q;
  assign shell_base_o  = chk_shell_base_q;
  assign shell_count_o = chk_shell_count_q;
  assign map_base_o    = chk_map_base_q;
  assign nx_o          = chk_nx_q;
  assign ny_o          = chk_ny_q;
  assign nz_o          = chk_nz_q;
  for (genvar i = 0; i < 9; i++) begin : g_m
    assign m_o[i*MW +: MW] = chk_m_q[i];
  end
  for (genvar i = 0; i < 3; i++) begin : g_t
    assign t_o[i*TW +: TW] = chk_t_q[i];
  end
  assign thr_o         = chk_thr_q;
  assign sparse_o      = chk_sparse_q;
  assign brick_base_o  = chk_brick_base_q;
  assign brick_units_o = chk_brick_units_q;
  assign checked_o     = chk_full_q;
  assign faults_o      = chk_faults_q;
  assign desc_full_o   = desc_full_q;
  assign receiving_o   = jbeat_q != '0 || jlong_q;
  assign dropped_o     = dropped_q;

`ifndef SYNTHESIS
  // ---- Parameter sanity, at elaboration ----
  `VOXCD_ASSERT_INIT(JobBeatWidthKnown, (JobDw & (JobDw - 1)) == 0 && JobDw >= 8 && JobDw <= 8 * JobBytes)

  // ---- AXI4-Stream rules: what the master driving the job stream promises ----
  `VOXCD_ASSERT(JobStable, s_axis_job_tvalid_i && !s_axis_job_tready_o |=>
                           s_axis_job_tvalid_i && $stable(s_axis_job_tdata_i) && $stable(s_axis_job_tlast_i))
  // Inside: the device sees a job only when it is valid, and the job stream stays closed until RUN.
  `VOXCD_ASSERT(JobValidDescriptor, !job_valid_o || (chk_mode_q <= 2'd2 && chk_nx_q != '0 && chk_ny_q != '0 &&
                                                   chk_nz_q != '0))
  `VOXCD_ASSERT(JobClosedBeforeRun, run_i || !s_axis_job_tready_o)
`endif

  // Functional coverage (docs/verification.md): a refused descriptor breaking each rule, a job frame of the wrong
  // length.
  `VOXCD_COVER(CoverFaultReserved, err_emit_i && chk_faults_q[FaultReserved])
  `VOXCD_COVER(CoverFaultMode, err_emit_i && chk_faults_q[FaultMode])
  `VOXCD_COVER(CoverFaultTag, err_emit_i && chk_faults_q[FaultTag])
  `VOXCD_COVER(CoverFaultShell, err_emit_i && chk_faults_q[FaultShell])
  `VOXCD_COVER(CoverFaultDims, err_emit_i && chk_faults_q[FaultDims])
  `VOXCD_COVER(CoverFaultMap, err_emit_i && chk_faults_q[FaultMap])
  `VOXCD_COVER(CoverFaultPose, err_emit_i && chk_faults_q[FaultPose])
  `VOXCD_COVER(CoverFaultThreshold, err_emit_i && chk_faults_q[FaultThreshold])
  `VOXCD_COVER(CoverJobFrameOfTheWrongLength, jframe_bad)

endmodule
