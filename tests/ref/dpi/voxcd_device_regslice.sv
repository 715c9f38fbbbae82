// voxcd_device_regslice: a second implementation of the device contract, for the DPI testbench's test of a swapped
// device (tests/ref/dpi/CMakeLists.txt builds tb_voxcd_dpi with +define+VOXCD_DUT=voxcd_device_regslice). It is
// voxcd_device behind a register slice that holds one output record: every record leaves at least a cycle later,
// and the core sees its consumer ready whenever the slice is empty. Parameters and ports are voxcd_device's.
module voxcd_device_regslice #(
  `VOXCD_DEVICE_PARAMS  // voxcd_device's (voxcd_arch_pkg.sv)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     shell_we_i,
  input  logic [SAW-1:0]           shell_waddr_i,
  input  logic [3*PW-1:0]          shell_wdata_i,
  input  logic                     map_we_i,
  input  logic [MAW-1:0]           map_waddr_i,
  input  logic [MEMW-1:0]          map_wdata_i,
  input  logic                     job_valid_i,
  output logic                     job_ready_o,
  input  logic [TAGW-1:0]          job_tag_i,
  input  logic [1:0]               job_mode_i,
  input  logic [3:0]               job_mask_i,
  input  logic [SAW-1:0]           job_shell_base_i,
  input  logic [SAW:0]             job_shell_count_i,
  input  logic [MAW-1:0]           job_map_base_i,
  input  logic [DW:0]              job_nx_i,
  input  logic [DW:0]              job_ny_i,
  input  logic [DW:0]              job_nz_i,
  input  logic [MW-1:0]            job_m00_i, job_m01_i, job_m02_i,
  input  logic [MW-1:0]            job_m10_i, job_m11_i, job_m12_i,
  input  logic [MW-1:0]            job_m20_i, job_m21_i, job_m22_i,
  input  logic [TW-1:0]            job_t0_i, job_t1_i, job_t2_i,
  input  logic [SB+3*WB-1:0]       job_threshold_i,
  input  logic [1:0]               job_sparse_i,
  input  logic [MAW-1:0]           job_brick_base_i,
  input  logic [MAW:0]             job_brick_units_i,
  output logic                     hit_valid_o,
  input  logic                     hit_ready_i,
  output logic [TAGW-1:0]          hit_tag_o,
  output logic [(BL > 0 ? SAW + 6 : SAW)-1:0] hit_point_o,
  output logic [DW-1:0]            hit_x_o,
  output logic [DW-1:0]            hit_y_o,
  output logic [DW-1:0]            hit_z_o,
  output logic [1:0]               hit_state_o,
  output logic [SB+3*WB-1:0]       hit_dist_o,
  output logic                     done_valid_o,
  input  logic                     done_ready_i,
  output logic [TAGW-1:0]          done_tag_o,
  output logic [(BL > 0 ? SAW + 6 : SAW):0] done_hits_o,
  output logic [voxcd_arch_pkg::CW-1:0] done_cycles_o,
  output logic [(BL > 0 ? SAW + 6 : SAW):0] done_points_o,
  output logic [voxcd_arch_pkg::CW-1:0] done_stalls_o,
  output logic                     busy_o,
  output logic [voxcd_arch_pkg::CW-1:0] conflicts_o
);

  localparam int unsigned CW  = voxcd_arch_pkg::CW;
  localparam int unsigned PtW = BL > 0 ? SAW + 6 : SAW;  // a point index (voxcd_device)

  // The core's output streams.
  logic            c_hit_valid, c_done_valid, c_busy;
  logic [TAGW-1:0] c_hit_tag, c_done_tag;
  logic [PtW-1:0]  c_hit_point;
  logic [DW-1:0]   c_hit_x, c_hit_y, c_hit_z;
  logic [1:0]      c_hit_state;
  logic [SB+3*WB-1:0] c_hit_dist;
  logic [PtW:0]    c_done_hits, c_done_points;
  logic [CW-1:0]   c_done_cycles, c_done_stalls, c_conflicts;

  // The slice: one record of either kind, so the stream keeps its order.
  logic full_q, is_done_q, out_ready, free;
  assign out_ready = is_done_q ? done_ready_i : hit_ready_i;
  assign free      = !full_q || out_ready;

  voxcd_device #(
    `VOXCD_DEVICE_PARAM_MAP
  ) u_core (
    .clk_i, .rst_ni, .shell_we_i, .shell_waddr_i, .shell_wdata_i, .map_we_i, .map_waddr_i, .map_wdata_i,
    .job_valid_i, .job_ready_o, .job_tag_i, .job_mode_i, .job_mask_i, .job_shell_base_i, .job_shell_count_i,
    .job_map_base_i, .job_nx_i, .job_ny_i, .job_nz_i, .job_m00_i, .job_m01_i, .job_m02_i, .job_m10_i, .job_m11_i,
    .job_m12_i, .job_m20_i, .job_m21_i, .job_m22_i, .job_t0_i, .job_t1_i, .job_t2_i, .job_threshold_i,
    .job_sparse_i, .job_brick_base_i, .job_brick_units_i,
    .hit_valid_o  (c_hit_valid),
    .hit_ready_i  (free),
    .hit_tag_o    (c_hit_tag),
    .hit_point_o  (c_hit_point),
    .hit_x_o      (c_hit_x),
    .hit_y_o      (c_hit_y),
    .hit_z_o      (c_hit_z),
    .hit_state_o  (c_hit_state),
    .hit_dist_o   (c_hit_dist),
    .done_valid_o (c_done_valid),
    .done_ready_i (free),
    .done_tag_o   (c_done_tag),
    .done_hits_o  (c_done_hits),
    .done_cycles_o(c_done_cycles),
    .done_points_o(c_done_points),
    .done_stalls_o(c_done_stalls),
    .busy_o       (c_busy),
    .conflicts_o  (c_conflicts)
  );
  assign conflicts_o = c_conflicts;  // a count, not a record: outside the slice

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      full_q    <= 1'b0;
      is_done_q <= 1'b0;
    end else if (free) begin
      full_q    <= c_hit_valid || c_done_valid;
      is_done_q <= c_done_valid;
    end
  end

  always_ff @(posedge clk_i) begin
    if (free && c_hit_valid) begin
      hit_tag_o   <= c_hit_tag;
      hit_point_o <= c_hit_point;
      hit_x_o     <= c_hit_x;
      hit_y_o     <= c_hit_y;
      hit_z_o     <= c_hit_z;
      hit_state_o <= c_hit_state;
      hit_dist_o  <= c_hit_dist;
    end
    if (free && c_done_valid) begin
      done_tag_o    <= c_done_tag;
      done_hits_o   <= c_done_hits;
      done_cycles_o <= c_done_cycles;
      done_points_o <= c_done_points;
      done_stalls_o <= c_done_stalls;
    end
  end

  assign hit_valid_o  = full_q && !is_done_q;
  assign done_valid_o = full_q && is_done_q;
  assign busy_o       = c_busy || full_q;

endmodule
