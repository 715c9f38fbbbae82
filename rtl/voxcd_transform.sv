// voxcd_transform: a lane's transform, from a shell point to the voxel it lands in (docs/contract.md).
//
// Stages (each a register, advancing when en_i is high, holding otherwise); those in [brackets] are there only at a
// Depth that adds them (voxcd_arch_pkg: the stage of rank r is there when Depth > r):
//   [IN]   point                                           (RankIn: the multipliers' input registers; M, one per slot,
//                                                           is the device's register)
//   PROD   products     M[i][j] * p[j]                     (M of the slot before: R0, or IN)
//   [SUM]  sums         M[i][0]*p[0] + t[i], M[i][1]*p[1] + M[i][2]*p[2]     (RankSum; t of the PROD slot)
//   ACC    accumulator  acc_i = sum_j M[i][j]*p[j] + t[i]  (t of the PROD slot without SUM), exact: AccW bits
//   [FLOOR] idx_i = acc_i >>> TF (floor); 0 <= idx_i < n_i at full width     (RankFloor; n of the ACC slot)
// The outputs show FLOOR, or the floor and bounds of ACC without it: whether the point is inside its map, the voxel
// index and (a distance lane) the top fraction bits of each coordinate, its weights. Latency: 2 + Depth's IN, SUM and
// FLOOR cycles from point_i to the outputs. Brick lanes (TX = 1) add the slot's base to three terms that need no
// multiplier (docs/contract.md, "Brick lanes"). Vectors of three coordinates hold x in the low bits: {z, y, x}; the
// matrix is {m22, m21, ..., m00} (entry (i, j) at [(3i + j) * MW +: MW]).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_transform #(
  parameter int unsigned PW    = voxcd_arch_pkg::PW,
  parameter int unsigned PF    = voxcd_arch_pkg::PF,
  parameter int unsigned MW    = voxcd_arch_pkg::MW,
  parameter int unsigned MF    = voxcd_arch_pkg::MF,
  parameter int unsigned TW    = voxcd_arch_pkg::TW,
  parameter int unsigned DW    = voxcd_arch_pkg::DW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
  parameter int unsigned WB    = voxcd_arch_pkg::WB,
  parameter int unsigned Depth = voxcd_arch_pkg::Depth,
  parameter int unsigned BL    = voxcd_arch_pkg::BL,
  parameter int unsigned TX    = voxcd_arch_pkg::TX
) (
  input  logic                  clk_i,
  input  logic                  en_i,      // every register advances
  // R0: the point; the register before PROD (R0, or IN): the matrix of its job
  input  logic [3*PW-1:0]       point_i,
  input  logic [9*MW-1:0]       m_i,
  // PROD: the translation of the job in the products' register; brick lanes (TX = 1): instead the slot's base
  // M o' + t (AccW bits a coordinate, {z, y, x}), and point_i is {k, d}: the point's offset d in its shell brick
  // (2 bits an axis) and the axes k whose coordinate wrapped at PW bits (3 bits)
  input  logic [3*TW-1:0]       t_i,
  input  logic [3*(((MW+PW+2 > TW) ? MW+PW+2 : TW)+1)-1:0] base_i,
  // ACC: the map dimensions of the job in the accumulator's register (the bounds)
  input  logic [3*(DW+1)-1:0]   n_i,
  // FLOOR (or ACC): the point is inside the map, its voxel {z, y, x} and the top fraction bits {fz, fy, fx} of each
  // coordinate (a distance lane's weights: the top WB, a sparse distance lane's the top WB + 3; 0 on a 2-bit lane)
  output logic                  inside_o,
  output logic [3*DW-1:0]       voxel_o,
  output logic [3*(SB > 2 ? (BL > 0 ? WB + 3 : WB) : 1)-1:0] frac_o
);

  localparam int unsigned TF    = MF + PF;
  localparam int unsigned ProdW = MW + PW;
  localparam int unsigned AccW  = ((ProdW + 2 > TW) ? ProdW + 2 : TW) + 1;  // DeviceConfig::acc_width()
  localparam int unsigned IdxW  = AccW - TF;                                // signed voxel index
  localparam int unsigned CmpW  = (IdxW - 1 > DW + 1) ? IdxW - 1 : DW + 1;  // unsigned compare width
  localparam int unsigned FxW   = SB > 2 ? (BL > 0 ? WB + 3 : WB) : 1;     // fraction bits kept per axis
  localparam int unsigned FW    = 3 * FxW;
  localparam bit HasIn    = Depth > voxcd_arch_pkg::RankIn;
  localparam bit HasSum   = Depth > voxcd_arch_pkg::RankSum;
  localparam bit HasFloor = Depth > voxcd_arch_pkg::RankFloor;

  // ---- IN: the multipliers' inputs (the point after the shell banks' rotation; M comes registered) ----
  logic [3*PW-1:0] p_in;
  logic [9*MW-1:0] m_in;
  assign m_in = m_i;
  voxcd_stage #(.Width(3*PW), .Enable(HasIn)) u_in (.clk_i(clk_i), .en_i(en_i), .d_i(point_i), .q_o(p_in));

  // A brick lane's term for matrix entry m and axis j of its point: (d_j * m) << PF, less m << PW where the
  // coordinate wrapped (k_j): d_j * m is 0, m, 2m or 2m + m, so no multiplier (docs/contract.md, "Brick lanes").
  // Modulo 2^AccW: the accumulator's exact value fits it, so its sum wraps to the exact value.
  function automatic logic [AccW-1:0] brick_term(input logic [MW-1:0] m, input logic [1:0] d, input logic k);
    logic [AccW-1:0] m1, sel;
    m1  = AccW'($signed(m));
    sel = (d[1] ? m1 << 1 : '0) + (d[0] ? m1 : '0);
    brick_term = (sel << PF) - (k ? m1 << PW : '0);
  endfunction

  // ---- PROD: products, [SUM], ACC: accumulator ----
  // One block per output coordinate i: its three products and their sum with t_i, each in a register of its own
  // width (no wider vector to slice: simulators keep each in a native word). Brick lanes: the three brick terms and
  // their sum with the slot's base (base_i in place of t_i).
  localparam int unsigned TermW = TX == 1 ? AccW : ProdW;
  logic [AccW-1:0] acc_q [3];
  for (genvar i = 0; i < 3; i++) begin : g_row
    logic [TermW-1:0] px_q, py_q, pz_q;  // M[i][0]*x, M[i][1]*y, M[i][2]*z
    logic [AccW-1:0]  sum_q;
    logic [AccW-1:0]  t_acc;             // t_i, or the slot's base on brick lanes
    if (TX == 1) begin : g_brick
      always_ff @(posedge clk_i) begin
        if (en_i) begin
          px_q <= brick_term(m_in[(3*i+0)*MW +: MW], p_in[0 +: 2], p_in[6]);
          py_q <= brick_term(m_in[(3*i+1)*MW +: MW], p_in[2 +: 2], p_in[7]);
          pz_q <= brick_term(m_in[(3*i+2)*MW +: MW], p_in[4 +: 2], p_in[8]);
        end
      end
      assign t_acc = base_i[i*AccW +: AccW];
    end else begin : g_mul
      always_ff @(posedge clk_i) begin
        if (en_i) begin
          // Signed MW x PW multipliers: the ProdW-bit products are exact.
          px_q <= ProdW'($signed(m_in[(3*i+0)*MW +: MW])) * ProdW'($signed(p_in[0*PW +: PW]));
          py_q <= ProdW'($signed(m_in[(3*i+1)*MW +: MW])) * ProdW'($signed(p_in[1*PW +: PW]));
          pz_q <= ProdW'($signed(m_in[(3*i+2)*MW +: MW])) * ProdW'($signed(p_in[2*PW +: PW]));
        end
      end
      assign t_acc = AccW'($signed(t_i[i*TW +: TW]));
    end
    if (HasSum) begin : g_sum
      // The sum tree's first level: each partial sum fits AccW bits (|t| < 2^(TW-1), |product| < 2^(ProdW-1)).
      logic [AccW-1:0] a_q, b_q;
      always_ff @(posedge clk_i) begin
        if (en_i) begin
          a_q   <= t_acc + AccW'($signed(px_q));
          b_q   <= AccW'($signed(py_q)) + AccW'($signed(pz_q));
          sum_q <= a_q + b_q;
        end
      end
    end else begin : g_no_sum
      always_ff @(posedge clk_i) begin
        if (en_i) sum_q <= t_acc + AccW'($signed(px_q)) + AccW'($signed(py_q)) + AccW'($signed(pz_q));
      end
    end
    assign acc_q[i] = sum_q;
  end

  if (TX == 1) begin : g_brick_unused
    logic unused_t;  // brick lanes add the slot's base, not t, and read only {k, d} of the point
    assign unused_t = ^{t_i, p_in[3*PW-1:9]};
  end else begin : g_mul_unused
    logic unused_base;  // lanes that multiply add t
    assign unused_base = ^base_i;
  end

  // The floor drops each coordinate's TF fraction bits (a distance lane keeps the top of them as its weights).
  logic unused_fraction;
  assign unused_fraction = ^{acc_q[2][TF-1:0], acc_q[1][TF-1:0], acc_q[0][TF-1:0]};

  // ---- Floor and bounds (both kinds of voxmap): at R3, or in FLOOR before it ----
  // The upper bits of a two's complement value are floor(acc / 2^TF).
  logic [IdxW-1:0] idx_x, idx_y, idx_z;
  logic [2:0]      in_axis;
  logic [FW-1:0]   frac_acc;  // {fz, fy, fx}: the top FxW fraction bits of each coordinate (distance lanes)
  assign idx_x = acc_q[0][TF +: IdxW];
  assign idx_y = acc_q[1][TF +: IdxW];
  assign idx_z = acc_q[2][TF +: IdxW];
  assign in_axis[0] = !idx_x[IdxW-1] && (CmpW'(idx_x[IdxW-2:0]) < CmpW'(n_i[0*(DW+1) +: DW+1]));
  assign in_axis[1] = !idx_y[IdxW-1] && (CmpW'(idx_y[IdxW-2:0]) < CmpW'(n_i[1*(DW+1) +: DW+1]));
  assign in_axis[2] = !idx_z[IdxW-1] && (CmpW'(idx_z[IdxW-2:0]) < CmpW'(n_i[2*(DW+1) +: DW+1]));
  if (SB > 2) begin : g_frac_acc
    for (genvar i = 0; i < 3; i++) begin : g_f
      assign frac_acc[i*FxW +: FxW] = acc_q[i][TF - FxW +: FxW];
    end
  end else begin : g_no_frac_acc
    assign frac_acc = '0;
  end

  // What R3 (and the y + ny*z product) sees: the floor's results, registered in FLOOR or straight from ACC.
  voxcd_stage #(.Width(1 + 3*DW + FW), .Enable(HasFloor)) u_floor (
    .clk_i(clk_i), .en_i(en_i),
    .d_i  ({&in_axis, idx_z[DW-1:0], idx_y[DW-1:0], idx_x[DW-1:0], frac_acc}),
    .q_o  ({inside_o, voxel_o, frac_o})
  );

  // The index keeps its sign bit above DW + 1 magnitude bits.
  `VOXCD_ASSERT_INIT(IndexHoldsDims, IdxW >= DW + 1)

endmodule
