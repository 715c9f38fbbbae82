// voxcd_bank_rounds: the rounds in which one read stage's requests read shared voxmap banks (docs/contract.md, "Shared
// voxmap banks"; docs/hardware.md). Word w is in bank w % NumB, row w / NumB.
//
// Contract: the stage register holds a slot whose requests want_i ask for the words addr_i. In each cycle with
// round_i high (the register after the stage may advance) the banks read one round: each bank reads the word of the
// lowest waiting request that falls in it (re_o, row_o), and every waiting request that wants that word takes it.
// wait_o: requests still wait after this cycle's round, so the stage register holds (the caller's enable of it is
// round_i && !wait_o, which it gives back as leave_i) and the register after it takes an empty slot. The words of
// the slot that left, for as long as the register after the stage holds it: word_o (request r at [r*MEMW +: MEMW]);
// a word read in an earlier round is caught the cycle after its read and held; the last round's words stay on the
// banks' outputs (rdata_i), which read only when round_i is high, so only when that register advances. Latency: the
// words of a slot whose requests fall in r distinct words of one bank reach the next register r - 1 cycles late.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_bank_rounds #(
  parameter int unsigned NReq = 4,   // requests: one per lane (eight per lane on a distance device)
  parameter int unsigned NumB = 4,   // banks, a power of two
  parameter int unsigned MAW  = 18,
  parameter int unsigned MEMW = 64
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic [NReq-1:0]      want_i,   // requests of the stage's slot that read
  input  logic [NReq*MAW-1:0]  addr_i,   // the word each asks for
  input  logic                 round_i,  // a round happens (the register after the stage advances)
  input  logic                 leave_i,  // the stage's slot leaves: round_i && !wait_o
  output logic                 wait_o,
  output logic [NumB-1:0]      re_o,     // bank b reads row row_o[b] this cycle
  output logic [NumB*MAW-1:0]  word_addr_o,  // the word bank b reads (its row: the address / NumB)
  input  logic [NumB*MEMW-1:0] rdata_i,  // each bank's output register
  output logic [NReq*MEMW-1:0] word_o    // the words of the slot in the register after the stage
);

  localparam int unsigned LgB   = $clog2(NumB);
  localparam int unsigned BankW = LgB > 0 ? LgB : 1;

  logic [NReq-1:0]       served_d, served_q;  // requests of the stage's slot served in earlier rounds
  logic [NReq-1:0]       waiting, granted;
  logic [NumB-1:0]       map_re;
  logic [NumB*MAW-1:0]   map_word;            // the word each bank reads this round
  logic [NReq-1:0]       early_read_q;        // requests whose word the banks read last cycle, in an earlier round
  logic [NReq*MEMW-1:0]  early_q, early_now, held_q;
  logic [NReq-1:0]       last_round_q;        // requests of the next register's slot read in its last round
  logic [NReq*BankW-1:0] next_bank_q;         // and the bank that read each

  assign waiting = want_i & ~served_q;

  // Each bank's word this round: the lowest waiting request's that falls in it.
  always_comb begin
    map_re   = '0;
    map_word = '0;
    for (int r = NReq - 1; r >= 0; r--) begin
      if (waiting[r]) begin
        map_re[32'(addr_i[MAW*r +: BankW]) % NumB] = 1'b1;
        map_word[MAW*(32'(addr_i[MAW*r +: BankW]) % NumB) +: MAW] = addr_i[MAW*r +: MAW];
      end
    end
    for (int r = 0; r < NReq; r++) begin
      granted[r] = waiting[r] && (map_word[MAW*(32'(addr_i[MAW*r +: BankW]) % NumB) +: MAW] == addr_i[MAW*r +: MAW]);
    end
  end
  assign wait_o      = |(waiting & ~granted);
  assign re_o        = round_i ? map_re : '0;
  assign word_addr_o = map_word;

  always_comb begin
    served_d = served_q;
    if (leave_i)      served_d = '0;
    else if (round_i) served_d = served_q | granted;
    for (int r = 0; r < NReq; r++) begin
      early_now[MEMW*r +: MEMW] = early_read_q[r]
          ? rdata_i[MEMW*(32'(addr_i[MAW*r +: BankW]) % NumB) +: MEMW] : early_q[MEMW*r +: MEMW];
      word_o[MEMW*r +: MEMW] = last_round_q[r]
          ? rdata_i[MEMW*next_bank_q[BankW*r +: BankW] +: MEMW] : held_q[MEMW*r +: MEMW];
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      served_q     <= '0;
      early_read_q <= '0;
      last_round_q <= '0;
    end else begin
      served_q     <= served_d;
      early_read_q <= (round_i && !leave_i) ? granted : '0;
      if (round_i) last_round_q <= leave_i ? granted : '0;
    end
  end
  // Words: no reset (read only for requests that read).
  always_ff @(posedge clk_i) begin
    early_q <= early_now;
    if (leave_i) begin
      held_q <= early_now;
      for (int r = 0; r < NReq; r++) next_bank_q[BankW*r +: BankW] <= BankW'(32'(addr_i[MAW*r +: BankW]) % NumB);
    end
  end

  `VOXCD_ASSERT_INIT(BanksPowerOfTwo, (NumB & (NumB - 1)) == 0 && NumB >= 1)
  // The stage's slot leaves only in a round, and only when no request still waits.
  `VOXCD_ASSERT(LeaveOnlyInALastRound, !leave_i || (round_i && !wait_o))

  // Functional coverage: slots read in 1, 2, 3 and 4 or more rounds (bank conflicts of each multiplicity), and a
  // round in which one bank's read serves several requests (the same word).
  logic [2:0] cov_rounds_q;  // rounds the stage's slot has taken before this one (saturating at 7; covers only)
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)                            cov_rounds_q <= '0;
    else if (leave_i)                       cov_rounds_q <= '0;
    else if (round_i && cov_rounds_q != 3'd7)   cov_rounds_q <= cov_rounds_q + 3'd1;
  end
  `VOXCD_COVER(CoverSlotReadInOneRound, leave_i && (|want_i) && cov_rounds_q == 3'd0)
  `VOXCD_COVER(CoverSlotReadInTwoRounds, leave_i && cov_rounds_q == 3'd1)
  `VOXCD_COVER(CoverSlotReadInThreeRounds, leave_i && cov_rounds_q == 3'd2)
  `VOXCD_COVER(CoverSlotReadInFourOrMoreRounds, leave_i && cov_rounds_q >= 3'd3)
  `VOXCD_COVER(CoverOneReadServesSeveral, round_i && $countones(granted) > $countones(map_re))

endmodule
