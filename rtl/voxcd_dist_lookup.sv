// voxcd_dist_lookup: a distance lane's lookup (SB > 2, docs/contract.md "Distance voxmaps"), from the voxel its
// point lands in and its weights to D, the interpolated distance there (voxcd_lane: the transform before it).
//
// The lane reads the eight nodes around the cell from eight parity banks and interpolates them:
//   R3     index        the weights f_i; yzh = (y>>1) + Hy*(z>>1), H_i = (n_i>>1) + 1   (a sparse map's cy + Cy*cz)
//   [ADDR] half-index   hbase = (x>>1) + Hx*yzh            (RankAddr; nx of the R3 slot, Hx kept for R4)
//   R4     rows         per bank p: h_p = hbase + dx_p + Hx*dy_p + HxHy*dz_p (d_p = 1 where the cell's coordinate
//                       is odd and p's parity bit even), row_p = map_base/8 + h_p / NPW, slot h_p % NPW
//   R5     bank words   (this lane's copy of the voxmap memory as 8 bank RAMs, each read at its row)
//   E, F, K (sparse lanes) the cell (voxcd_cell), the sub-cell's rows in its brick (voxcd_brick_rows), the brick's
//                       8 bank words and its node values
//   [READ] nodes        the eight node values, selected (bank p holds the node at offset (cell parity) ^ p)
//   R6     node select (without READ) and the four x interpolations
//   R7     the two y interpolations
//   R8     the z interpolation: D, exact, SB + 3*WB bits signed
// Each interpolation is a*2^WB + (b - a)*f, exact at its width; outputs show the R8 slot. Enables and SharedMap as in
// voxcd_state_lookup: a distance lane shows 8 addresses, one in each parity bank p at [p*MAW +: MAW].
module voxcd_dist_lookup #(
  parameter int unsigned DW    = voxcd_arch_pkg::DW,
  parameter int unsigned MEMW  = voxcd_arch_pkg::MEMW,
  parameter int unsigned MAW   = voxcd_arch_pkg::MAW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
  parameter int unsigned WB    = voxcd_arch_pkg::WB,
  parameter int unsigned Depth = voxcd_arch_pkg::Depth,
  parameter int unsigned BL    = voxcd_arch_pkg::BL,
  parameter bit          SharedMap = 1'b0
) (
  input  logic                  clk_i,
  input  logic                  en_i,        // every register up to R4 advances
  input  logic                  en_mid_i,    // R5, E (and F) advance (sparse lanes; en_i implies it)
  input  logic                  en_out_i,    // K and the registers after it advance (R5 on a dense lane)
  // voxmap write port (shared by all lanes)
  input  logic                  map_we_i,
  input  logic [MAW-1:0]        map_waddr_i,
  input  logic [MEMW-1:0]       map_wdata_i,
  // The transform's result where R3 reads it (FLOOR, or ACC): inside, the voxel {z, y, x}
  // and its fractions {fz, fy, fx}: the top WB bits of each (WB + 3 on a sparse lane)
  input  logic                  inside_i,
  input  logic [3*DW-1:0]       voxel_i,
  input  logic [3*(BL > 0 ? WB + 3 : WB)-1:0] frac_i,
  // the register the y + ny*z product reads (FLOOR, or ACC without it): that job's ny (Cy and whether its map is
  // sparse: sparse lanes)
  input  logic [DW:0]           ny_i,
  input  logic                  sparse_yz_i,
  input  logic [DW:0]           cy_i,
  // R3: the job in R3 (the linear index's nx; Cx and whether its map is sparse)
  input  logic [DW:0]           nx_i,
  input  logic                  sparse_r3_i,
  input  logic [DW:0]           cx_i,
  // the register R4 is computed from (ADDR, or R3 without it): the job's map base and Hx*Hy, and whether its map is
  // sparse
  input  logic [MAW-1:0]        map_base_i,
  input  logic [2*DW:0]         hxy_i,
  input  logic                  sparse_lin_i,
  // R5: its job's bricks (sparse lanes)
  input  logic [MAW-1:0]        brick_base_i,
  input  logic [MAW:0]          brick_units_i,
  // Shared voxmap banks (SharedMap): the R4 word addresses (one per parity bank), whether the point reads them, and the R5 words; the
  // brick stage's likewise, and the K words
  output logic [8*MAW-1:0]  addr_o,
  output logic [8-1:0]      read_o,
  input  logic [8*MEMW-1:0] word_i,
  output logic [8*MAW-1:0]  baddr_o,
  output logic [8-1:0]      bread_o,
  input  logic [8*MEMW-1:0] bword_i,
  // The result: R8
  output logic                  inside_o,
  output logic [SB+3*WB-1:0]    dist_o,
  output logic [3*DW-1:0]       voxel_o
);

  localparam int unsigned IW      = SB + 3 * WB;                            // interpolated distance D
  localparam bit          Sparse  = BL > 0;
  localparam int unsigned FxW     = Sparse ? WB + 3 : WB;                   // fraction bits per axis
  localparam int unsigned FW      = 3 * FxW;
  localparam int unsigned BLW     = Sparse ? BL : 1;                        // the coarse shift (1 unused)
  localparam bit          HasAddr = Depth > voxcd_arch_pkg::RankAddr;
  localparam bit          HasRead = Depth > voxcd_arch_pkg::RankRead;

  logic en_r5;  // R5's enable: en_mid_i on a sparse lane (E follows it), en_out_i on a dense one
  assign en_r5 = Sparse ? en_mid_i : en_out_i;

  logic            inside3_q;
  logic [3*DW-1:0] vox3_q;
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      inside3_q <= inside_i;
      vox3_q    <= voxel_i;
    end
  end

  logic [DW-1:0] y_f, z_f;  // the voxel's y and z where the y + ny*z product reads them
  assign y_f = voxel_i[DW +: DW];
  assign z_f = voxel_i[2*DW +: DW];

  // A sparse map's index products take the coarse cell (the voxel index >> BL) and the coarse extents.
  logic          coarse_yz, coarse_r3, coarse_lin;
  logic [DW-1:0] cy_f, cz_f, cx3;
  assign coarse_yz  = Sparse && sparse_yz_i;
  assign coarse_r3  = Sparse && sparse_r3_i;
  assign coarse_lin = Sparse && sparse_lin_i;
  assign cy_f = y_f >> BLW;
  assign cz_f = z_f >> BLW;
  assign cx3  = vox3_q[DW-1:0] >> BLW;


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
      frac3_q <= frac_i;
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

  logic unused_dist;  // the bank bits of map_base (a distance map starts on a bank boundary) and D's sign copy
  assign unused_dist = ^{map_base_i[2:0], zv[ZIW-1:IW]};

  logic unused_sparse_in;  // the coarse inputs of a dense device's lanes
  assign unused_sparse_in = ^{sparse_yz_i, cy_i, sparse_r3_i, cx_i, sparse_lin_i, cy_f, cz_f, cx3, coarse_yz,
                              coarse_r3, coarse_lin};

endmodule
