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

  localparam bit          Sparse = BL > 0;
  localparam int unsigned FW     = 3 * (SB > 2 ? (Sparse ? WB + 3 : WB) : 1);  // the transform's fraction bits

  // ---- IN, PROD, [SUM], ACC, [FLOOR]: the voxel the point lands in ----
  logic            inside_f;
  logic [3*DW-1:0] vox_f;
  logic [FW-1:0]   frac_f;
  voxcd_transform #(
    .PW(PW), .PF(PF), .MW(MW), .MF(MF), .TW(TW), .DW(DW), .SB(SB), .WB(WB), .Depth(Depth), .BL(BL), .TX(TX)
  ) u_transform (
    .clk_i   (clk_i),
    .en_i    (en_i),
    .point_i (point_i),
    .m_i     (m_i),
    .t_i     (t_i),
    .base_i  (base_i),
    .n_i     (n_i),
    .inside_o(inside_f),
    .voxel_o (vox_f),
    .frac_o  (frac_f)
  );

  // ---- R3 .. the last register: what the voxmap holds there ----
  if (SB == 2) begin : g_states
    voxcd_state_lookup #(
      .DW(DW), .MEMW(MEMW), .MAW(MAW), .SB(SB), .Depth(Depth), .BL(BL), .SharedMap(SharedMap)
    ) u_lookup (
      .clk_i        (clk_i),
      .en_i         (en_i),
      .en_mid_i     (en_mid_i),
      .en_out_i     (en_out_i),
      .map_we_i     (map_we_i),
      .map_waddr_i  (map_waddr_i),
      .map_wdata_i  (map_wdata_i),
      .inside_i     (inside_f),
      .voxel_i      (vox_f),
      .ny_i         (ny_i),
      .sparse_yz_i  (sparse_yz_i),
      .cy_i         (cy_i),
      .nx_i         (nx_i),
      .sparse_r3_i  (sparse_r3_i),
      .cx_i         (cx_i),
      .map_base_i   (map_base_i),
      .sparse_lin_i (sparse_lin_i),
      .brick_base_i (brick_base_i),
      .brick_units_i(brick_units_i),
      .addr_o       (addr_o),
      .read_o       (read_o),
      .word_i       (word_i),
      .baddr_o      (baddr_o),
      .bread_o      (bread_o),
      .bword_i      (bword_i),
      .inside_pre_o (inside_pre_o),
      .state_pre_o  (state_pre_o),
      .inside_o     (inside_o),
      .state_o      (state_o),
      .voxel_o      (voxel_o)
    );
    assign dist_o = '0;  // a 2-bit voxmap has no distance

    logic unused_dist;  // the distance inputs of a 2-bit lane, and the weights it does not keep
    assign unused_dist = ^{hxy_i, frac_f};

  end else begin : g_dist
    voxcd_dist_lookup #(
      .DW(DW), .MEMW(MEMW), .MAW(MAW), .SB(SB), .WB(WB), .Depth(Depth), .BL(BL), .SharedMap(SharedMap)
    ) u_lookup (
      .clk_i        (clk_i),
      .en_i         (en_i),
      .en_mid_i     (en_mid_i),
      .en_out_i     (en_out_i),
      .map_we_i     (map_we_i),
      .map_waddr_i  (map_waddr_i),
      .map_wdata_i  (map_wdata_i),
      .inside_i     (inside_f),
      .voxel_i      (vox_f),
      .frac_i       (frac_f),
      .ny_i         (ny_i),
      .sparse_yz_i  (sparse_yz_i),
      .cy_i         (cy_i),
      .nx_i         (nx_i),
      .sparse_r3_i  (sparse_r3_i),
      .cx_i         (cx_i),
      .map_base_i   (map_base_i),
      .hxy_i        (hxy_i),
      .sparse_lin_i (sparse_lin_i),
      .brick_base_i (brick_base_i),
      .brick_units_i(brick_units_i),
      .addr_o       (addr_o),
      .read_o       (read_o),
      .word_i       (word_i),
      .baddr_o      (baddr_o),
      .bread_o      (bread_o),
      .bword_i      (bword_i),
      .inside_o     (inside_o),
      .dist_o       (dist_o),
      .voxel_o      (voxel_o)
    );
    assign state_o      = 2'd0;  // a distance voxmap has no states
    assign inside_pre_o = 1'b0;
    assign state_pre_o  = 2'd0;
  end

  // Parameter sanity, at elaboration: SB is a width the lane has a data path for, Depth a pipeline it has, and a
  // sparse lane's widths hold its table and bricks (voxcd_transform checks that its index holds the dimensions).
  `VOXCD_ASSERT_INIT(ValueWidthKnown, SB == 2 || SB == 4 || SB == 8 || SB == 16)
  `VOXCD_ASSERT_INIT(DepthInRange, Depth <= voxcd_arch_pkg::MaxDepth)
  `VOXCD_ASSERT_INIT(SparseWidths, !Sparse || (BL >= 2 && BL <= 4 && BL <= DW && MEMW >= 8 && 3 * PW >= 72 &&
                                               (SB == 2 || MF + PF >= WB + 3)))

endmodule
