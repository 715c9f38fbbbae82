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
//
// Structure: the register file and memory port (voxcd_axi_regs), the job receiver and checker (voxcd_axi_jobs),
// the device (voxcd_device) and the record sender (voxcd_axi_records).

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

  localparam int unsigned IW  = SB + 3 * WB;
  localparam int unsigned PtW = BL > 0 ? SAW + 6 : SAW;  // a point index (a sparse shell's: 64 a word)
  localparam int unsigned CW  = voxcd_arch_pkg::CW;

  // ---- Register file and memory port ----
  logic                 shell_we, map_we;
  logic [SAW-1:0]       shell_waddr;
  logic [3*PW-1:0]      shell_wdata;
  logic [MAW-1:0]       map_waddr;
  logic [MEMW-1:0]      map_wdata;
  logic                 run;                      // RUN has been written: the job stream is open
  logic [63:0]          shell_words, map_words;   // the words loaded in each memory
  logic [63:0]          jobs_done, hits, points, cycles, stalls, dropped;
  logic [CW-1:0]        conflicts;                // the device's bank conflict cycles
  logic                 dev_busy, desc_full, checked, receiving, rec_valid;

  voxcd_axi_regs #(
    .PW(PW), .PF(PF), .MW(MW), .MF(MF), .TW(TW), .DW(DW), .MEMW(MEMW), .MAW(MAW), .SB(SB), .WB(WB), .Depth(Depth),
    .BL(BL), .LANES(LANES), .SAW(SAW), .TAGW(TAGW), .BANKS(BANKS), .AxilDw(AxilDw), .ClockPs(ClockPs)
  ) u_regs (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .s_axil_awvalid_i(s_axil_awvalid_i),
    .s_axil_awready_o(s_axil_awready_o),
    .s_axil_awaddr_i (s_axil_awaddr_i),
    .s_axil_awprot_i (s_axil_awprot_i),
    .s_axil_wvalid_i (s_axil_wvalid_i),
    .s_axil_wready_o (s_axil_wready_o),
    .s_axil_wdata_i  (s_axil_wdata_i),
    .s_axil_wstrb_i  (s_axil_wstrb_i),
    .s_axil_bvalid_o (s_axil_bvalid_o),
    .s_axil_bready_i (s_axil_bready_i),
    .s_axil_bresp_o  (s_axil_bresp_o),
    .s_axil_arvalid_i(s_axil_arvalid_i),
    .s_axil_arready_o(s_axil_arready_o),
    .s_axil_araddr_i (s_axil_araddr_i),
    .s_axil_arprot_i (s_axil_arprot_i),
    .s_axil_rvalid_o (s_axil_rvalid_o),
    .s_axil_rready_i (s_axil_rready_i),
    .s_axil_rdata_o  (s_axil_rdata_o),
    .s_axil_rresp_o  (s_axil_rresp_o),
    .shell_we_o      (shell_we),
    .shell_waddr_o   (shell_waddr),
    .shell_wdata_o   (shell_wdata),
    .map_we_o        (map_we),
    .map_waddr_o     (map_waddr),
    .map_wdata_o     (map_wdata),
    .run_o           (run),
    .shell_words_o   (shell_words),
    .map_words_o     (map_words),
    .dev_busy_i      (dev_busy),
    .desc_full_i     (desc_full),
    .checked_i       (checked),
    .receiving_i     (receiving),
    .rec_valid_i     (rec_valid),
    .jobs_done_i     (jobs_done),
    .hits_i          (hits),
    .points_i        (points),
    .cycles_i        (cycles),
    .stalls_i        (stalls),
    .dropped_i       (dropped),
    .conflicts_i     (conflicts)
  );

  // ---- Job receiver and checker ----
  logic                 job_valid, job_ready;
  logic [31:0]          chk_tag;                  // the checked descriptor's tag as sent
  logic [1:0]           chk_mode, chk_sparse;
  logic [3:0]           chk_mask;
  logic [SAW-1:0]       chk_shell_base;
  logic [SAW:0]         chk_shell_count;
  logic [MAW-1:0]       chk_map_base, chk_brick_base;
  logic [MAW:0]         chk_brick_units;
  logic [DW:0]          chk_nx, chk_ny, chk_nz;
  logic [9*MW-1:0]      chk_m;                    // {m22, ..., m00}
  logic [3*TW-1:0]      chk_t;                    // {t2, t1, t0}
  logic [IW-1:0]        chk_thr;
  logic [7:0]           chk_faults;
  logic                 err_emit;                 // the checked descriptor's error record enters the record register

  voxcd_axi_jobs #(
    .MW(MW), .TW(TW), .DW(DW), .MEMW(MEMW), .SAW(SAW), .MAW(MAW), .TAGW(TAGW), .SB(SB), .WB(WB), .BL(BL),
    .JobDw(JobDw)
  ) u_jobs (
    .clk_i              (clk_i),
    .rst_ni             (rst_ni),
    .run_i              (run),
    .shell_words_i      (shell_words),
    .map_words_i        (map_words),
    .s_axis_job_tvalid_i(s_axis_job_tvalid_i),
    .s_axis_job_tready_o(s_axis_job_tready_o),
    .s_axis_job_tdata_i (s_axis_job_tdata_i),
    .s_axis_job_tlast_i (s_axis_job_tlast_i),
    .job_valid_o        (job_valid),
    .job_ready_i        (job_ready),
    .tag_o              (chk_tag),
    .mode_o             (chk_mode),
    .mask_o             (chk_mask),
    .shell_base_o       (chk_shell_base),
    .shell_count_o      (chk_shell_count),
    .map_base_o         (chk_map_base),
    .nx_o               (chk_nx),
    .ny_o               (chk_ny),
    .nz_o               (chk_nz),
    .m_o                (chk_m),
    .t_o                (chk_t),
    .thr_o              (chk_thr),
    .sparse_o           (chk_sparse),
    .brick_base_o       (chk_brick_base),
    .brick_units_o      (chk_brick_units),
    .checked_o          (checked),
    .faults_o           (chk_faults),
    .err_emit_i         (err_emit),
    .desc_full_o        (desc_full),
    .receiving_o        (receiving),
    .dropped_o          (dropped)
  );

  // ---- Device ----
  logic                 hit_valid, done_valid, rec_take;
  logic [TAGW-1:0]      hit_tag, done_tag;
  logic [PtW-1:0]       hit_point;
  logic [DW-1:0]        hit_x, hit_y, hit_z;
  logic [1:0]           hit_state;
  logic [IW-1:0]        hit_dist;
  logic [PtW:0]         done_hits, done_points;
  logic [CW-1:0]        done_cycles, done_stalls;

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
    .job_tag_i        (TAGW'(chk_tag)),
    .job_mode_i       (chk_mode),
    .job_mask_i       (chk_mask),
    .job_shell_base_i (chk_shell_base),
    .job_shell_count_i(chk_shell_count),
    .job_map_base_i   (chk_map_base),
    .job_nx_i         (chk_nx),
    .job_ny_i         (chk_ny),
    .job_nz_i         (chk_nz),
    .job_m00_i        (chk_m[0*MW +: MW]), .job_m01_i(chk_m[1*MW +: MW]), .job_m02_i(chk_m[2*MW +: MW]),
    .job_m10_i        (chk_m[3*MW +: MW]), .job_m11_i(chk_m[4*MW +: MW]), .job_m12_i(chk_m[5*MW +: MW]),
    .job_m20_i        (chk_m[6*MW +: MW]), .job_m21_i(chk_m[7*MW +: MW]), .job_m22_i(chk_m[8*MW +: MW]),
    .job_t0_i         (chk_t[0*TW +: TW]), .job_t1_i(chk_t[1*TW +: TW]), .job_t2_i(chk_t[2*TW +: TW]),
    .job_threshold_i  (chk_thr),
    .job_sparse_i     (chk_sparse),
    .job_brick_base_i (chk_brick_base),
    .job_brick_units_i(chk_brick_units),
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

  // ---- Record sender ----
  voxcd_axi_records #(
    .DW(DW), .SAW(SAW), .TAGW(TAGW), .SB(SB), .WB(WB), .BL(BL), .RecDw(RecDw)
  ) u_records (
    .clk_i              (clk_i),
    .rst_ni             (rst_ni),
    .dev_busy_i         (dev_busy),
    .take_o             (rec_take),
    .hit_valid_i        (hit_valid),
    .hit_tag_i          (hit_tag),
    .hit_point_i        (hit_point),
    .hit_x_i            (hit_x),
    .hit_y_i            (hit_y),
    .hit_z_i            (hit_z),
    .hit_state_i        (hit_state),
    .hit_dist_i         (hit_dist),
    .done_valid_i       (done_valid),
    .done_tag_i         (done_tag),
    .done_hits_i        (done_hits),
    .done_points_i      (done_points),
    .done_cycles_i      (done_cycles),
    .done_stalls_i      (done_stalls),
    .checked_i          (checked),
    .faults_i           (chk_faults),
    .tag_i              (chk_tag),
    .err_emit_o         (err_emit),
    .m_axis_rec_tvalid_o(m_axis_rec_tvalid_o),
    .m_axis_rec_tready_i(m_axis_rec_tready_i),
    .m_axis_rec_tdata_o (m_axis_rec_tdata_o),
    .m_axis_rec_tlast_o (m_axis_rec_tlast_o),
    .rec_valid_o        (rec_valid),
    .jobs_done_o        (jobs_done),
    .hits_o             (hits),
    .points_o           (points),
    .cycles_o           (cycles),
    .stalls_o           (stalls)
  );

`ifndef SYNTHESIS
  // ---- Parameter sanity, at elaboration (the widths of each unit: in its module) ----
  // The address map holds SAW <= 24, MAW <= 28, TAGW <= 32 and IW <= 64.
  `VOXCD_ASSERT_INIT(WidthsFitTheAddressMap, SAW <= 24 && MAW <= 28 && TAGW <= 32 && IW <= 64)
`endif

endmodule
