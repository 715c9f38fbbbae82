// voxcd_state_lookup: a 2-bit lane's lookup (SB = 2, the paper's device), from the voxel its point lands in to the
// state the voxmap holds there (voxcd_lane: the transform before it).
//
// Stages (each a register; those in [brackets] there only at a Depth that adds them, voxcd_arch_pkg):
//   R3     index        inside, the voxel index; yz = y + ny*z    (a sparse map's cy + Cy*cz)
//   [ADDR] linear       x + nx*yz                          (RankAddr; nx of the R3 slot; a sparse map's table index)
//   R4     address      word = map_base + linear / (MEMW/2), slot = linear % (MEMW/2)   (map_base of the slot
//                                                          before: R3, or ADDR; a sparse map's table word and slot)
//   R5     voxmap word  (this lane's copy of the voxmap memory, read with the R4 address), slot, inside, x, y, z
//   E, K   (sparse lanes) the cell (voxcd_cell) and its brick word's address; the brick word and the state
//   [READ] state        bits [2*slot+1 : 2*slot] of the word, inside, x, y, z       (RankRead)
// Outputs show the last register (R5, K or READ); inside_pre_o and state_pre_o the register before READ (R5, or K),
// where the device's shared banks stop reading for a FIRST job's hit. Registers up to R4 advance on en_i, R5 and E
// on en_mid_i (a sparse lane; en_out_i on a dense one), K and the registers after it on en_out_i. With SharedMap the
// lane has no copy of the voxmap: it shows its R4 address and whether it reads (addr_o, read_o) and takes the word
// for R5 (word_i), and likewise its brick address at E and the word for K (baddr_o, bread_o, bword_i).
module voxcd_state_lookup #(
  parameter int unsigned DW    = voxcd_arch_pkg::DW,
  parameter int unsigned MEMW  = voxcd_arch_pkg::MEMW,
  parameter int unsigned MAW   = voxcd_arch_pkg::MAW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
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
  input  logic                  inside_i,
  input  logic [3*DW-1:0]       voxel_i,
  // the register the y + ny*z product reads (FLOOR, or ACC without it): that job's ny (Cy and whether its map is
  // sparse: sparse lanes)
  input  logic [DW:0]           ny_i,
  input  logic                  sparse_yz_i,
  input  logic [DW:0]           cy_i,
  // R3: the job in R3 (the linear index's nx; Cx and whether its map is sparse)
  input  logic [DW:0]           nx_i,
  input  logic                  sparse_r3_i,
  input  logic [DW:0]           cx_i,
  // the register R4 is computed from (ADDR, or R3 without it): the job's map base and whether its map is sparse
  input  logic [MAW-1:0]        map_base_i,
  input  logic                  sparse_lin_i,
  // R5: its job's bricks (sparse lanes)
  input  logic [MAW-1:0]        brick_base_i,
  input  logic [MAW:0]          brick_units_i,
  // Shared voxmap banks (SharedMap): the R4 word address, whether the point reads it, and the R5 word; the
  // brick stage's likewise, and the K word
  output logic [MAW-1:0]    addr_o,
  output logic              read_o,
  input  logic [MEMW-1:0]   word_i,
  output logic [MAW-1:0]    baddr_o,
  output logic              bread_o,
  input  logic [MEMW-1:0]   bword_i,
  // The register before READ: inside and its state
  output logic                  inside_pre_o,
  output logic [1:0]            state_pre_o,
  // The result: R5, K or READ
  output logic                  inside_o,
  output logic [1:0]            state_o,
  output logic [3*DW-1:0]       voxel_o
);

  localparam bit          Sparse  = BL > 0;
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

  logic unused_sparse_in;  // the coarse inputs of a dense device's lanes
  assign unused_sparse_in = ^{sparse_yz_i, cy_i, sparse_r3_i, cx_i, sparse_lin_i, cy_f, cz_f, cx3, coarse_yz,
                              coarse_r3, coarse_lin};

endmodule
