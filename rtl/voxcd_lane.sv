// voxcd_lane: one lookup lane, from a shell point to the state of the voxel it lands in.
//
// Stages (each a register, all advancing together when en_i is high, holding otherwise):
//   R1  products    M[i][j] * p[j]                          (p: the point shown in R0, M of the R0 slot)
//   R2  accumulator acc_i = sum_j M[i][j]*p[j] + t[i]        (t of the R1 slot), exact: AccW bits
//   R3  index       idx_i = acc_i >>> TF (floor); inside = 0 <= idx_i < n_i at full width;
//                   yz = y + ny*z                           (n of the R2 slot)
//   R4  address     word = map_base + (x + nx*yz) / (MEMW/2), slot = (x + nx*yz) % (MEMW/2)  (R3 slot's job)
//   R5  voxmap word (this lane's copy of the voxmap memory, read with the R4 address), slot, inside, x, y, z
// Outputs show the R5 slot: inside_o, state_o (bits [2*slot+1 : 2*slot] of the word) and the voxel index.
// Latency: 5 cycles from the point in R0 to its state at R5 (plus the shell RAM read before R0).
// Vectors of three coordinates hold x in the low bits: {z, y, x}; the matrix is {m22, m21, ..., m00} (entry
// (i, j) at [(3i + j) * MW +: MW]). Written in the subset of SystemVerilog that Verilator and yosys both read.
// Each lane owns a copy of the voxmap memory, written through the shared write port, so that every lane can
// read one word in every cycle.
module voxcd_lane #(
  parameter int unsigned PW   = voxcd_pkg::PW,
  parameter int unsigned PF   = voxcd_pkg::PF,
  parameter int unsigned MW   = voxcd_pkg::MW,
  parameter int unsigned MF   = voxcd_pkg::MF,
  parameter int unsigned TW   = voxcd_pkg::TW,
  parameter int unsigned DW   = voxcd_pkg::DW,
  parameter int unsigned MEMW = voxcd_pkg::MEMW,
  parameter int unsigned MAW  = voxcd_pkg::MAW
) (
  input  logic                  clk_i,
  input  logic                  en_i,
  // voxmap write port (shared by all lanes)
  input  logic                  map_we_i,
  input  logic [MAW-1:0]        map_waddr_i,
  input  logic [MEMW-1:0]       map_wdata_i,
  // R0: the point and the matrix of its job
  input  logic [3*PW-1:0]       point_i,
  input  logic [9*MW-1:0]       m_i,
  // R1: the translation of the job in R1
  input  logic [3*TW-1:0]       t_i,
  // R2: the map dimensions of the job in R2
  input  logic [3*(DW+1)-1:0]   n_i,
  // R3: the job in R3
  input  logic [DW:0]           nx_i,
  input  logic [MAW-1:0]        map_base_i,
  // R5: the result
  output logic                  inside_o,
  output logic [1:0]            state_o,
  output logic [3*DW-1:0]       voxel_o
);

  localparam int unsigned TF    = MF + PF;
  localparam int unsigned ProdW = MW + PW;
  localparam int unsigned AccW  = ((ProdW + 2 > TW) ? ProdW + 2 : TW) + 1;  // DeviceConfig::acc_width()
  localparam int unsigned IdxW  = AccW - TF;                                // signed voxel index
  localparam int unsigned CmpW  = (IdxW - 1 > DW + 1) ? IdxW - 1 : DW + 1;  // unsigned compare width
  localparam int unsigned YzW   = 2 * DW + 1;                               // y + ny*z < 2^(2DW)
  localparam int unsigned LinW  = 3 * DW + 2;                               // x + nx*yz < 2^(3DW)
  localparam int unsigned SlotW = $clog2(MEMW / 2) > 0 ? $clog2(MEMW / 2) : 1;
  localparam int unsigned SpwLg = $clog2(MEMW / 2);

  // ---- R1: products ----
  logic [9*ProdW-1:0] prod_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int i = 0; i < 3; i++) begin
        for (int j = 0; j < 3; j++) begin
          // A signed MW x PW multiplier: the ProdW-bit product is exact.
          prod_q[(3*i+j)*ProdW +: ProdW] <=
              ProdW'($signed(m_i[(3*i+j)*MW +: MW])) * ProdW'($signed(point_i[j*PW +: PW]));
        end
      end
    end
  end

  // ---- R2: accumulator ----
  /* verilator lint_off UNUSEDSIGNAL */
  logic [3*AccW-1:0] acc_q;  // the floor drops each coordinate's TF fraction bits
  /* verilator lint_on UNUSEDSIGNAL */
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int i = 0; i < 3; i++) begin
        acc_q[i*AccW +: AccW] <=
              {{(AccW - TW){t_i[i*TW + TW-1]}}, t_i[i*TW +: TW]}
            + {{(AccW - ProdW){prod_q[(3*i+0)*ProdW + ProdW-1]}}, prod_q[(3*i+0)*ProdW +: ProdW]}
            + {{(AccW - ProdW){prod_q[(3*i+1)*ProdW + ProdW-1]}}, prod_q[(3*i+1)*ProdW +: ProdW]}
            + {{(AccW - ProdW){prod_q[(3*i+2)*ProdW + ProdW-1]}}, prod_q[(3*i+2)*ProdW +: ProdW]};
      end
    end
  end

  // ---- R3: floor, bounds, y + ny*z ----
  // The upper bits of a two's complement value are floor(acc / 2^TF).
  logic [IdxW-1:0] idx_x, idx_y, idx_z;
  logic [2:0]      in_axis;
  assign idx_x = acc_q[0*AccW + TF +: IdxW];
  assign idx_y = acc_q[1*AccW + TF +: IdxW];
  assign idx_z = acc_q[2*AccW + TF +: IdxW];
  assign in_axis[0] = !idx_x[IdxW-1] && (CmpW'(idx_x[IdxW-2:0]) < CmpW'(n_i[0*(DW+1) +: DW+1]));
  assign in_axis[1] = !idx_y[IdxW-1] && (CmpW'(idx_y[IdxW-2:0]) < CmpW'(n_i[1*(DW+1) +: DW+1]));
  assign in_axis[2] = !idx_z[IdxW-1] && (CmpW'(idx_z[IdxW-2:0]) < CmpW'(n_i[2*(DW+1) +: DW+1]));

  logic            inside3_q;
  logic [3*DW-1:0] vox3_q;
  logic [YzW-1:0]  yz3_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      inside3_q <= &in_axis;
      vox3_q    <= {idx_z[DW-1:0], idx_y[DW-1:0], idx_x[DW-1:0]};
      yz3_q     <= YzW'(idx_y[DW-1:0]) + YzW'(n_i[1*(DW+1) +: DW+1]) * YzW'(idx_z[DW-1:0]);
    end
  end

  // ---- R4: linear index, word address and slot ----
  logic [LinW-1:0] linear;
  assign linear = LinW'(vox3_q[DW-1:0]) + LinW'(nx_i) * LinW'(yz3_q);

  logic             inside4_q;
  logic [3*DW-1:0]  vox4_q;
  logic [MAW-1:0]   addr4_q;
  logic [SlotW-1:0] slot4_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      inside4_q <= inside3_q;
      vox4_q    <= vox3_q;
      // Inside points of a valid job address loaded words only, so the MAW-bit sum is exact for them.
      addr4_q   <= map_base_i + MAW'(linear >> SpwLg);
      slot4_q   <= SlotW'(linear & LinW'((MEMW / 2) - 1));  // 0 when MEMW = 2
    end
  end

  // ---- R5: voxmap read, state select ----
  logic [MEMW-1:0]  word5;
  logic             inside5_q;
  logic [3*DW-1:0]  vox5_q;
  logic [SlotW-1:0] slot5_q;

  voxcd_ram #(
    .Width(MEMW),
    .AddrW(MAW)
  ) u_map (
    .clk_i  (clk_i),
    .we_i   (map_we_i),
    .waddr_i(map_waddr_i),
    .wdata_i(map_wdata_i),
    .re_i   (en_i),
    .raddr_i(addr4_q),
    .rdata_o(word5)
  );

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      inside5_q <= inside4_q;
      vox5_q    <= vox4_q;
      slot5_q   <= slot4_q;
    end
  end

  assign inside_o = inside5_q;
  assign voxel_o  = vox5_q;
  assign state_o  = word5[2 * slot5_q +: 2];

endmodule
