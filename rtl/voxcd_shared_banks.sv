// voxcd_shared_banks: one voxmap in shared banks that every lane reads (a device with BANKS > 0), and the
// arbitration of their read ports between the lanes' requests.
//
// Word w is in bank w % NumB, row w / NumB.
// NumB = BANKS on a 2-bit device; on a distance device each of the 8 parity banks is split BANKS ways (8 * BANKS
// banks), and each lane makes 8 requests, one word of each parity bank. A read stage's slot reads in rounds
// (voxcd_bank_rounds), one in each cycle in which the register after it may advance: R4 (the table port, into R5)
// and on a sparse device the brick stage (the brick port, into K), the brick stage first: the table stage takes a
// round only in a cycle in which the brick stage does not wait (each bank is a voxcd_ram2, one read port for each
// stage). A stage's slot leaves in its last round; before that the register after it takes empty slots (a bank
// conflict cycle each). So a slot with at most r distinct words in any one bank at a stage reaches the hit test
// r - 1 cycles late; a slot of a FIRST job whose hit has been found reads nothing at either stage (it is squashed:
// on a 2-bit device the hit is seen at the hit test, or with READ in the register before it, before the slot behind
// it reads; on a distance device at the hit test, after the slots behind it read in the slot registers between).
// ref/banks.h counts the same (first_window follows it cycle by cycle).
//
// The device writes the banks through its write port while it is idle. Requests: lane r / NPar's, parity bank r % NPar
// on a distance device (read_i, addr_i at R4, the table port; bread_i, baddr_i at the brick stage, the brick port);
// the words each request reads, word_o at R5 and bword_o at K, in the cycles their slot is there. wait_o high: the
// stage has requests left after this cycle's round, and its register holds (the device's enables).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_shared_banks #(
  parameter int unsigned LANES = voxcd_arch_pkg::LANES,
  parameter int unsigned MEMW  = voxcd_arch_pkg::MEMW,
  parameter int unsigned MAW   = voxcd_arch_pkg::MAW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
  parameter int unsigned BANKS = 1,                      // banks a parity bank is split into (BANKS > 0)
  parameter int unsigned Depth = voxcd_arch_pkg::Depth,
  parameter int unsigned BL    = voxcd_arch_pkg::BL,
  parameter int unsigned SeqW  = 1                       // a job's sequence number (voxcd_device)
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  // The device's voxmap write port
  input  logic                                  map_we_i,
  input  logic [MAW-1:0]                        map_waddr_i,
  input  logic [MEMW-1:0]                       map_wdata_i,
  // The device's enables: the registers up to R4 (advance_i), R5 up to the brick stage (advance_mid_i), the ones
  // after (advance_out_i)
  input  logic                                  advance_i,
  input  logic                                  advance_mid_i,
  input  logic                                  advance_out_i,
  // The slots of R4, of the brick stage and of the register before READ (valid, job sequence number, lanes), that
  // register's job (mode and mask: a 2-bit FIRST job's hit there), and the brick stage's job has a sparse map
  input  logic                                  r4_valid_i,
  input  logic [SeqW-1:0]                       r4_seq_i,
  input  logic [LANES-1:0]                      r4_lanes_i,
  input  logic                                  brick_valid_i,
  input  logic [SeqW-1:0]                       brick_seq_i,
  input  logic [LANES-1:0]                      brick_lanes_i,
  input  logic                                  brick_sparse_i,
  input  logic                                  pre_valid_i,
  input  logic [SeqW-1:0]                       pre_seq_i,
  input  logic [LANES-1:0]                      pre_lanes_i,
  input  voxcd_arch_pkg::mode_e                 pre_mode_i,
  input  logic [3:0]                            pre_mask_i,
  input  logic [LANES-1:0]                      inside_pre_i,
  input  logic [2*LANES-1:0]                    state_pre_i,
  // FIRST: the hit test's job whose hit has been found (found_i, found_seq_i), and the last register's slot holds a
  // FIRST job's hit (last_hit_i, of job last_seq_i)
  input  logic                                  found_i,
  input  logic [SeqW-1:0]                       found_seq_i,
  input  logic                                  last_hit_i,
  input  logic [SeqW-1:0]                       last_seq_i,
  // The lanes' requests and the words they read: the table port (R4 -> R5) and the brick port (brick stage -> K)
  input  logic [LANES*(SB > 2 ? 8 : 1)-1:0]     read_i,
  input  logic [LANES*(SB > 2 ? 8 : 1)*MAW-1:0] addr_i,
  output logic [LANES*(SB > 2 ? 8 : 1)*MEMW-1:0] word_o,
  input  logic [LANES*(SB > 2 ? 8 : 1)-1:0]     bread_i,
  input  logic [LANES*(SB > 2 ? 8 : 1)*MAW-1:0] baddr_i,
  output logic [LANES*(SB > 2 ? 8 : 1)*MEMW-1:0] bword_o,
  output logic                                  table_wait_o,
  output logic                                  brick_wait_o,
  // Bank conflict cycles since reset
  output logic [voxcd_arch_pkg::CW-1:0]         conflicts_o
);

  localparam int unsigned CW      = voxcd_arch_pkg::CW;
  localparam bit          Dist    = SB > 2;
  localparam bit          Sparse  = BL > 0;
  localparam bit          HasRead = Depth > voxcd_arch_pkg::RankRead;
  localparam int unsigned NPar    = Dist ? 8 : 1;                  // words a lane reads per point (its requests)
  localparam int unsigned NReq    = LANES * NPar;                  // request r: lane r / NPar, parity bank r % NPar
  localparam int unsigned NumB    = BANKS * NPar;                  // shared banks: word w in bank w % NumB
  localparam int unsigned LgB     = $clog2(NumB);
  localparam int unsigned BRowW   = MAW > LgB ? MAW - LgB : 1;     // rows of one bank (one at NumB = 2^MAW)

  logic                 pre_first_hit;  // the register before READ (2-bit, HasRead) holds a FIRST job's hit
  logic                 r4_squashed;
  logic [NReq-1:0]      table_want;
  logic [NumB-1:0]      table_re;
  logic [NumB*MAW-1:0]  table_word_addr;
  logic [NumB*MEMW-1:0] table_rdata;

  always_comb begin
    pre_first_hit = 1'b0;
    if (HasRead && !Dist && pre_valid_i && pre_mode_i == voxcd_arch_pkg::ModeFirst) begin
      for (int l = 0; l < LANES; l++) begin
        pre_first_hit = pre_first_hit ||
                        (pre_lanes_i[l] && inside_pre_i[l] && pre_mask_i[state_pre_i[2*l +: 2]]);
      end
    end
  end
  assign r4_squashed = (found_i && (found_seq_i == r4_seq_i)) || (last_hit_i && (last_seq_i == r4_seq_i)) ||
                       (pre_first_hit && (pre_seq_i == r4_seq_i));
  for (genvar r = 0; r < NReq; r++) begin : g_want
    assign table_want[r] = r4_valid_i && !r4_squashed && r4_lanes_i[r / NPar] && read_i[r];
  end

  voxcd_bank_rounds #(.NReq(NReq), .NumB(NumB), .MAW(MAW), .MEMW(MEMW)) u_table_rounds (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .want_i     (table_want),
    .addr_i     (addr_i),
    .round_i    (advance_mid_i),
    .leave_i    (advance_i),
    .wait_o     (table_wait_o),
    .re_o       (table_re),
    .word_addr_o(table_word_addr),
    .rdata_i    (table_rdata),
    .word_o     (word_o)
  );

  if (Sparse) begin : g_brick_port
    logic                 brick_squashed;
    logic [NReq-1:0]      brick_want;
    logic [NumB-1:0]      brick_re;
    logic [NumB*MAW-1:0]  brick_word_addr;
    logic [NumB*MEMW-1:0] brick_rdata;
    assign brick_squashed = (found_i && (found_seq_i == brick_seq_i)) ||
                            (last_hit_i && (last_seq_i == brick_seq_i)) ||
                            (pre_first_hit && (pre_seq_i == brick_seq_i));
    for (genvar r = 0; r < NReq; r++) begin : g_want
      assign brick_want[r] = brick_valid_i && !brick_squashed && brick_lanes_i[r / NPar] && bread_i[r];
    end
    voxcd_bank_rounds #(.NReq(NReq), .NumB(NumB), .MAW(MAW), .MEMW(MEMW)) u_brick_rounds (
      .clk_i      (clk_i),
      .rst_ni     (rst_ni),
      .want_i     (brick_want),
      .addr_i     (baddr_i),
      .round_i    (advance_out_i),
      .leave_i    (advance_mid_i),
      .wait_o     (brick_wait_o),
      .re_o       (brick_re),
      .word_addr_o(brick_word_addr),
      .rdata_i    (brick_rdata),
      .word_o     (bword_o)
    );
    for (genvar b = 0; b < NumB; b++) begin : g_bank
      voxcd_ram2 #(
        .Width(MEMW),
        .AddrW(BRowW)
      ) u_map (
        .clk_i    (clk_i),
        .we_i     (map_we_i && ((32'(map_waddr_i) % NumB) == b)),
        .waddr_i  (BRowW'(map_waddr_i >> LgB)),
        .wdata_i  (map_wdata_i),
        .re_a_i   (table_re[b]),
        .raddr_a_i(BRowW'(table_word_addr[MAW*b +: MAW] >> LgB)),
        .rdata_a_o(table_rdata[MEMW*b +: MEMW]),
        .re_b_i   (brick_re[b]),
        .raddr_b_i(BRowW'(brick_word_addr[MAW*b +: MAW] >> LgB)),
        .rdata_b_o(brick_rdata[MEMW*b +: MEMW])
      );
    end
    // The brick port reads only for a brick cell of a sparse map: a slot at the brick stage whose job's map is
    // sparse, and a lane whose cell is a brick (a uniform cell and a dense map read nothing there).
    `VOXCD_ASSERT(BrickReadsOnlyBricks, !(|brick_want) || brick_sparse_i)
    `VOXCD_COVER(CoverBrickPortWaits, brick_wait_o)
  end else begin : g_table_port
    assign brick_wait_o = 1'b0;
    for (genvar l = 0; l < LANES; l++) begin : g_no_bword  // lane by lane: a wide device's is over 8k bits
      assign bword_o[NPar*MEMW*l +: NPar*MEMW] = '0;
    end
    for (genvar b = 0; b < NumB; b++) begin : g_bank
      voxcd_ram #(
        .Width(MEMW),
        .AddrW(BRowW)
      ) u_map (
        .clk_i  (clk_i),
        .we_i   (map_we_i && ((32'(map_waddr_i) % NumB) == b)),
        .waddr_i(BRowW'(map_waddr_i >> LgB)),
        .wdata_i(map_wdata_i),
        .re_i   (table_re[b]),
        .raddr_i(BRowW'(table_word_addr[MAW*b +: MAW] >> LgB)),
        .rdata_o(table_rdata[MEMW*b +: MEMW])
      );
    end
    logic unused_brick;  // a dense device has no brick port
    assign unused_brick = ^{baddr_i, bread_i, brick_valid_i, brick_seq_i, brick_lanes_i, brick_sparse_i};
  end

  `VOXCD_COVER(CoverTablePortWaits, table_wait_o)
  `VOXCD_COVER(CoverSquashedSlotAtTheTableStage, r4_valid_i && r4_squashed)

  // Bank conflict cycles: the registers after the read stages advance while the table stage holds.
  logic [CW-1:0] conflicts_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) conflicts_q <= '0;
    else         conflicts_q <= conflicts_q + CW'(advance_out_i && !advance_i);
  end
  assign conflicts_o = conflicts_q;

endmodule
