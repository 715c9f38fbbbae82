// voxcd_axi: voxcd_device behind standard interfaces: an AXI4-Lite slave for registers and memory writes, an
// AXI4-Stream slave for job descriptors and an AXI4-Stream master for result records (docs/hardware.md,
// "The AXI top").
//
// Contract: the register offsets, memory windows and byte layouts are those of the SystemC address map
// (ref/address_map.h): a descriptor is its 128 bytes and a record its 32 bytes, little-endian, spread over
// 1024 / JobDw and 256 / RecDw beats, the lowest bytes in the first beat, TLAST on the last. The device's stream
// contract is unchanged: records leave in the contract's stream order, a completion's cycles are the device's.
//
// AXI4-Lite (AxilDw = 32 or 64 data bits, 32 address bits, one outstanding read and one outstanding write):
//   registers at 0x0000 .. 0x0fff: 64-bit registers (with AxilDw = 32: the low half at the register's offset, the
//     high half at offset + 4). Reads of RUN: SLVERR; writes of any register but RUN: SLVERR; offsets with no
//     register: DECERR. Writing RUN (any value) opens the job stream: TREADY stays low from reset until then.
//   shell memory at 0x1000_0000 + 16 k: word k is {x, y, z, 0} as four little-endian 32-bit values; the write of
//     bytes 8..11 (z) commits the word with the x and y written before it for the same k.
//   voxmap memory at 0x2000_0000 + 8 k: word k, 64 bits; the write of bytes 4..7 (the whole word with AxilDw = 64)
//     commits it.
//   SLVERR for a memory write while a job is in the device or waits to enter it, a value that does not fit
//     (PW bits signed, MEMW bits), a reserved byte that is not zero, a commit without its earlier parts, a partial
//     WSTRB, an address not aligned to AxilDw / 8, or a read of a memory window. DECERR for any other address
//     (the job and result windows of the address map are the two streams here).
// Job stream: a descriptor whose TLAST is not on its last beat is dropped and counted in DROPPED. A whole
//   descriptor is checked as the reference checks a job (ref/pipeline.h, job_faults): a reserved byte set, a mode
//   of 3 or a mask above 15, a tag wider than TAGW, a shell range past the words loaded, map dimensions outside
//   1..2^DW, a voxmap range past the words loaded (or, on a distance device, a map base off a bank boundary), an M,
//   t or threshold that does not fit; on a sparse device (BL > 0) also a sparse map's table and bricks past the words
//   loaded (or off a bank boundary on a distance device), a dense map's brick fields not 0, and anywhere a sparse
//   map or shell on a dense device or sparse bits other than 0 and 1 (byte 0x06: bits 2..7 are reserved, so such a
//   descriptor breaks the format, fault bit 0, as well as bit 1: ref/pipeline.h's job_faults). A descriptor that
//   breaks any rule is refused: the device never sees it; once
//   the records of every job before it have left, an error record {kind 3, tag, faults} takes its place in the
//   record stream (the rules it breaks, one bit each: ref/address_map.h), and DROPPED counts it.
//
// Latency: with the job stream always valid and the record stream always ready, a job whose first descriptor beat
// is taken in cycle f and whose completion record carries `cycles` has its completion's last beat taken in cycle
// f + cycles + 2 + 1024 / JobDw + 256 / RecDw (the device alone: its job taken in cycle a, its completion in cycle
// a + cycles + 1). One register receives a descriptor, one holds it checked, one holds a record: 3 cycles more
// than the beats.

`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
`ifndef VOXCD_PARAMS_SVH
`include "voxcd_params.svh"
`endif
module voxcd_axi #(
  `VOXCD_DEVICE_PARAMS,
  parameter int unsigned AxilDw  = 32,     // AXI4-Lite data bits: 32 or 64
  parameter int unsigned JobDw   = 64,     // job stream TDATA bits: a power of two, 8 .. 1024
  parameter int unsigned RecDw   = 64,     // record stream TDATA bits: a power of two, 8 .. 256
  parameter int unsigned ClockPs = 10000   // the CLOCK_PS register: the clock period in picoseconds
) (
  input  logic                clk_i,
  input  logic                rst_ni,

  // AXI4-Lite slave.
  input  logic                s_axil_awvalid_i,
  output logic                s_axil_awready_o,
  input  logic [31:0]         s_axil_awaddr_i,
  input  logic [2:0]          s_axil_awprot_i,   // ignored
  input  logic                s_axil_wvalid_i,
  output logic                s_axil_wready_o,
  input  logic [AxilDw-1:0]   s_axil_wdata_i,
  input  logic [AxilDw/8-1:0] s_axil_wstrb_i,
  output logic                s_axil_bvalid_o,
  input  logic                s_axil_bready_i,
  output logic [1:0]          s_axil_bresp_o,
  input  logic                s_axil_arvalid_i,
  output logic                s_axil_arready_o,
  input  logic [31:0]         s_axil_araddr_i,
  input  logic [2:0]          s_axil_arprot_i,   // ignored
  output logic                s_axil_rvalid_o,
  input  logic                s_axil_rready_i,
  output logic [AxilDw-1:0]   s_axil_rdata_o,
  output logic [1:0]          s_axil_rresp_o,

  // AXI4-Stream slave: job descriptors.
  input  logic                s_axis_job_tvalid_i,
  output logic                s_axis_job_tready_o,
  input  logic [JobDw-1:0]    s_axis_job_tdata_i,
  input  logic                s_axis_job_tlast_i,

  // AXI4-Stream master: result records.
  output logic                m_axis_rec_tvalid_o,
  input  logic                m_axis_rec_tready_i,
  output logic [RecDw-1:0]    m_axis_rec_tdata_o,
  output logic                m_axis_rec_tlast_o
);

  localparam int unsigned IW       = SB + 3 * WB;
  localparam int unsigned PtW      = BL > 0 ? SAW + 6 : SAW;  // a point index (a sparse shell's: 64 a word)
  localparam int unsigned CW       = voxcd_arch_pkg::CW;
  localparam int unsigned JobBytes = 128;
  localparam int unsigned RecBytes = 32;
  localparam int unsigned JobBeats = 8 * JobBytes / JobDw;
  localparam int unsigned RecBeats = 8 * RecBytes / RecDw;
  localparam int unsigned JobBW    = JobBeats > 1 ? $clog2(JobBeats) : 1;
  localparam int unsigned RecBW    = RecBeats > 1 ? $clog2(RecBeats) : 1;
  localparam int unsigned AlignW   = $clog2(AxilDw / 8);

  localparam logic [1:0] RespOkay   = 2'b00;
  localparam logic [1:0] RespSlverr = 2'b10;
  localparam logic [1:0] RespDecerr = 2'b11;

  // The address map (ref/address_map.h).
  localparam logic [31:0] RegSize    = 32'h0000_1000;
  localparam logic [31:0] ShellBase  = 32'h1000_0000;
  localparam logic [31:0] MapBase    = 32'h2000_0000;
  localparam logic [63:0] ShellBytes = 64'd16 << SAW;
  localparam logic [63:0] MapBytes   = 64'd8 << MAW;
  localparam logic [63:0] DeviceId   = 64'h766f_7863_6400_0001;
  localparam logic [11:0] RegId = 12'h000, RegConfig0 = 12'h008, RegConfig1 = 12'h010, RegClockPs = 12'h018,
                          RegStatus = 12'h020, RegStaged = 12'h028, RegResultCount = 12'h030, RegRun = 12'h038,
                          RegJobsDone = 12'h040, RegHits = 12'h048, RegPoints = 12'h050, RegCycles = 12'h058,
                          RegStalls = 12'h060, RegShellWords = 12'h068, RegMapWords = 12'h070,
                          RegDropped = 12'h078, RegConflicts = 12'h080;
  localparam logic [63:0] Config0 = {8'(LANES), 8'(MEMW), 8'(DW), 8'(TW), 8'(MF), 8'(MW), 8'(PF), 8'(PW)};
  localparam logic [63:0] Config1 = {8'(BL), 8'(Depth), 8'(BANKS), 8'(WB), 8'(SB), 8'(TAGW), 8'(MAW), 8'(SAW)};
  // The rules a refused descriptor breaks (the error record's faults; ref/pipeline.h and ref/address_map.h).
  localparam int unsigned FaultW = 8;
  localparam int unsigned FaultReserved = 0, FaultMode = 1, FaultTag = 2, FaultShell = 3, FaultDims = 4,
                          FaultMap = 5, FaultPose = 6, FaultThreshold = 7;

  // ---- Device ----
  logic                 shell_we, map_we;
  logic [SAW-1:0]       shell_waddr;
  logic [3*PW-1:0]      shell_wdata;
  logic [MAW-1:0]       map_waddr;
  logic [MEMW-1:0]      map_wdata;
  logic                 job_valid, job_ready;
  logic                 hit_valid, done_valid, rec_take;
  logic [TAGW-1:0]      hit_tag, done_tag;
  logic [PtW-1:0]       hit_point;
  logic [DW-1:0]        hit_x, hit_y, hit_z;
  logic [1:0]           hit_state;
  logic [IW-1:0]        hit_dist;
  logic [PtW:0]         done_hits, done_points;
  logic [CW-1:0]        done_cycles, done_stalls, conflicts;  // conflicts: the device's bank conflict cycles
  logic                 dev_busy;

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

  logic [63:0] shell_words_q, map_words_q;

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
    d_faults[FaultShell] = (d_shell_base >> SAW) != '0 || 64'(d_shell_base) + 64'(d_shell_count) > shell_words_q ||
                           (BL == 0 && d_sparse[1]);
    d_faults[FaultDims]  = !dims_ok;
    d_faults[FaultMap]   = (d_map_base >> MAW) != '0 || (SB > 2 && d_map_base[2:0] != 3'd0) ||
                           (dims_ok && 64'(d_map_base) + (d_sparse[0] ? d_table_words : d_map_words) > map_words_q);
    // A sparse map's bricks (any sparse map on a dense device), or a dense map's brick fields.
    if (d_sparse[0]) begin
      d_faults[FaultMap] = d_faults[FaultMap] || BL == 0 || (d_brick_base >> MAW) != '0 ||
                           (SB > 2 && d_brick_base[2:0] != 3'd0) || d_bricks_end > map_words_q;
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
  logic              err_emit;   // the checked descriptor's error record enters the record register
  logic              chk_leave;  // the checked descriptor leaves (into the device, or as its error record)
  logic              desc_leave; // the descriptor register empties into the checked one

  assign job_valid = chk_full_q && chk_faults_q == '0;
  assign chk_leave = chk_full_q && (job_valid ? job_ready : err_emit);
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

  voxcd_device #(
    `VOXCD_DEVICE_PARAM_MAP
  ) u_device (
    .clk_i            (clk_i),
    .rst_ni           (rst_ni),
    .shell_we_i       (shell_we),
    .shell_waddr_i    (shell_waddr),
    .shell_wdata_i    (shell_wdata),
    .map_we_i         (map_we),
    .map_waddr_i      (map_waddr),
    .map_wdata_i      (map_wdata),
    .job_valid_i      (job_valid),
    .job_ready_o      (job_ready),
    .job_tag_i        (TAGW'(chk_tag_q)),
    .job_mode_i       (chk_mode_q),
    .job_mask_i       (chk_mask_q),
    .job_shell_base_i (chk_shell_base_q),
    .job_shell_count_i(chk_shell_count_q),
    .job_map_base_i   (chk_map_base_q),
    .job_nx_i         (chk_nx_q),
    .job_ny_i         (chk_ny_q),
    .job_nz_i         (chk_nz_q),
    .job_m00_i        (chk_m_q[0]), .job_m01_i(chk_m_q[1]), .job_m02_i(chk_m_q[2]),
    .job_m10_i        (chk_m_q[3]), .job_m11_i(chk_m_q[4]), .job_m12_i(chk_m_q[5]),
    .job_m20_i        (chk_m_q[6]), .job_m21_i(chk_m_q[7]), .job_m22_i(chk_m_q[8]),
    .job_t0_i         (chk_t_q[0]), .job_t1_i(chk_t_q[1]), .job_t2_i(chk_t_q[2]),
    .job_threshold_i  (chk_thr_q),
    .job_sparse_i     (chk_sparse_q),
    .job_brick_base_i (chk_brick_base_q),
    .job_brick_units_i(chk_brick_units_q),
    .hit_valid_o      (hit_valid),
    .hit_ready_i      (rec_take),
    .hit_tag_o        (hit_tag),
    .hit_point_o      (hit_point),
    .hit_x_o          (hit_x),
    .hit_y_o          (hit_y),
    .hit_z_o          (hit_z),
    .hit_state_o      (hit_state),
    .hit_dist_o       (hit_dist),
    .done_valid_o     (done_valid),
    .done_ready_i     (rec_take),
    .done_tag_o       (done_tag),
    .done_hits_o      (done_hits),
    .done_cycles_o    (done_cycles),
    .done_points_o    (done_points),
    .done_stalls_o    (done_stalls),
    .conflicts_o      (conflicts),
    .busy_o           (dev_busy)
  );

  // ---- Job stream: beats into the descriptor register ----
  logic [JobBW-1:0] jbeat_q;     // beat of the descriptor being received
  logic             jlong_q;     // it has had more than JobBeats beats
  logic             jtake;
  logic             run_q;
  logic [63:0]      dropped_q;

  assign s_axis_job_tready_o = run_q && (!desc_full_q || desc_leave);
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
      dropped_q <= dropped_q + 64'(err_emit) + 64'(jframe_bad);
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
  assign err_emit = chk_full_q && chk_faults_q != '0 && !dev_busy && rec_take;

  always_comb begin
    rec_d = '0;
    if (err_emit) begin
      rec_d[8*32'h00 +: 8]  = 8'd3;
      rec_d[8*32'h04 +: 32] = chk_tag_q;
      rec_d[8*32'h08 +: 32] = 32'(chk_faults_q);
    end else if (done_valid) begin
      rec_d[8*32'h00 +: 8]  = 8'd2;
      rec_d[8*32'h04 +: 32] = 32'(done_tag);
      rec_d[8*32'h08 +: 32] = 32'(done_hits);
      rec_d[8*32'h0c +: 32] = 32'(done_points);
      rec_d[8*32'h10 +: 64] = 64'(done_cycles);
      rec_d[8*32'h18 +: 64] = 64'(done_stalls);
    end else begin
      rec_d[8*32'h00 +: 8]  = 8'd1;
      rec_d[8*32'h01 +: 8]  = 8'(hit_state);
      rec_d[8*32'h04 +: 32] = 32'(hit_tag);
      rec_d[8*32'h08 +: 32] = 32'(hit_point);
      rec_d[8*32'h0c +: 32] = 32'(hit_x);
      rec_d[8*32'h10 +: 32] = 32'(hit_y);
      rec_d[8*32'h14 +: 32] = 32'(hit_z);
      rec_d[8*32'h18 +: 64] = SB > 2 ? 64'($signed(hit_dist)) : 64'd0;
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
      if (rec_take) rec_valid_q <= hit_valid || done_valid || err_emit;
      if (rec_take && done_valid) begin
        jobs_done_q <= jobs_done_q + 64'd1;
        hits_q      <= hits_q + 64'(done_hits);
        points_q    <= points_q + 64'(done_points);
        cycles_q    <= cycles_q + 64'(done_cycles);
        stalls_q    <= stalls_q + 64'(done_stalls);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (rec_take && (hit_valid || done_valid || err_emit)) rec_q <= rec_d;
  end

  assign m_axis_rec_tvalid_o = rec_valid_q;
  assign m_axis_rec_tdata_o  = rec_q[32'(rbeat_q) * RecDw +: RecDw];
  assign m_axis_rec_tlast_o  = rlast;

  // ---- AXI4-Lite: registers ----
  logic        busy;
  logic [63:0] status;
  assign busy   = dev_busy || desc_full_q || chk_full_q || jbeat_q != '0 || jlong_q || rec_valid_q;
  assign status = {60'd0, 1'b0, desc_full_q || chk_full_q, rec_valid_q, busy};  // fault, staged, results, busy

  // Whether byte address a is in the window [base, base + size).
  function automatic logic in_window(input logic [31:0] a, input logic [31:0] base, input logic [63:0] size);
    logic [31:0] off;
    off = a - base;
    in_window = a >= base && {32'd0, off} < size;
  endfunction

  // ---- AXI4-Lite: reads (one outstanding) ----
  logic              rvalid_q;
  logic [AxilDw-1:0] rdata_q, rdata_d;
  logic [1:0]        rresp_q, rresp_d;

  always_comb begin
    logic [63:0] v;
    logic [1:0]  kind;
    // The register at the offset; kind: 0 readable, 1 write-only (RUN), 2 none.
    kind = 2'd0;
    case ({s_axil_araddr_i[11:3], 3'b000})
      RegId:          v = DeviceId;
      RegConfig0:     v = Config0;
      RegConfig1:     v = Config1;
      RegClockPs:     v = 64'(ClockPs);
      RegStatus:      v = status;
      RegStaged:      v = 64'(desc_full_q) + 64'(chk_full_q);
      RegResultCount: v = 64'(rec_valid_q);
      RegJobsDone:    v = jobs_done_q;
      RegHits:        v = hits_q;
      RegPoints:      v = points_q;
      RegCycles:      v = cycles_q;
      RegStalls:      v = stalls_q;
      RegShellWords:  v = shell_words_q;
      RegMapWords:    v = map_words_q;
      RegDropped:     v = dropped_q;
      RegConflicts:   v = 64'(conflicts);
      RegRun:         begin v = '0; kind = 2'd1; end
      default:        begin v = '0; kind = 2'd2; end
    endcase
    rdata_d = AxilDw'(AxilDw == 64 ? v : (s_axil_araddr_i[2] ? v >> 32 : v));
    if (s_axil_araddr_i < RegSize) begin
      rresp_d = kind == 2'd0 ? RespOkay : (kind == 2'd1 ? RespSlverr : RespDecerr);
      if (AlignW'(s_axil_araddr_i) != '0) rresp_d = RespSlverr;
    end else if (in_window(s_axil_araddr_i, ShellBase, ShellBytes) || in_window(s_axil_araddr_i, MapBase, MapBytes)) begin
      rresp_d = RespSlverr;  // the memories are write-only
    end else begin
      rresp_d = RespDecerr;
    end
    if (rresp_d != RespOkay) rdata_d = '0;
  end

  assign s_axil_arready_o = !rvalid_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      rvalid_q <= 1'b0;
      rdata_q  <= '0;
      rresp_q  <= RespOkay;
    end else if (s_axil_arvalid_i && s_axil_arready_o) begin
      rvalid_q <= 1'b1;
      rdata_q  <= rdata_d;
      rresp_q  <= rresp_d;
    end else if (s_axil_rready_i) begin
      rvalid_q <= 1'b0;
    end
  end

  assign s_axil_rvalid_o = rvalid_q;
  assign s_axil_rdata_o  = rdata_q;
  assign s_axil_rresp_o  = rresp_q;

  // ---- AXI4-Lite: writes (address and data taken in either order, then one response) ----
  logic                aw_full_q, w_full_q, bvalid_q;
  logic [31:0]         awaddr_q;
  logic [AxilDw-1:0]   wdata_q;
  logic [AxilDw/8-1:0] wstrb_q;
  logic [1:0]          bresp_q, bresp_d;
  logic                do_write;
  // Parts of a memory word written before the write that commits it.
  logic [SAW-1:0]      sk_q;        // the shell word they belong to
  logic [1:0]          shas_q;      // x, y written
  logic [PW-1:0]       sx_q, sy_q;
  logic [MAW-1:0]      mk_q;
  logic                mhas_q;      // low half written (AxilDw = 32)
  logic [31:0]         mlo_q;
  // Next values from this write.
  logic [1:0]          shas_d;
  logic [PW-1:0]       sx_d, sy_d;
  logic [SAW-1:0]      sk_d;
  logic                mhas_d;
  logic [MAW-1:0]      mk_d;
  logic [31:0]         mlo_d;
  logic                run_d;

  assign s_axil_awready_o = !aw_full_q && !bvalid_q;
  assign s_axil_wready_o  = !w_full_q && !bvalid_q;
  assign do_write         = aw_full_q && w_full_q && !bvalid_q;

  // The memory word the pending write addresses (when it is in that memory's window).
  logic [31:0]    shell_off, map_off;
  logic [SAW-1:0] shell_k;
  logic [MAW-1:0] map_k;
  assign shell_off = awaddr_q - ShellBase;
  assign map_off   = awaddr_q - MapBase;
  assign shell_k   = SAW'(shell_off >> 4);
  assign map_k     = MAW'(map_off >> 3);

  // A write's effect: its response, and the memory write it commits (if any).
  always_comb begin
    logic [31:0] a;
    logic [3:0]  b;         // byte offset in a shell word, or in a voxmap word (b[2:0])
    logic [31:0] lo, hi;    // the write's two 32-bit halves (hi only with AxilDw = 64)
    logic [63:0] word;
    a           = awaddr_q;
    lo          = wdata_q[31:0];
    hi          = AxilDw == 64 ? 32'(wdata_q >> 32) : 32'd0;
    b           = a[3:0];
    word        = 64'd0;
    bresp_d     = RespOkay;
    run_d       = 1'b0;
    shell_we    = 1'b0;
    map_we      = 1'b0;
    shell_waddr = sk_q;
    shell_wdata = {sy_q, sy_q, sx_q};  // with shell_we low: any value
    map_waddr   = mk_q;
    map_wdata   = '0;
    shas_d      = shas_q;
    sk_d        = sk_q;
    sx_d        = sx_q;
    sy_d        = sy_q;
    mhas_d      = mhas_q;
    mk_d        = mk_q;
    mlo_d       = mlo_q;
    if (AlignW'(a) != '0 || wstrb_q != '1) begin
      bresp_d = RespSlverr;  // an unaligned address or a partial WSTRB: the write changes nothing
    end else if (a < RegSize) begin
      if ({a[11:3], 3'b000} == RegRun) run_d = 1'b1;
      else bresp_d = {a[11:3], 3'b000} <= RegConflicts ? RespSlverr : RespDecerr;  // read-only, or no register
    end else if (in_window(a, ShellBase, ShellBytes)) begin
      if (busy) bresp_d = RespSlverr;
      else if (b == 4'd0 || b == 4'd4) begin
        // x (and y with AxilDw = 64), or y.
        if (b == 4'd0 && !fits_signed64(64'($signed(lo)), PW)) bresp_d = RespSlverr;
        if ((b == 4'd4 || AxilDw == 64) && !fits_signed64(64'($signed(b == 4'd4 ? lo : hi)), PW))
          bresp_d = RespSlverr;
        if (bresp_d == RespOkay) begin
          if (shell_k != sk_q) shas_d = 2'b00;
          sk_d = shell_k;
          if (b == 4'd0) begin
            sx_d      = PW'(lo);
            shas_d[0] = 1'b1;
          end
          if (b == 4'd4 || AxilDw == 64) begin
            sy_d      = PW'(b == 4'd4 ? lo : hi);
            shas_d[1] = 1'b1;
          end
        end
      end else if (b == 4'd8) begin
        // z commits the word (with AxilDw = 64 the reserved bytes 12..15 come with it and must be zero).
        if (!fits_signed64(64'($signed(lo)), PW) || hi != '0 || shas_q != 2'b11 || shell_k != sk_q)
          bresp_d = RespSlverr;
        else begin
          shell_we    = 1'b1;
          shell_wdata = {PW'(lo), sy_q, sx_q};
          shas_d      = 2'b00;
        end
      end else if (lo != '0) begin
        bresp_d = RespSlverr;  // bytes 12..15 are reserved
      end
    end else if (in_window(a, MapBase, MapBytes)) begin
      word  = AxilDw == 64 ? {hi, lo} : {lo, mlo_q};
      if (busy) bresp_d = RespSlverr;
      else if (AxilDw == 32 && b[2] == 1'b0) begin
        if (MEMW < 32 && (lo >> MEMW) != '0) bresp_d = RespSlverr;
        else begin
          mhas_d = 1'b1;
          mk_d   = map_k;
          mlo_d  = lo;
        end
      end else begin
        if ((MEMW < 64 && (word >> MEMW) != '0) || (AxilDw == 32 && (!mhas_q || map_k != mk_q)))
          bresp_d = RespSlverr;
        else begin
          map_we    = 1'b1;
          map_waddr = map_k;
          map_wdata = MEMW'(word);
          mhas_d    = 1'b0;
        end
      end
    end else begin
      bresp_d = RespDecerr;
    end
    if (!do_write) begin
      shell_we = 1'b0;
      map_we   = 1'b0;
      run_d    = 1'b0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      aw_full_q     <= 1'b0;
      w_full_q      <= 1'b0;
      bvalid_q      <= 1'b0;
      bresp_q       <= RespOkay;
      run_q         <= 1'b0;
      shas_q        <= 2'b00;
      mhas_q        <= 1'b0;
      shell_words_q <= '0;
      map_words_q   <= '0;
    end else begin
      if (s_axil_awvalid_i && s_axil_awready_o) aw_full_q <= 1'b1;
      if (s_axil_wvalid_i && s_axil_wready_o) w_full_q <= 1'b1;
      if (do_write) begin
        aw_full_q <= 1'b0;
        w_full_q  <= 1'b0;
        bvalid_q  <= 1'b1;
        bresp_q   <= bresp_d;
        shas_q    <= shas_d;
        mhas_q    <= mhas_d;
        if (run_d) run_q <= 1'b1;
        if (shell_we && 64'(shell_waddr) >= shell_words_q) shell_words_q <= 64'(shell_waddr) + 64'd1;
        if (map_we && 64'(map_waddr) >= map_words_q) map_words_q <= 64'(map_waddr) + 64'd1;
      end else if (s_axil_bready_i) begin
        bvalid_q <= 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (s_axil_awvalid_i && s_axil_awready_o) awaddr_q <= s_axil_awaddr_i;
    if (s_axil_wvalid_i && s_axil_wready_o) begin
      wdata_q <= s_axil_wdata_i;
      wstrb_q <= s_axil_wstrb_i;
    end
    if (do_write) begin
      sk_q  <= sk_d;
      sx_q  <= sx_d;
      sy_q  <= sy_d;
      mk_q  <= mk_d;
      mlo_q <= mlo_d;
    end
  end

  assign s_axil_bvalid_o = bvalid_q;
  assign s_axil_bresp_o  = bresp_q;

  logic unused;
  assign unused = ^{s_axil_awprot_i, s_axil_arprot_i, shell_off, map_off};

`ifndef SYNTHESIS
  // ---- Parameter sanity, at elaboration ----
  if (AxilDw != 32 && AxilDw != 64) begin : g_bad_axil_dw
    $error("AxilDw = %0d must be 32 or 64", AxilDw);
  end
  if ((JobDw & (JobDw - 1)) != 0 || JobDw < 8 || JobDw > 8 * JobBytes) begin : g_bad_job_dw
    $error("JobDw = %0d must be a power of two in 8..1024", JobDw);
  end
  if ((RecDw & (RecDw - 1)) != 0 || RecDw < 8 || RecDw > 8 * RecBytes) begin : g_bad_rec_dw
    $error("RecDw = %0d must be a power of two in 8..256", RecDw);
  end
  if (SAW > 24 || MAW > 28 || TAGW > 32 || IW > 64) begin : g_bad_windows
    $error("the address map holds SAW <= 24, MAW <= 28, TAGW <= 32 and IW <= 64");
  end

  // ---- AXI rules (AMBA AXI4 and AXI4-Stream): what this slave and master promise ----
  // A response or a record beat, once valid, stays valid and unchanged until it is taken.
  `VOXCD_ASSERT(AxilBStable, s_axil_bvalid_o && !s_axil_bready_i |=> s_axil_bvalid_o && $stable(s_axil_bresp_o))
  `VOXCD_ASSERT(AxilRStable, s_axil_rvalid_o && !s_axil_rready_i |=>
                             s_axil_rvalid_o && $stable(s_axil_rdata_o) && $stable(s_axil_rresp_o))
  `VOXCD_ASSERT(RecStable, m_axis_rec_tvalid_o && !m_axis_rec_tready_i |=>
                           m_axis_rec_tvalid_o && $stable(m_axis_rec_tdata_o) && $stable(m_axis_rec_tlast_o))
  // AXI4-Lite has no EXOKAY.
  `VOXCD_ASSERT(AxilNoExokay, !(s_axil_bvalid_o && s_axil_bresp_o == 2'b01) &&
                              !(s_axil_rvalid_o && s_axil_rresp_o == 2'b01))
  // What the masters driving this top promise (their own checkers' rules; a failure here is theirs).
  `VOXCD_ASSERT(AxilAwStable, s_axil_awvalid_i && !s_axil_awready_o |=>
                              s_axil_awvalid_i && $stable(s_axil_awaddr_i))
  `VOXCD_ASSERT(AxilWStable, s_axil_wvalid_i && !s_axil_wready_o |=>
                             s_axil_wvalid_i && $stable(s_axil_wdata_i) && $stable(s_axil_wstrb_i))
  `VOXCD_ASSERT(AxilArStable, s_axil_arvalid_i && !s_axil_arready_o |=>
                              s_axil_arvalid_i && $stable(s_axil_araddr_i))
  `VOXCD_ASSERT(JobStable, s_axis_job_tvalid_i && !s_axis_job_tready_o |=>
                           s_axis_job_tvalid_i && $stable(s_axis_job_tdata_i) && $stable(s_axis_job_tlast_i))
  // Inside: the record register is only loaded when it is free, the device sees a write only while idle and a
  // job only when it is valid, and the job stream stays closed until RUN.
  `VOXCD_ASSERT(RecNoOverwrite, !(rec_valid_q && !(m_axis_rec_tready_i && rlast) && rec_take))
  `VOXCD_ASSERT(MemWriteIdle, !((shell_we || map_we) && (dev_busy || desc_full_q || chk_full_q)))
  `VOXCD_ASSERT(JobValidDescriptor, !job_valid || (chk_mode_q <= 2'd2 && chk_nx_q != '0 && chk_ny_q != '0 &&
                                                   chk_nz_q != '0))
  // An error record waits for the device to be idle, and leaves only into a free record register.
  `VOXCD_ASSERT(ErrorAfterEarlierRecords, !err_emit || (!dev_busy && !hit_valid && !done_valid))
  `VOXCD_ASSERT(JobClosedBeforeRun, run_q || !s_axis_job_tready_o)
`endif


  // Functional coverage (docs/verification.md): a refused descriptor breaking each rule, a job frame of the wrong
  // length, and each error response of the AXI4-Lite port.
  `VOXCD_COVER(CoverFaultReserved, err_emit && chk_faults_q[FaultReserved])
  `VOXCD_COVER(CoverFaultMode, err_emit && chk_faults_q[FaultMode])
  `VOXCD_COVER(CoverFaultTag, err_emit && chk_faults_q[FaultTag])
  `VOXCD_COVER(CoverFaultShell, err_emit && chk_faults_q[FaultShell])
  `VOXCD_COVER(CoverFaultDims, err_emit && chk_faults_q[FaultDims])
  `VOXCD_COVER(CoverFaultMap, err_emit && chk_faults_q[FaultMap])
  `VOXCD_COVER(CoverFaultPose, err_emit && chk_faults_q[FaultPose])
  `VOXCD_COVER(CoverFaultThreshold, err_emit && chk_faults_q[FaultThreshold])
  `VOXCD_COVER(CoverJobFrameOfTheWrongLength, jframe_bad)
  `VOXCD_COVER(CoverWriteRefused, s_axil_bvalid_o && s_axil_bresp_o == RespSlverr)
  `VOXCD_COVER(CoverWriteToNoRegister, s_axil_bvalid_o && s_axil_bresp_o == RespDecerr)
  `VOXCD_COVER(CoverReadRefused, s_axil_rvalid_o && s_axil_rresp_o == RespSlverr)
  `VOXCD_COVER(CoverReadOfNoRegister, s_axil_rvalid_o && s_axil_rresp_o == RespDecerr)

endmodule
