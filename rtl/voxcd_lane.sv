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
  input  logic                    clk_i,
  input  logic                    en_i,
  // voxmap write port (shared by all lanes)
  input  logic                    map_we_i,
  input  logic [MAW-1:0]          map_waddr_i,
  input  logic [MEMW-1:0]         map_wdata_i,
  // R0: the point and the matrix of its job
  input  logic [2:0][PW-1:0]      point_i,
  input  logic [2:0][2:0][MW-1:0] m_i,        // m_i[row][col]
  // R1: the translation of the job in R1
  input  logic [2:0][TW-1:0]      t_i,
  // R2: the map dimensions of the job in R2
  input  logic [2:0][DW:0]        n_i,
  // R3: the job in R3
  input  logic [DW:0]             nx_i,
  input  logic [MAW-1:0]          map_base_i,
  // R5: the result
  output logic                    inside_o,
  output logic [1:0]              state_o,
  output logic [2:0][DW-1:0]      voxel_o
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
  logic [2:0][2:0][ProdW-1:0] prod_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int i = 0; i < 3; i++) begin
        for (int j = 0; j < 3; j++) begin
          // Both operands sign-extended to the product width: the low ProdW bits of the product are exact.
          prod_q[i][j] <= {{PW{m_i[i][j][MW-1]}}, m_i[i][j]} * {{MW{point_i[j][PW-1]}}, point_i[j]};
        end
      end
    end
  end

  // ---- R2: accumulator ----
  logic [2:0][AccW-1:0] acc_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int i = 0; i < 3; i++) begin
        acc_q[i] <= {{(AccW - TW){t_i[i][TW-1]}}, t_i[i]}
                  + {{(AccW - ProdW){prod_q[i][0][ProdW-1]}}, prod_q[i][0]}
                  + {{(AccW - ProdW){prod_q[i][1][ProdW-1]}}, prod_q[i][1]}
                  + {{(AccW - ProdW){prod_q[i][2][ProdW-1]}}, prod_q[i][2]};
      end
    end
  end

  // ---- R3: floor, bounds, y + ny*z ----
  logic [2:0][IdxW-1:0] idx;
  logic [2:0]           in_axis;
  always_comb begin
    for (int i = 0; i < 3; i++) begin
      idx[i]     = acc_q[i][AccW-1:TF];  // the upper bits of a two's complement value: floor(acc / 2^TF)
      in_axis[i] = !idx[i][IdxW-1] &&
                   (CmpW'(idx[i][IdxW-2:0]) < CmpW'(n_i[i]));
    end
  end

  logic                 inside3_q;
  logic [2:0][DW-1:0]   vox3_q;
  logic [YzW-1:0]       yz3_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      inside3_q <= &in_axis;
      for (int i = 0; i < 3; i++) vox3_q[i] <= idx[i][DW-1:0];
      yz3_q     <= YzW'(idx[1][DW-1:0]) + YzW'(n_i[1]) * YzW'(idx[2][DW-1:0]);
    end
  end

  // ---- R4: linear index, word address and slot ----
  logic [LinW-1:0] linear;
  assign linear = LinW'(vox3_q[0]) + LinW'(nx_i) * LinW'(yz3_q);

  logic                 inside4_q;
  logic [2:0][DW-1:0]   vox4_q;
  logic [MAW-1:0]       addr4_q;
  logic [SlotW-1:0]     slot4_q;
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
  logic [MEMW-1:0]    word5;
  logic               inside5_q;
  logic [2:0][DW-1:0] vox5_q;
  logic [SlotW-1:0]   slot5_q;

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
