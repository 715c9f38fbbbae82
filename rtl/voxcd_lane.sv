// voxcd_lane: one lookup lane, from a shell point to the voxel it lands in and what the voxmap holds there.
//
// Stages (each a register, all advancing together when en_i is high, holding otherwise); those in [brackets] are
// there only at a Depth that adds them (voxcd_arch_pkg: the stage of rank r is there when Depth > r):
//   [IN]   point                                           (RankIn: the multipliers' input registers; p: the point
//                                                           shown in R0; M, one per slot, is the device's register)
//   PROD   products     M[i][j] * p[j]                     (the multipliers' product registers; M of the slot before:
//                                                           R0, or IN)
//   [SUM]  sums         M[i][0]*p[0] + t[i], M[i][1]*p[1] + M[i][2]*p[2]     (RankSum; t of the PROD slot)
//   ACC    accumulator  acc_i = sum_j M[i][j]*p[j] + t[i]  (t of the PROD slot without SUM), exact: AccW bits
//   [FLOOR] idx_i = acc_i >>> TF (floor); 0 <= idx_i < n_i at full width     (RankFloor; n of the ACC slot)
//   R3     index        inside, the voxel index; yz = y + ny*z    (without FLOOR: the floor and bounds too, n of the
//                                                                  ACC slot; ny of the FLOOR slot with it)
//   [ADDR] linear       x + nx*yz                          (RankAddr; nx of the R3 slot)
//   R4     address      word = map_base + linear / (MEMW/2), slot = linear % (MEMW/2)   (map_base of the slot
//                                                          before: R3, or ADDR; without ADDR also the linear index)
//   R5     voxmap word  (this lane's copy of the voxmap memory, read with the R4 address), slot, inside, x, y, z
//   [READ] state        bits [2*slot+1 : 2*slot] of the word, inside, x, y, z       (RankRead)
// Outputs show the last register (R5, or READ): inside_o, state_o and the voxel index. Latency: 5 + Depth cycles
// from the point in R0 to its state (plus the shell RAM read before R0).
//
// A distance lane (SB > 2, docs/contract.md "Distance voxmaps") reads the eight nodes around the cell from eight
// parity banks and interpolates them; IN, PROD, SUM, ACC and FLOOR are the same, then:
//   R3     index        as above; the weights f_i = acc_i[TF-1 -: WB]; yzh = (y>>1) + Hy*(z>>1), H_i = (n_i>>1) + 1
//   [ADDR] half-index   hbase = (x>>1) + Hx*yzh            (RankAddr; nx of the R3 slot, Hx kept for R4)
//   R4     rows         per bank p: h_p = hbase + dx_p + Hx*dy_p + HxHy*dz_p (d_p = 1 where the cell's coordinate
//                       is odd and p's parity bit even), row_p = map_base/8 + h_p / NPW, slot h_p % NPW
//   R5     bank words   (this lane's copy of the voxmap memory as 8 bank RAMs, each read at its row)
//   [READ] nodes        the eight node values, selected (bank p holds the node at offset (cell parity) ^ p)
//   R6     node select (without READ) and the four x interpolations
//   R7     the two y interpolations
//   R8     the z interpolation: D, exact, SB + 3*WB bits signed
// Each interpolation is a*2^WB + (b - a)*f, exact at its width; outputs show the R8 slot: inside_o, dist_o (D),
// the voxel index, and state_o = 0. Latency: 8 + Depth cycles from the point in R0 to D at R8.
//
// A sparse lane (BL > 0, docs/contract.md "Sparse voxmaps and shells") also looks up sparse maps (sparse_*_i: the
// slot's job has one). Its index products then compute the coarse cell's table index t = cx + Cx*(cy + Cy*cz) (c =
// the voxel index >> BL; Cx, Cy the job's coarse extents), R4 the table word map_base + t / CPW and the code's slot,
// R5 reads the table word (the table port), and three registers (four on a distance lane) follow R5 before READ:
//   E      entry        the cell (voxcd_cell): a uniform cell's state (its node value), or a brick's first word; a
//                       2-bit lane also the brick word's address first + i / (MEMW/2) and slot, i = the voxel's
//                       place in the brick; a dense map's state (node values) selected from the R5 word(s)
//   [F]    rows         (distance) the sub-cell at the brick's level, its weights and the 8 parity-bank rows of its
//                       corner nodes (voxcd_brick_rows)
//   K      brick word   the brick port's read (the brick's word, 8 bank words on a distance lane) for a brick cell
//                       only; the state (node values) selected from it, or E's (F's) for a uniform cell or a dense map
// so a lookup's two dependent reads cost 3 (4) cycles of latency and no throughput; dense maps read at the table
// port as a dense device does and pass through E (F) and K. The lane's copy of the voxmap memory then has two read
// ports (voxcd_ram2). Latency: 8 + Depth (12 + Depth on a distance lane) cycles from R0 to the last register.
//
// Vectors of three coordinates hold x in the low bits: {z, y, x}; the matrix is {m22, m21, ..., m00} (entry
// (i, j) at [(3i + j) * MW +: MW]). Written in the subset of SystemVerilog that Verilator and yosys both read.
// Each lane owns a copy of the voxmap memory, written through the shared write port, so that every lane can
// read one word (eight bank words on a distance device) in every cycle. With SharedMap the lane has no copy: it shows
// its R4 address (a distance lane its 8 addresses, one in each parity bank) and whether it reads (read_o: the point
// is inside; a sparse table word is one address), and the device's shared banks give it the words for R5 (word_i,
// in the R5 slot's cycles); a sparse lane likewise shows its brick addresses (baddr_o, bread_o: a brick cell's, at
// E, or F) and takes the words for K (bword_i). Registers up to R4 advance on en_i; R5 (and E, F) on en_mid_i, which
// the device may raise without en_i (R5 takes a bubble while R4 waits for a bank); K and the registers after it on
// en_out_i, which it may raise without en_mid_i (K takes a bubble while the brick stage waits). Without a sparse
// device R5 advances on en_out_i.
// inside_pre_o and state_pre_o show the register before READ (R5; K on a sparse lane) of a 2-bit lane: the device's
// banks stop reading for a FIRST job at a hit there.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
`ifndef VOXCD_PARAMS_SVH
`include "voxcd_params.svh"
`endif
module voxcd_lane #(
  `VOXCD_LANE_PARAMS,
  parameter bit          SharedMap = 1'b0
) (
  input  logic                  clk_i,
  input  logic                  en_i,        // every register up to R4 advances
  input  logic                  en_mid_i,    // R5, E and F advance (sparse lanes; en_i implies it)
  input  logic                  en_out_i,    // K and the registers after it advance (R5 on a dense lane; en_mid_i
                                             // implies it); all three the same without SharedMap
  // voxmap write port (shared by all lanes)
  input  logic                  map_we_i,
  input  logic [MAW-1:0]        map_waddr_i,
  input  logic [MEMW-1:0]       map_wdata_i,
  // R0: the point; the register before PROD (R0, or IN): the matrix of its job
  input  logic [3*PW-1:0]       point_i,
  input  logic [9*MW-1:0]       m_i,
  // PROD: the translation of the job in the products' register; brick lanes (TX = 1): instead the slot's base
  // M o' + t (AccW bits a coordinate, {z, y, x}) from the device's transform unit, and point_i is {k, d}: the point's
  // offset d in its shell brick (2 bits an axis) and the axes k whose coordinate wrapped at PW bits (3 bits)
  input  logic [3*TW-1:0]       t_i,
  input  logic [3*(((MW+PW+2 > TW) ? MW+PW+2 : TW)+1)-1:0] base_i,
  // ACC: the map dimensions of the job in the accumulator's register (the bounds)
  input  logic [3*(DW+1)-1:0]   n_i,
  // the register the y + ny*z product reads (FLOOR, or ACC without it): that job's ny (Cy and whether its map is
  // sparse: sparse lanes)
  input  logic [DW:0]           ny_i,
  input  logic                  sparse_yz_i,
  input  logic [DW:0]           cy_i,
  // R3: the job in R3 (the linear index's nx; Cx and whether its map is sparse)
  input  logic [DW:0]           nx_i,
  input  logic                  sparse_r3_i,
  input  logic [DW:0]           cx_i,
  // the register R4 is computed from (ADDR, or R3 without it): the job's map base and Hx*Hy (distance lanes only)
  // and whether its map is sparse
  input  logic [MAW-1:0]        map_base_i,
  input  logic [2*DW:0]         hxy_i,
  input  logic                  sparse_lin_i,
  // R5: its job's bricks (sparse lanes)
  input  logic [MAW-1:0]        brick_base_i,
  input  logic [MAW:0]          brick_units_i,
  // Shared voxmap banks (SharedMap): the R4 word addresses (one; a distance lane's eight, one per parity bank p at
  // [p*MAW +: MAW]), whether the point reads them, and the R5 words; the brick stage's likewise, and the K words
  output logic [(SB > 2 ? 8 : 1)*MAW-1:0]  addr_o,
  output logic [(SB > 2 ? 8 : 1)-1:0]      read_o,
  input  logic [(SB > 2 ? 8 : 1)*MEMW-1:0] word_i,
  output logic [(SB > 2 ? 8 : 1)*MAW-1:0]  baddr_o,
  output logic [(SB > 2 ? 8 : 1)-1:0]      bread_o,
  input  logic [(SB > 2 ? 8 : 1)*MEMW-1:0] bword_i,
  // The register before READ (2-bit lanes): inside and its state
  output logic                  inside_pre_o,
  output logic [1:0]            state_pre_o,
  // The result: R5, K or READ (SB = 2), R8 (SB > 2)
  output logic                  inside_o,
  output logic [1:0]            state_o,
  output logic [SB+3*WB-1:0]    dist_o,
  output logic [3*DW-1:0]       voxel_o
);

  localparam int unsigned TF    = MF + PF;
  localparam int unsigned ProdW = MW + PW;
  localparam int unsigned AccW  = ((ProdW + 2 > TW) ? ProdW + 2 : TW) + 1;  // DeviceConfig::acc_width()
  localparam int unsigned IdxW  = AccW - TF;                                // signed voxel index
  localparam int unsigned CmpW  = (IdxW - 1 > DW + 1) ? IdxW - 1 : DW + 1;  // unsigned compare width
  localparam int unsigned IW    = SB + 3 * WB;                              // interpolated distance D
  localparam bit          Sparse = BL > 0;
  // The fraction bits per axis a stage carries: a distance lane's weights (the top WB), a sparse distance lane's the
  // top WB + 3 (a brick of level l takes its weights l bits lower).
  localparam int unsigned FxW   = SB > 2 ? (Sparse ? WB + 3 : WB) : 1;
  localparam int unsigned FW    = 3 * FxW;
  localparam int unsigned BLW   = Sparse ? BL : 1;                          // the coarse shift (1 unused)
  localparam bit HasIn    = Depth > voxcd_arch_pkg::RankIn;
  localparam bit HasSum   = Depth > voxcd_arch_pkg::RankSum;
  localparam bit HasFloor = Depth > voxcd_arch_pkg::RankFloor;
  localparam bit HasAddr  = Depth > voxcd_arch_pkg::RankAddr;
  localparam bit HasRead  = Depth > voxcd_arch_pkg::RankRead;

  logic en_r5;  // R5's enable: en_mid_i on a sparse lane (E follows it), en_out_i on a dense one
  assign en_r5 = Sparse ? en_mid_i : en_out_i;

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
  logic            inside_f;
  logic [3*DW-1:0] vox_f;
  logic [FW-1:0]   frac_f;
  voxcd_stage #(.Width(1 + 3*DW + FW), .Enable(HasFloor)) u_floor (
    .clk_i(clk_i), .en_i(en_i),
    .d_i  ({&in_axis, idx_z[DW-1:0], idx_y[DW-1:0], idx_x[DW-1:0], frac_acc}),
    .q_o  ({inside_f, vox_f, frac_f})
  );

  logic            inside3_q;
  logic [3*DW-1:0] vox3_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      inside3_q <= inside_f;
      vox3_q    <= vox_f;
    end
  end

  logic [DW-1:0] y_f, z_f;  // the voxel's y and z where the y + ny*z product reads them
  assign y_f = vox_f[DW +: DW];
  assign z_f = vox_f[2*DW +: DW];

  // A sparse map's index products take the coarse cell (the voxel index >> BL) and the coarse extents.
  logic          coarse_yz, coarse_r3, coarse_lin;
  logic [DW-1:0] cy_f, cz_f, cx3;
  assign coarse_yz  = Sparse && sparse_yz_i;
  assign coarse_r3  = Sparse && sparse_r3_i;
  assign coarse_lin = Sparse && sparse_lin_i;
  assign cy_f = y_f >> BLW;
  assign cz_f = z_f >> BLW;
  assign cx3  = vox3_q[DW-1:0] >> BLW;

  if (SB == 2) begin : g_states
    // ---- 2-bit voxel states (the paper's device) ----
    localparam int unsigned YzW   = 2 * DW + 1;                               // y + ny*z < 2^(2DW)
    localparam int unsigned LinW  = 3 * DW + 2;                               // x + nx*yz < 2^(3DW)
    localparam int unsigned SlotW = $clog2(MEMW / 2) > 0 ? $clog2(MEMW / 2) : 1;
    localparam int unsigned SpwLg = $clog2(MEMW / 2);
    localparam int unsigned CpwLg = Sparse ? $clog2(MEMW / 4) : 0;           // table codes a word, log2
    localparam int unsigned CslW  = CpwLg > 0 ? CpwLg : 1;

    // ---- R3: y + ny*z (a sparse map's cy + Cy*cz) ----
    logic [YzW-1:0] yz3_q;
    always_ff @(posedge clk_i) begin
      if (en_i) yz3_q <= coarse_yz ? YzW'(cy_f) + YzW'(cy_i) * YzW'(cz_f) : YzW'(y_f) + YzW'(ny_i) * YzW'(z_f);
    end

    // ---- [ADDR]: the linear index (a sparse map's table index); R4: word address and slot ----
    logic [LinW-1:0]  linear;
    logic             inside_l;
    logic [3*DW-1:0]  vox_l;
    voxcd_stage #(.Width(LinW + 1 + 3*DW), .Enable(HasAddr)) u_addr (
      .clk_i(clk_i), .en_i(en_i),
      .d_i  ({coarse_r3 ? LinW'(cx3) + LinW'(cx_i) * LinW'(yz3_q) : LinW'(vox3_q[DW-1:0]) + LinW'(nx_i) * LinW'(yz3_q),
              inside3_q, vox3_q}),
      .q_o  ({linear, inside_l, vox_l})
    );

    logic             inside4_q;
    logic [3*DW-1:0]  vox4_q;
    logic [MAW-1:0]   addr4_q;
    logic [SlotW-1:0] slot4_q;
    logic             sparse4_q;
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        inside4_q <= inside_l;
        vox4_q    <= vox_l;
        sparse4_q <= coarse_lin;
        // Inside points of a valid job address loaded words only, so the MAW-bit sum is exact for them.
        if (coarse_lin) begin
          addr4_q <= map_base_i + MAW'(linear >> CpwLg);
          slot4_q <= SlotW'(linear & LinW'((1 << CpwLg) - 1));
        end else begin
          addr4_q <= map_base_i + MAW'(linear >> SpwLg);
          slot4_q <= SlotW'(linear & LinW'((MEMW / 2) - 1));  // 0 when MEMW = 2
        end
      end
    end

    // ---- R5: voxmap read (the table port), state select ----
    logic [MEMW-1:0]  word5;
    logic             inside5_q;
    logic [3*DW-1:0]  vox5_q;
    logic [SlotW-1:0] slot5_q;
    logic [MEMW-1:0]  wordk;     // the brick port's word (sparse lanes)
    logic [MAW-1:0]   baddr_e;   // the brick word the E slot reads (sparse lanes)
    logic             brick_e;   // and whether it reads one (a brick cell)

    if (SharedMap) begin : g_shared
      assign word5 = word_i;
      assign wordk = bword_i;
      logic unused_write;  // the device writes its shared banks (and reads the bricks at baddr_o)
      assign unused_write = ^{map_we_i, map_waddr_i, map_wdata_i, baddr_e, brick_e};
    end else if (Sparse) begin : g_copy2
      voxcd_ram2 #(
        .Width(MEMW),
        .AddrW(MAW)
      ) u_map (
        .clk_i    (clk_i),
        .we_i     (map_we_i),
        .waddr_i  (map_waddr_i),
        .wdata_i  (map_wdata_i),
        .re_a_i   (en_r5),
        .raddr_a_i(addr4_q),
        .rdata_a_o(word5),
        .re_b_i   (en_out_i && brick_e),  // the brick port reads for a brick cell only
        .raddr_b_i(baddr_e),
        .rdata_b_o(wordk)
      );
      logic unused_word;  // a lane with its own copy reads no shared bank
      assign unused_word = ^{word_i, bword_i};
    end else begin : g_copy
      voxcd_ram #(
        .Width(MEMW),
        .AddrW(MAW)
      ) u_map (
        .clk_i  (clk_i),
        .we_i   (map_we_i),
        .waddr_i(map_waddr_i),
        .wdata_i(map_wdata_i),
        .re_i   (en_out_i),
        .raddr_i(addr4_q),
        .rdata_o(word5)
      );
      assign wordk = '0;
      logic unused_word;  // a lane with its own copy reads no shared bank
      assign unused_word = ^{word_i, bword_i, baddr_e, brick_e};
    end
    assign addr_o = addr4_q;
    assign read_o = inside4_q;

    logic sparse5_q;
    always_ff @(posedge clk_i) begin
      if (en_r5) begin
        inside5_q <= inside4_q;
        vox5_q    <= vox4_q;
        slot5_q   <= slot4_q;
        sparse5_q <= sparse4_q;
      end
    end

    logic [1:0] state5;
    assign state5 = word5[2 * slot5_q +: 2];

    // The register before READ: R5, or K on a sparse lane.
    logic            inside_p;
    logic [3*DW-1:0] vox_p;
    logic [1:0]      state_p;

    if (Sparse) begin : g_sparse
      // ---- E: the cell, and its brick word's address ----
      logic             brick5;
      logic [1:0]       cell_state;
      logic [MAW-1:0]   first5;
      logic [1:0]       unused_level;
      logic             unused_deep;
      voxcd_cell #(.MEMW(MEMW), .MAW(MAW), .SB(SB), .BL(BL)) u_cell (
        .word_i       (word5),
        .slot_i       (CslW'(slot5_q)),
        .brick_base_i (brick_base_i),
        .brick_units_i(brick_units_i),
        .brick_o      (brick5),
        .level_o      (unused_level),
        .state_o      (cell_state),
        .deep_o       (unused_deep),
        .first_o      (first5)
      );
      // The voxel's place in its brick: i = fx + B (fy + B fz), the low BL bits of each index.
      logic [3*BL-1:0] fine5;
      assign fine5 = {vox5_q[2*DW +: BL], vox5_q[DW +: BL], vox5_q[0 +: BL]};

      logic             inside_e_q, brick_e_q;
      logic [3*DW-1:0]  vox_e_q;
      logic [1:0]       state_e_q;
      logic [MAW-1:0]   baddr_e_q;
      logic [SlotW-1:0] bslot_e_q;
      always_ff @(posedge clk_i) begin
        if (en_mid_i) begin
          inside_e_q <= inside5_q;
          vox_e_q    <= vox5_q;
          brick_e_q  <= sparse5_q && inside5_q && brick5;
          state_e_q  <= sparse5_q ? cell_state : state5;
          baddr_e_q  <= first5 + (MAW'(fine5) >> SpwLg);
          bslot_e_q  <= SlotW'(fine5 & (3*BL)'((MEMW / 2) - 1));
        end
      end
      assign baddr_e = baddr_e_q;
      assign brick_e = brick_e_q;
      assign baddr_o = baddr_e_q;
      assign bread_o = brick_e_q;

      // ---- K: the brick word (the brick port), the state ----
      logic             inside_k_q, brick_k_q;
      logic [3*DW-1:0]  vox_k_q;
      logic [1:0]       state_k_q;
      logic [SlotW-1:0] bslot_k_q;
      always_ff @(posedge clk_i) begin
        if (en_out_i) begin
          inside_k_q <= inside_e_q;
          vox_k_q    <= vox_e_q;
          brick_k_q  <= brick_e_q;
          state_k_q  <= state_e_q;
          bslot_k_q  <= bslot_e_q;
        end
      end
      assign inside_p = inside_k_q;
      assign vox_p    = vox_k_q;
      assign state_p  = brick_k_q ? wordk[2 * bslot_k_q +: 2] : state_k_q;
    end else begin : g_dense
      assign inside_p = inside5_q;
      assign vox_p    = vox5_q;
      assign state_p  = state5;
      assign baddr_e  = '0;
      assign brick_e  = 1'b0;
      assign baddr_o  = '0;
      assign bread_o  = 1'b0;
      logic unused_sparse;  // a dense lane reads no table and no brick
      assign unused_sparse = ^{sparse5_q, wordk, brick_base_i, brick_units_i};
    end
    assign inside_pre_o = inside_p;
    assign state_pre_o  = state_p;

    // ---- [READ]: the state in a register of its own ----
    voxcd_stage #(.Width(1 + 3*DW + 2), .Enable(HasRead)) u_read (
      .clk_i(clk_i), .en_i(en_out_i),
      .d_i  ({inside_p, vox_p, state_p}),
      .q_o  ({inside_o, voxel_o, state_o})
    );
    assign dist_o = '0;  // a 2-bit voxmap has no distance

    logic unused_dist;  // the distance inputs of a 2-bit lane, and the weights it does not keep
    assign unused_dist = ^{hxy_i, frac_f};

  end else begin : g_dist
    // ---- Signed node distances in 8 parity banks ----
    localparam int unsigned NPW   = MEMW / SB;                  // node values per word
    localparam int unsigned NpwLg = $clog2(NPW);
    localparam int unsigned NslW  = NpwLg > 0 ? NpwLg : 1;      // a slot within a word
    localparam int unsigned RowW  = MAW > 3 ? MAW - 3 : 1;      // rows of one bank (one row at MAW = 3)
    localparam int unsigned YzhW  = 2 * DW;                     // (y>>1) + Hy*(z>>1) < Hy*Hz <= 2^(2DW)
    localparam int unsigned HW    = 3 * DW + 1;                 // a half-index h < Hx*Hy*Hz
    localparam int unsigned XW    = SB + WB;                    // an x interpolation (between two values * 2^WB)
    localparam int unsigned YW    = SB + 2 * WB;                // a y interpolation
    localparam int unsigned XIW   = XW + 1;                     // b - a and (b - a)*f need one bit more
    localparam int unsigned YIW   = YW + 1;
    localparam int unsigned ZIW   = IW + 1;
    localparam int unsigned CpwLg = Sparse ? $clog2(MEMW / 8) : 0;  // table codes a word, log2 (a sparse map)
    localparam int unsigned CslW  = CpwLg > 0 ? CpwLg : 1;

    // ---- R3: the weights, and (y>>1) + Hy*(z>>1) (a sparse map's cy + Cy*cz) ----
    logic [DW:0]     hy;
    logic [DW-1:0]   y_half, z_half;
    logic [FW-1:0]   frac3_q;  // {fz, fy, fx}
    logic [YzhW-1:0] yzh3_q;
    assign hy     = (ny_i >> 1) + (DW + 1)'(1);
    assign y_half = y_f >> 1;
    assign z_half = z_f >> 1;
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        frac3_q <= frac_f;
        yzh3_q  <= coarse_yz ? YzhW'(cy_f) + YzhW'(cy_i) * YzhW'(cz_f) : YzhW'(y_half) + YzhW'(hy) * YzhW'(z_half);
      end
    end

    // ---- [ADDR]: the half-index of the cell's corner (a sparse map's table index); R4: one row and slot per bank ----
    // Bank p holds the cell's corner node whose coordinate parities are p: on an axis where the cell's index is odd
    // and p's bit is even, that node is one further on, so its half-index is one more.
    logic [DW:0]       hx3, hx;   // Hx of the R3 slot's job, and of the job R4 is computed for
    logic [HW-1:0]     hbase3, hbase;
    logic              inside_l;
    logic [3*DW-1:0]   vox_l;
    logic [FW-1:0]     frac_l;
    assign hx3    = (nx_i >> 1) + (DW + 1)'(1);
    logic [DW-1:0] x_half;
    assign x_half = vox3_q[DW-1:0] >> 1;
    assign hbase3 = coarse_r3 ? HW'(cx3) + HW'(cx_i) * HW'(yzh3_q) : HW'(x_half) + HW'(hx3) * HW'(yzh3_q);
    voxcd_stage #(.Width(DW + 1 + HW + 1 + 3*DW + FW), .Enable(HasAddr)) u_addr (
      .clk_i(clk_i), .en_i(en_i),
      .d_i  ({hx3, hbase3, inside3_q, vox3_q, frac3_q}),
      .q_o  ({hx, hbase, inside_l, vox_l, frac_l})
    );

    logic [2:0]        par_l;   // parities of the cell's x, y, z
    logic [8*RowW-1:0] row;
    logic [8*NslW-1:0] slot;
    logic [MAW-1:0]    table_word;  // a sparse map's table word
    assign par_l      = {vox_l[2*DW], vox_l[DW], vox_l[0]};
    assign table_word = map_base_i + MAW'(hbase >> CpwLg);
    for (genvar p = 0; p < 8; p++) begin : g_row
      logic [2:0]    step;  // the half-index steps of bank p's node: x, y, z
      logic [HW-1:0] h;
      assign step = par_l & ~3'(p);
      assign h    = hbase + HW'(step[0]) + (step[1] ? HW'(hx) : HW'(0)) + (step[2] ? HW'(hxy_i) : HW'(0));
      // Inside points of a valid job read loaded words only, so the RowW-bit sum is exact for them. A sparse map's
      // table word is in bank table_word % 8: every bank reads its row, the lane takes that bank's word.
      assign row[p*RowW +: RowW]  = coarse_lin ? RowW'(table_word >> 3) : RowW'(map_base_i >> 3) + RowW'(h >> NpwLg);
      assign slot[p*NslW +: NslW] = NslW'(h & HW'(NPW - 1));  // 0 when a word holds one node
    end

    logic              inside4_q;
    logic [3*DW-1:0]   vox4_q;
    logic [FW-1:0]     frac4_q;
    logic [8*RowW-1:0] row4_q;
    logic [8*NslW-1:0] slot4_q;
    logic              sparse4_q;
    logic [2:0]        tbank4_q;   // a sparse map's table word: its bank and code slot
    logic [CslW-1:0]   tslot4_q;
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        inside4_q <= inside_l;
        vox4_q    <= vox_l;
        frac4_q   <= frac_l;
        row4_q    <= row;
        slot4_q   <= slot;
        sparse4_q <= coarse_lin;
        tbank4_q  <= table_word[2:0];
        tslot4_q  <= CslW'(hbase & HW'((1 << CpwLg) - 1));
      end
    end

    // ---- R5: the 8 bank words (word w of the voxmap is row w >> 3 of bank w & 7) ----
    logic [8*MEMW-1:0] word5, wordk;
    logic [8*RowW-1:0] brow_f;  // the brick rows the F slot reads (sparse lanes)
    logic              brick_f; // and whether it reads them (a brick cell)
    logic              inside5_q;
    logic [3*DW-1:0]   vox5_q;
    logic [FW-1:0]     frac5_q;
    logic [8*NslW-1:0] slot5_q;
    logic              sparse5_q;
    logic [2:0]        tbank5_q;
    logic [CslW-1:0]   tslot5_q;
    for (genvar p = 0; p < 8; p++) begin : g_addr_out
      // Word (map_base/8 + h_p/NPW)*8 + p: the shared banks' address of bank p's node.
      assign addr_o[p*MAW +: MAW] = MAW'({row4_q[p*RowW +: RowW], 3'(p)});
      assign read_o[p]            = inside4_q && (!sparse4_q || tbank4_q == 3'(p));
    end
    if (SharedMap) begin : g_shared
      assign word5 = word_i;
      assign wordk = bword_i;
      logic unused_write;  // the device writes its shared banks (and reads the bricks at baddr_o)
      assign unused_write = ^{map_we_i, map_waddr_i, map_wdata_i, brow_f, brick_f};
    end else begin : g_copy
      for (genvar p = 0; p < 8; p++) begin : g_bank
        if (Sparse) begin : g_two_ports
          voxcd_ram2 #(
            .Width(MEMW),
            .AddrW(RowW)
          ) u_bank (
            .clk_i    (clk_i),
            .we_i     (map_we_i && (map_waddr_i[2:0] == 3'(p))),
            .waddr_i  (RowW'(map_waddr_i >> 3)),
            .wdata_i  (map_wdata_i),
            .re_a_i   (en_r5),
            .raddr_a_i(row4_q[p*RowW +: RowW]),
            .rdata_a_o(word5[p*MEMW +: MEMW]),
            .re_b_i   (en_out_i && brick_f),  // for a brick cell only
            .raddr_b_i(brow_f[p*RowW +: RowW]),
            .rdata_b_o(wordk[p*MEMW +: MEMW])
          );
        end else begin : g_one_port
          voxcd_ram #(
            .Width(MEMW),
            .AddrW(RowW)
          ) u_bank (
            .clk_i  (clk_i),
            .we_i   (map_we_i && (map_waddr_i[2:0] == 3'(p))),
            .waddr_i(RowW'(map_waddr_i >> 3)),
            .wdata_i(map_wdata_i),
            .re_i   (en_out_i),
            .raddr_i(row4_q[p*RowW +: RowW]),
            .rdata_o(word5[p*MEMW +: MEMW])
          );
          assign wordk[p*MEMW +: MEMW] = '0;
        end
      end
      logic unused_word;  // a lane with its own copy reads no shared bank
      assign unused_word = ^{word_i, bword_i};
    end
    always_ff @(posedge clk_i) begin
      if (en_r5) begin
        inside5_q <= inside4_q;
        vox5_q    <= vox4_q;
        frac5_q   <= frac4_q;
        slot5_q   <= slot4_q;
        sparse5_q <= sparse4_q;
        tbank5_q  <= tbank4_q;
        tslot5_q  <= tslot4_q;
      end
    end

    // ---- Node select (into READ, or into R6 with the x interpolations; on a sparse lane into E) ----
    logic [8*SB-1:0] bank_val;  // the value bank p read
    logic [8*SB-1:0] q5;        // q(dx, dy, dz) at [(dx | dy<<1 | dz<<2)*SB +: SB]
    logic [2:0]      par5;
    assign par5 = {vox5_q[2*DW], vox5_q[DW], vox5_q[0]};
    for (genvar p = 0; p < 8; p++) begin : g_val
      assign bank_val[p*SB +: SB] = word5[p*MEMW + SB*slot5_q[p*NslW +: NslW] +: SB];
    end
    for (genvar c = 0; c < 8; c++) begin : g_node
      // The node at offset c from the cell's corner has parities par5 ^ c.
      logic [2:0] bank;
      assign bank           = 3'(c) ^ par5;
      assign q5[c*SB +: SB] = bank_val[bank*SB +: SB];
    end

    // The register before READ: R5 (its node values selected), or K on a sparse lane.
    logic [8*SB-1:0] q_p;
    logic            inside_p;
    logic [3*DW-1:0] vox_p;
    logic [3*WB-1:0] frac_p;

    if (Sparse) begin : g_sparse
      // ---- E: the cell; a dense map's node values, a uniform cell's value at every node ----
      logic            brick5, deep5;
      logic [1:0]      level5;
      logic [MAW-1:0]  first5;
      logic [1:0]      unused_state;
      voxcd_cell #(.MEMW(MEMW), .MAW(MAW), .SB(SB), .BL(BL)) u_cell (
        .word_i       (word5[MEMW*tbank5_q +: MEMW]),
        .slot_i       (tslot5_q),
        .brick_base_i (brick_base_i),
        .brick_units_i(brick_units_i),
        .brick_o      (brick5),
        .level_o      (level5),
        .state_o      (unused_state),
        .deep_o       (deep5),
        .first_o      (first5)
      );
      localparam logic [SB-1:0] QMax = {1'b0, {(SB-1){1'b1}}}, QMin = {1'b1, {(SB-1){1'b0}}};

      logic            inside_e_q, brick_e_q;
      logic [3*DW-1:0] vox_e_q;
      logic [FW-1:0]   frac_e_q;
      logic [1:0]      level_e_q;
      logic [MAW-1:0]  first_e_q;
      logic [8*SB-1:0] q_e_q;
      always_ff @(posedge clk_i) begin
        if (en_mid_i) begin
          inside_e_q <= inside5_q;
          vox_e_q    <= vox5_q;
          frac_e_q   <= frac5_q;
          brick_e_q  <= sparse5_q && inside5_q && brick5;
          level_e_q  <= level5;
          first_e_q  <= first5;
          q_e_q      <= sparse5_q ? {8{deep5 ? QMin : QMax}} : q5;
        end
      end

      // ---- F: the sub-cell's rows in the brick, and the weights ----
      logic [8*RowW-1:0] brow;
      logic [8*NslW-1:0] bslot;
      logic [2:0]        bpar;
      logic [3*WB-1:0]   bweight, dweight;
      voxcd_brick_rows #(.MEMW(MEMW), .MAW(MAW), .SB(SB), .WB(WB), .BL(BL)) u_rows (
        .fine_i  ({vox_e_q[2*DW +: BL], vox_e_q[DW +: BL], vox_e_q[0 +: BL]}),
        .frac_i  (frac_e_q),
        .level_i (level_e_q),
        .first_i (first_e_q),
        .row_o   (brow),
        .slot_o  (bslot),
        .par_o   (bpar),
        .weight_o(bweight)
      );
      // A dense map's (and a uniform cell's) weights: the top WB fraction bits.
      for (genvar i = 0; i < 3; i++) begin : g_w
        assign dweight[i*WB +: WB] = frac_e_q[i*FxW + 3 +: WB];
      end

      logic              inside_f_q, brick_f_q;
      logic [3*DW-1:0]   vox_f_q;
      logic [8*RowW-1:0] brow_f_q;
      logic [8*NslW-1:0] bslot_f_q;
      logic [2:0]        bpar_f_q;
      logic [3*WB-1:0]   w_f_q;
      logic [8*SB-1:0]   q_f_q;
      always_ff @(posedge clk_i) begin
        if (en_mid_i) begin
          inside_f_q <= inside_e_q;
          vox_f_q    <= vox_e_q;
          brick_f_q  <= brick_e_q;
          brow_f_q   <= brow;
          bslot_f_q  <= bslot;
          bpar_f_q   <= bpar;
          w_f_q      <= brick_e_q ? bweight : dweight;
          q_f_q      <= q_e_q;
        end
      end
      assign brow_f  = brow_f_q;
      assign brick_f = brick_f_q;
      for (genvar p = 0; p < 8; p++) begin : g_baddr
        assign baddr_o[p*MAW +: MAW] = MAW'({brow_f_q[p*RowW +: RowW], 3'(p)});
      end
      assign bread_o = {8{brick_f_q}};

      // ---- K: the brick's 8 bank words (the brick port), its node values ----
      logic              inside_k_q, brick_k_q;
      logic [3*DW-1:0]   vox_k_q;
      logic [8*NslW-1:0] bslot_k_q;
      logic [2:0]        bpar_k_q;
      logic [3*WB-1:0]   w_k_q;
      logic [8*SB-1:0]   q_k_q;
      always_ff @(posedge clk_i) begin
        if (en_out_i) begin
          inside_k_q <= inside_f_q;
          vox_k_q    <= vox_f_q;
          brick_k_q  <= brick_f_q;
          bslot_k_q  <= bslot_f_q;
          bpar_k_q   <= bpar_f_q;
          w_k_q      <= w_f_q;
          q_k_q      <= q_f_q;
        end
      end
      logic [8*SB-1:0] bval_k, qsel_k;
      for (genvar p = 0; p < 8; p++) begin : g_bval
        assign bval_k[p*SB +: SB] = wordk[p*MEMW + SB*bslot_k_q[p*NslW +: NslW] +: SB];
      end
      for (genvar c = 0; c < 8; c++) begin : g_bnode
        logic [2:0] bank;
        assign bank               = 3'(c) ^ bpar_k_q;
        assign qsel_k[c*SB +: SB] = bval_k[bank*SB +: SB];
      end
      assign q_p      = brick_k_q ? qsel_k : q_k_q;
      assign inside_p = inside_k_q;
      assign vox_p    = vox_k_q;
      assign frac_p   = w_k_q;
    end else begin : g_dense
      assign q_p      = q5;
      assign inside_p = inside5_q;
      assign vox_p    = vox5_q;
      assign frac_p   = frac5_q[3*WB-1:0];
      assign brow_f   = '0;
      assign brick_f  = 1'b0;
      assign baddr_o  = '0;
      assign bread_o  = '0;
      logic unused_sparse;  // a dense lane reads no table and no brick
      assign unused_sparse = ^{sparse5_q, tbank5_q, tslot5_q, wordk, brow_f, brick_f, brick_base_i, brick_units_i};
    end

    logic [8*SB-1:0] q;
    logic            inside_r;
    logic [3*DW-1:0] vox_r;
    logic [3*WB-1:0] frac_r;
    voxcd_stage #(.Width(8*SB + 1 + 3*DW + 3*WB), .Enable(HasRead)) u_read (
      .clk_i(clk_i), .en_i(en_out_i),
      .d_i  ({q_p, inside_p, vox_p, frac_p}),
      .q_o  ({q, inside_r, vox_r, frac_r})
    );

    // ---- R6: x interpolation ----
    logic [4*XW-1:0] lx;  // at (dy | dz<<1): between q(0, dy, dz) and q(1, dy, dz)
    for (genvar k = 0; k < 4; k++) begin : g_x
      logic signed [XIW-1:0] a, b, f, v;
      assign a = XIW'($signed(q[(2*k)*SB +: SB]));
      assign b = XIW'($signed(q[(2*k+1)*SB +: SB]));
      assign f = $signed(XIW'(frac_r[0*WB +: WB]));
      assign v = (a <<< WB) + (b - a) * f;  // exact: |b - a| < 2^SB, f < 2^WB
      assign lx[k*XW +: XW] = v[XW-1:0];    // exact: between a and b times 2^WB
      logic unused_sign;
      assign unused_sign = v[XIW-1];
    end

    logic            inside6_q;
    logic [3*DW-1:0] vox6_q;
    logic [2*WB-1:0] frac6_q;  // {fz, fy}
    logic [4*XW-1:0] lx6_q;
    always_ff @(posedge clk_i) begin
      if (en_out_i) begin
        inside6_q <= inside_r;
        vox6_q    <= vox_r;
        frac6_q   <= frac_r[WB +: 2*WB];
        lx6_q     <= lx;
      end
    end

    // ---- R7: y interpolation ----
    logic [2*YW-1:0] ly;  // at dz: between the x interpolations at dy = 0 and dy = 1
    for (genvar k = 0; k < 2; k++) begin : g_y
      logic signed [YIW-1:0] a, b, f, v;
      assign a = YIW'($signed(lx6_q[(2*k)*XW +: XW]));
      assign b = YIW'($signed(lx6_q[(2*k+1)*XW +: XW]));
      assign f = $signed(YIW'(frac6_q[0*WB +: WB]));
      assign v = (a <<< WB) + (b - a) * f;
      assign ly[k*YW +: YW] = v[YW-1:0];
      logic unused_sign;
      assign unused_sign = v[YIW-1];
    end

    logic            inside7_q;
    logic [3*DW-1:0] vox7_q;
    logic [WB-1:0]   fz7_q;
    logic [2*YW-1:0] ly7_q;
    always_ff @(posedge clk_i) begin
      if (en_out_i) begin
        inside7_q <= inside6_q;
        vox7_q    <= vox6_q;
        fz7_q     <= frac6_q[WB +: WB];
        ly7_q     <= ly;
      end
    end

    // ---- R8: z interpolation, D ----
    logic signed [ZIW-1:0] za, zb, zf, zv;
    assign za = ZIW'($signed(ly7_q[0*YW +: YW]));
    assign zb = ZIW'($signed(ly7_q[1*YW +: YW]));
    assign zf = $signed(ZIW'(fz7_q));
    assign zv = (za <<< WB) + (zb - za) * zf;

    logic            inside8_q;
    logic [3*DW-1:0] vox8_q;
    logic [IW-1:0]   dist8_q;
    always_ff @(posedge clk_i) begin
      if (en_out_i) begin
        inside8_q <= inside7_q;
        vox8_q    <= vox7_q;
        dist8_q   <= zv[IW-1:0];
      end
    end

    assign inside_o     = inside8_q;
    assign voxel_o      = vox8_q;
    assign dist_o       = dist8_q;
    assign state_o      = 2'd0;  // a distance voxmap has no states
    assign inside_pre_o = 1'b0;
    assign state_pre_o  = 2'd0;

    logic unused_dist;  // the bank bits of map_base (a distance map starts on a bank boundary) and D's sign copy
    assign unused_dist = ^{map_base_i[2:0], zv[ZIW-1:IW]};

  end

  logic unused_sparse_in;  // the coarse inputs of a dense device's lanes
  assign unused_sparse_in = ^{sparse_yz_i, cy_i, sparse_r3_i, cx_i, sparse_lin_i, cy_f, cz_f, cx3, coarse_yz,
                              coarse_r3, coarse_lin};

  // Parameter sanity, at elaboration: the index keeps its sign bit above DW + 1 magnitude bits, SB is a width the
  // lane has a data path for, Depth a pipeline it has, and a sparse lane's widths hold its table and bricks.
  `VOXCD_ASSERT_INIT(IndexHoldsDims, IdxW >= DW + 1)
  `VOXCD_ASSERT_INIT(ValueWidthKnown, SB == 2 || SB == 4 || SB == 8 || SB == 16)
  `VOXCD_ASSERT_INIT(DepthInRange, Depth <= voxcd_arch_pkg::MaxDepth)
  `VOXCD_ASSERT_INIT(SparseWidths, !Sparse || (BL >= 2 && BL <= 4 && BL <= DW && MEMW >= 8 && 3 * PW >= 72 &&
                                               (SB == 2 || MF + PF >= WB + 3)))

endmodule
