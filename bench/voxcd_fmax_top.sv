// voxcd_fmax_top: a pin-limited wrapper of voxcd_device for place and route. For measurement only (logic cells,
// RAMs and Fmax in bench/rtl_cost.sh); it is not part of the device and does nothing useful.
//
// The device has hundreds of ports, more than an FPGA package has pins. Here one input pin feeds a shift register
// as wide as all the device's inputs together (except clk_i / rst_ni), which drives every device input; every
// device output is registered and the registers are XOR-reduced into one registered output pin. So no logic of
// the device is optimised away (every input is live, every output observed), and every path into and out of the
// device starts or ends at a flip-flop next to it, so IO timing does not limit the internal paths.
//
// Depth is the register stages voxcd_device adds to its lanes (docs/hardware.md, "Pipeline depth").
module voxcd_fmax_top #(
  `VOXCD_DEVICE_PARAMS  // voxcd_device's (voxcd_arch_pkg.sv)
) (
  input  logic clk_i,
  input  logic rst_ni,
  input  logic din_i,
  output logic dout_o
);

  localparam int unsigned CW = voxcd_arch_pkg::CW;
  localparam int unsigned IW = SB + 3 * WB;
  // The threshold and distance ports count only on a distance device (a 2-bit device leaves them unused), the sparse
  // job fields only on a sparse device; a hit's point and a completion's counts are 6 bits wider there.
  localparam int unsigned DistW = SB > 2 ? IW : 0;
  localparam int unsigned SpW   = BL > 0 ? 2 + MAW + (MAW + 1) : 0;
  localparam int unsigned PtW   = BL > 0 ? SAW + 6 : SAW;

  // Every device input but clk_i / rst_ni, in port order (the threshold last).
  localparam int unsigned BaseInW = 1 + SAW + 3 * PW       // shell write port
                              + 1 + MAW + MEMW             // voxmap write port
                              + 1 + TAGW + 2 + 4 + SAW + (SAW + 1) + MAW + 3 * (DW + 1) + 9 * MW + 3 * TW  // job
                              + 1                          // hit_ready_i
                              + 1;                         // done_ready_i
  localparam int unsigned InW = BaseInW + DistW + SpW;
  // Every device output, in port order (the distance last).
  localparam int unsigned BaseOutW = 1                                    // job_ready_o
                               + 1 + TAGW + PtW + 3 * DW + 2              // hit stream
                               + 1 + TAGW + (PtW + 1) + CW + (PtW + 1) + CW  // completion stream
                               + 1                                        // busy_o
                               + CW;                                      // conflicts_o
  localparam int unsigned OutW = BaseOutW + DistW;

  // ---- Inputs: a shift register from din_i ----
  logic [InW-1:0] in_q;
  always_ff @(posedge clk_i) in_q <= {in_q[InW-2:0], din_i};

  logic                shell_we;
  logic [SAW-1:0]      shell_waddr;
  logic [3*PW-1:0]     shell_wdata;
  logic                map_we;
  logic [MAW-1:0]      map_waddr;
  logic [MEMW-1:0]     map_wdata;
  logic                job_valid;
  logic [TAGW-1:0]     job_tag;
  logic [1:0]          job_mode;
  logic [3:0]          job_mask;
  logic [SAW-1:0]      job_shell_base;
  logic [SAW:0]        job_shell_count;
  logic [MAW-1:0]      job_map_base;
  logic [DW:0]         job_nx, job_ny, job_nz;
  logic [MW-1:0]       job_m00, job_m01, job_m02, job_m10, job_m11, job_m12, job_m20, job_m21, job_m22;
  logic [TW-1:0]       job_t0, job_t1, job_t2;
  logic                hit_ready, done_ready;
  logic [IW-1:0]       job_threshold;
  logic [1:0]          job_sparse;
  logic [MAW-1:0]      job_brick_base;
  logic [MAW:0]        job_brick_units;

  assign {shell_we, shell_waddr, shell_wdata,
          map_we, map_waddr, map_wdata,
          job_valid, job_tag, job_mode, job_mask, job_shell_base, job_shell_count, job_map_base,
          job_nx, job_ny, job_nz,
          job_m00, job_m01, job_m02, job_m10, job_m11, job_m12, job_m20, job_m21, job_m22,
          job_t0, job_t1, job_t2,
          hit_ready, done_ready} = in_q[InW-1 -: BaseInW];
  if (SB > 2) begin : g_threshold
    assign job_threshold = in_q[SpW +: IW];
  end else begin : g_no_threshold
    assign job_threshold = '0;
  end
  if (BL > 0) begin : g_sparse
    assign {job_sparse, job_brick_base, job_brick_units} = in_q[SpW-1:0];
  end else begin : g_no_sparse
    assign {job_sparse, job_brick_base, job_brick_units} = '0;
  end

  // ---- The device ----
  logic            job_ready;
  logic            hit_valid;
  logic [TAGW-1:0] hit_tag;
  logic [PtW-1:0]  hit_point;
  logic [DW-1:0]   hit_x, hit_y, hit_z;
  logic [1:0]      hit_state;
  logic [IW-1:0]   hit_dist;
  logic            done_valid;
  logic [TAGW-1:0] done_tag;
  logic [PtW:0]    done_hits;
  logic [CW-1:0]   done_cycles;
  logic [PtW:0]    done_points;
  logic [CW-1:0]   done_stalls;
  logic            busy;
  logic [CW-1:0]   conflicts;

  voxcd_device #(
    `VOXCD_DEVICE_PARAM_MAP
  ) u_device (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .shell_we_i        (shell_we),
    .shell_waddr_i     (shell_waddr),
    .shell_wdata_i     (shell_wdata),
    .map_we_i          (map_we),
    .map_waddr_i       (map_waddr),
    .map_wdata_i       (map_wdata),
    .job_valid_i       (job_valid),
    .job_ready_o       (job_ready),
    .job_tag_i         (job_tag),
    .job_mode_i        (job_mode),
    .job_mask_i        (job_mask),
    .job_shell_base_i  (job_shell_base),
    .job_shell_count_i (job_shell_count),
    .job_map_base_i    (job_map_base),
    .job_nx_i          (job_nx),
    .job_ny_i          (job_ny),
    .job_nz_i          (job_nz),
    .job_m00_i         (job_m00),
    .job_m01_i         (job_m01),
    .job_m02_i         (job_m02),
    .job_m10_i         (job_m10),
    .job_m11_i         (job_m11),
    .job_m12_i         (job_m12),
    .job_m20_i         (job_m20),
    .job_m21_i         (job_m21),
    .job_m22_i         (job_m22),
    .job_t0_i          (job_t0),
    .job_t1_i          (job_t1),
    .job_t2_i          (job_t2),
    .job_threshold_i   (job_threshold),
    .job_sparse_i      (job_sparse),
    .job_brick_base_i  (job_brick_base),
    .job_brick_units_i (job_brick_units),
    .hit_valid_o       (hit_valid),
    .hit_ready_i       (hit_ready),
    .hit_tag_o         (hit_tag),
    .hit_point_o       (hit_point),
    .hit_x_o           (hit_x),
    .hit_y_o           (hit_y),
    .hit_z_o           (hit_z),
    .hit_state_o       (hit_state),
    .hit_dist_o        (hit_dist),
    .done_valid_o      (done_valid),
    .done_ready_i      (done_ready),
    .done_tag_o        (done_tag),
    .done_hits_o       (done_hits),
    .done_cycles_o     (done_cycles),
    .done_points_o     (done_points),
    .done_stalls_o     (done_stalls),
    .busy_o            (busy),
    .conflicts_o       (conflicts)
  );

  // ---- Outputs: registered, XOR-reduced into one registered pin ----
  logic [OutW-1:0]     out_q;
  logic [BaseOutW-1:0] out_base;
  assign out_base = {job_ready,
                     hit_valid, hit_tag, hit_point, hit_x, hit_y, hit_z, hit_state,
                     done_valid, done_tag, done_hits, done_cycles, done_points, done_stalls,
                     busy, conflicts};
  if (SB > 2) begin : g_dist_out
    always_ff @(posedge clk_i) out_q <= {out_base, hit_dist};
  end else begin : g_no_dist_out
    always_ff @(posedge clk_i) out_q <= out_base;
    logic unused_dist;
    assign unused_dist = ^hit_dist;  // 0 on a 2-bit device
  end
  always_ff @(posedge clk_i) dout_o <= ^out_q;

endmodule
