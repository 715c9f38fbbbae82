// voxcd_hit_stage: the device's hit test and record emission at its last slot register (R5, R8 on a distance device;
// K, or the registers after it, on a sparse one), and the output slice the records wait in (docs/hardware.md).
//
// The last register's slot (its bookkeeping: valid, job sequence number, the job's last slot, the point index of
// lane 0, the lanes holding a point) and its job's hit-test fields (tag, mode, mask, threshold, and the stamps of the
// cycle and stall accounting) come in with the lanes' results. Each cycle it emits at most one record into the output
// slice (voxcd_skid: an output register and a skid register): ALL a hit record per hit lane, lowest lane first, FIRST
// the slot's lowest hit, COUNT none; then, where the slot ends its job (or FIRST hit), the completion record
// {tag, hits, cycles, points, stalls}. out_ready_o is the slice's registered ready (no path from *_ready_i);
// slot_busy_o says the slot has more than this cycle's record to emit, so the device holds its pipeline
// (advance_out_i = out_ready_o && !slot_busy_o). FIRST: once the job's hit has been found (found_o, found_seq_o) its
// later slots are squashed here, and first_stop_o tells the issue stage to stop the job. Latency: a record is on the
// stream ports in the cycle after its emission.
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
module voxcd_hit_stage #(
  parameter int unsigned LANES = voxcd_arch_pkg::LANES,
  parameter int unsigned TAGW  = voxcd_arch_pkg::TAGW,
  parameter int unsigned SAW   = voxcd_arch_pkg::SAW,
  parameter int unsigned DW    = voxcd_arch_pkg::DW,
  parameter int unsigned SB    = voxcd_arch_pkg::SB,
  parameter int unsigned WB    = voxcd_arch_pkg::WB,
  parameter int unsigned BL    = voxcd_arch_pkg::BL,
  parameter int unsigned SeqW  = 1                       // a job's sequence number (voxcd_device)
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,
  // The device's enable of the last register (and the registers before it up to K)
  input  logic                                  advance_out_i,
  // The last register's slot
  input  logic                                  slot_valid_i,
  input  logic [SeqW-1:0]                       slot_seq_i,
  input  logic                                  slot_last_i,
  input  logic [(BL > 0 ? SAW + 6 : SAW):0]     slot_k_i,
  input  logic [LANES-1:0]                      slot_lanes_i,
  // Its job's hit-test fields: the threshold (distance devices; else unread), whether it was accepted after the
  // previous completion record (fresh_i), and the cycle and the stall count at its acceptance
  input  logic [TAGW-1:0]                       tag_i,
  input  voxcd_arch_pkg::mode_e                 mode_i,
  input  logic [3:0]                            mask_i,
  input  logic [SB+3*WB-1:0]                    thr_i,
  input  logic                                  fresh_i,
  input  logic [voxcd_arch_pkg::CW-1:0]         stamp_i,
  input  logic [voxcd_arch_pkg::CW-1:0]         stall_stamp_i,
  // The lanes' results at the last register
  input  logic [LANES-1:0]                      inside_i,
  input  logic [2*LANES-1:0]                    state_i,
  input  logic [3*DW*LANES-1:0]                 voxel_i,
  input  logic [(SB+3*WB)*LANES-1:0]            dist_i,
  // The device's cycle number and its stall cycles before this one and up to and including it
  input  logic [voxcd_arch_pkg::CW-1:0]         now_i,
  input  logic [voxcd_arch_pkg::CW-1:0]         stall_total_i,
  input  logic [voxcd_arch_pkg::CW-1:0]         stall_total_next_i,
  // To the device: the output slice takes a record, the slot has more than one left, a record (a completion record)
  // enters the slice, the FIRST job's hit and stop, the job whose hit was found, a record waits in the slice
  output logic                                  out_ready_o,
  output logic                                  slot_busy_o,
  output logic                                  emit_o,
  output logic                                  emit_done_o,
  output logic                                  first_hit_o,
  output logic                                  first_stop_o,
  output logic                                  found_o,
  output logic [SeqW-1:0]                       found_seq_o,
  output logic                                  busy_o,
  // Hit stream
  output logic                                  hit_valid_o,
  input  logic                                  hit_ready_i,
  output logic [TAGW-1:0]                       hit_tag_o,
  output logic [(BL > 0 ? SAW + 6 : SAW)-1:0]   hit_point_o,
  output logic [DW-1:0]                         hit_x_o,
  output logic [DW-1:0]                         hit_y_o,
  output logic [DW-1:0]                         hit_z_o,
  output logic [1:0]                            hit_state_o,
  output logic [SB+3*WB-1:0]                    hit_dist_o,
  // Completion stream
  output logic                                  done_valid_o,
  input  logic                                  done_ready_i,
  output logic [TAGW-1:0]                       done_tag_o,
  output logic [(BL > 0 ? SAW + 6 : SAW):0]     done_hits_o,
  output logic [voxcd_arch_pkg::CW-1:0]         done_cycles_o,
  output logic [(BL > 0 ? SAW + 6 : SAW):0]     done_points_o,
  output logic [voxcd_arch_pkg::CW-1:0]         done_stalls_o
);

  localparam int unsigned CW    = voxcd_arch_pkg::CW;
  localparam bit          Dist  = SB > 2;                        // a distance device
  localparam int unsigned IW    = SB + 3 * WB;                   // D, the threshold
  localparam int unsigned PtW   = BL > 0 ? SAW + 6 : SAW;        // a point index (a sparse shell: 64 a word)
  localparam int unsigned LgL   = $clog2(LANES);
  localparam int unsigned LaneW = LgL > 0 ? LgL : 1;

  // One output record, hit or completion, as it waits in the output slice (the fields of the other kind are
  // don't-cares).
  typedef struct packed {
    logic              is_done;  // a completion record (else a hit record)
    logic [TAGW-1:0]   tag;
    logic [PtW-1:0]    point;
    logic [3*DW-1:0]   voxel;    // {z, y, x}
    logic [1:0]        state;
    logic [IW-1:0]     distance;
    logic [PtW:0]      hits;
    logic [PtW:0]      points;
    logic [CW-1:0]     cycles;
    logic [CW-1:0]     stalls;
  } record_t;

  // ---- Hit test and record emission ----
  logic [LANES-1:0] lane_hit;              // lanes whose point is a hit
  logic [LANES-1:0] emitted_d, emitted_q;  // hit records of the last slot already emitted (ALL)
  logic             found_d, found_q;      // a FIRST job's hit has been emitted; its later slots are squashed
  logic [SeqW-1:0]  found_seq_d, found_seq_q;
  logic             squash;                // the last slot belongs to a FIRST job whose hit was emitted
  logic             is_first;
  logic [LANES-1:0] records_left;          // hit records still to emit for the last slot
  logic             done_due;              // the last slot ends its job: a completion record follows its hits
  logic             slot_busy;             // after this cycle's record the last slot has another one to emit
  logic [LaneW-1:0] emit_lane;             // lowest lane in records_left: the hit record of this cycle
  logic [PtW:0]     slot_hits, slot_points;
  logic [PtW:0]     hits_d, hits_q, points_d, points_q;  // of the current job, over its slots before this one
  logic             out_ready;             // the output slice takes a record (a register: no path from *_ready_i)
  logic             emit;                  // a record enters the output slice
  logic             emit_done;             // a completion record enters the output slice
  logic             first_hit;             // the last slot holds the first hit of a FIRST job
  logic             first_stop;            // and the last register advances: stop issuing the job

  always_comb begin
    for (int i = 0; i < LANES; i++) begin
      if (Dist) lane_hit[i] = slot_lanes_i[i] && inside_i[i] &&
                              ($signed(dist_i[IW*i +: IW]) <= $signed(thr_i));
      else      lane_hit[i] = slot_lanes_i[i] && inside_i[i] && mask_i[state_i[2*i +: 2]];
    end
  end

  always_comb begin
    is_first     = mode_i == voxcd_arch_pkg::ModeFirst;
    squash       = slot_valid_i && found_q && (found_seq_q == slot_seq_i);
    records_left = '0;
    done_due     = 1'b0;
    if (slot_valid_i && !squash) begin
      if (mode_i == voxcd_arch_pkg::ModeAll) records_left = lane_hit & ~emitted_q;
      else if (is_first)                       records_left = lane_hit & (~lane_hit + 1'b1) & ~emitted_q;  // lowest
      done_due = slot_last_i || (is_first && (|lane_hit));
    end
    emit_lane = '0;
    for (int i = LANES - 1; i >= 0; i--) begin
      if (records_left[i]) emit_lane = LaneW'(i);
    end
    // More than one record left: two or more hits, or a hit and the completion.
    slot_busy = ((records_left & (records_left - 1'b1)) != '0) || ((|records_left) && done_due);
    slot_hits   = '0;
    slot_points = '0;
    for (int i = 0; i < LANES; i++) begin
      slot_hits   = slot_hits + (PtW + 1)'(lane_hit[i]);
      slot_points = slot_points + (PtW + 1)'(slot_lanes_i[i]);
    end
    if (is_first) slot_hits = (PtW + 1)'(|lane_hit);
  end

  assign emit       = out_ready && ((|records_left) || done_due);
  assign emit_done  = emit && !(|records_left);
  assign first_hit  = slot_valid_i && !squash && is_first && (|lane_hit);
  assign first_stop = advance_out_i && first_hit;

  always_comb begin
    emitted_d   = emitted_q;
    found_d     = found_q;
    found_seq_d = found_seq_q;
    hits_d      = hits_q;
    points_d    = points_q;
    if (out_ready && (|records_left)) emitted_d = emitted_q | (LANES'(1) << emit_lane);
    if (advance_out_i) begin
      emitted_d = '0;
      if (first_stop) begin
        found_d     = 1'b1;
        found_seq_d = slot_seq_i;
      end else if (slot_valid_i && (slot_seq_i != found_seq_q)) begin
        found_d = 1'b0;
      end
      if (slot_valid_i && !squash) begin
        hits_d   = done_due ? '0 : hits_q + slot_hits;
        points_d = done_due ? '0 : points_q + slot_points;
      end
    end
  end

  `VOXCD_FF(emitted_q, emitted_d, '0)
  `VOXCD_FF(found_q, found_d, 1'b0)
  `VOXCD_FF(found_seq_q, found_seq_d, '0)
  `VOXCD_FF(hits_q, hits_d, '0)
  `VOXCD_FF(points_q, points_d, '0)

  // ---- Cycle and stall accounting of the completion records ----
  // Both count over one window: from the later of the job's acceptance and the previous completion record's
  // emission, to this record's emission. cycles: the cycles of that window; stalls: its stall cycles (the cycles
  // in which the output slice held the pipeline). Stalls before a job's acceptance (an idle device whose last
  // record waits for its consumer) cannot delay it and are not counted.
  logic [CW-1:0] since_done_d, since_done_q;            // cycles since the previous completion's emission
  logic [CW-1:0] stalls_at_done_d, stalls_at_done_q;    // stall_total at the previous completion's emission
  logic [CW-1:0] job_age, cycles, stalls, stalls_since_job, stalls_since_done;
  logic          window_from_job;                       // the job was accepted after the previous completion
  // A job accepted with no earlier job in flight (fresh) was accepted after the previous completion's emission; one
  // accepted in the cycle of that emission may take either window (both give the same counts). Each candidate is
  // computed from registers, side by side, and then selected: no comparison of the two windows on the path.
  assign job_age           = now_i - stamp_i;
  assign window_from_job   = fresh_i;
  assign cycles            = window_from_job ? job_age : since_done_q;
  assign stalls_since_job  = stall_total_i - stall_stamp_i;
  assign stalls_since_done = stall_total_i - stalls_at_done_q;
  assign stalls            = window_from_job ? stalls_since_job : stalls_since_done;

  always_comb begin
    since_done_d     = emit_done ? CW'(1) : ((since_done_q == '1) ? since_done_q : since_done_q + 1'b1);
    stalls_at_done_d = emit_done ? stall_total_next_i : stalls_at_done_q;
  end

  `VOXCD_FF(since_done_q, since_done_d, '1)
  `VOXCD_FF(stalls_at_done_q, stalls_at_done_d, '0)

  // ---- Output slice: the record of this cycle, then voxcd_skid ----
  record_t emit_record, out_record;
  logic    out_valid, out_taken;
  always_comb begin
    emit_record.is_done = !(|records_left);
    emit_record.tag     = tag_i;
    emit_record.point   = PtW'(slot_k_i + (PtW + 1)'(emit_lane));
    emit_record.voxel   = voxel_i[3*DW*emit_lane +: 3*DW];
    emit_record.state   = state_i[2*emit_lane +: 2];
    emit_record.distance = dist_i[IW*emit_lane +: IW];  // 0 on a 2-bit device
    emit_record.hits    = hits_q + slot_hits;
    emit_record.points  = points_q + slot_points;
    emit_record.cycles  = cycles;
    emit_record.stalls  = stalls;
  end

  // The consumer's ready selects by the kind of the waiting record; it reaches only the slice.
  assign out_taken = out_record.is_done ? done_ready_i : hit_ready_i;

  voxcd_skid #(
    .Width($bits(emit_record))
  ) u_out_slice (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i((|records_left) || done_due),
    .ready_o(out_ready),
    .data_i (emit_record),
    .valid_o(out_valid),
    .ready_i(out_taken),
    .data_o (out_record)
  );

  assign hit_valid_o   = out_valid && !out_record.is_done;
  assign hit_tag_o     = out_record.tag;
  assign hit_point_o   = out_record.point;
  assign hit_x_o       = out_record.voxel[0*DW +: DW];
  assign hit_y_o       = out_record.voxel[1*DW +: DW];
  assign hit_z_o       = out_record.voxel[2*DW +: DW];
  assign hit_state_o   = out_record.state;
  assign hit_dist_o    = out_record.distance;
  assign done_valid_o  = out_valid && out_record.is_done;
  assign done_tag_o    = out_record.tag;
  assign done_hits_o   = out_record.hits;
  assign done_points_o = out_record.points;
  assign done_cycles_o = out_record.cycles;
  assign done_stalls_o = out_record.stalls;

  // Each mode's completion records, with and without hits.
  logic cov_is_count;
  assign cov_is_count = mode_i == voxcd_arch_pkg::ModeCount;
  `VOXCD_COVER(CoverAllJobWithHits, emit_done && !is_first && !cov_is_count && emit_record.hits != '0)
  `VOXCD_COVER(CoverAllJobWithoutHits, emit_done && !is_first && !cov_is_count && emit_record.hits == '0)
  `VOXCD_COVER(CoverFirstJobWithAHit, emit_done && is_first && emit_record.hits != '0)
  `VOXCD_COVER(CoverFirstJobWithoutHits, emit_done && is_first && emit_record.hits == '0)
  `VOXCD_COVER(CoverCountJobWithHits, emit_done && cov_is_count && emit_record.hits != '0)
  `VOXCD_COVER(CoverCountJobWithoutHits, emit_done && cov_is_count && emit_record.hits == '0)
  `VOXCD_COVER(CoverJobWithoutPoints, emit_done && emit_record.points == '0)
  // FIRST: its stop with slots of the job behind it, and those slots squashed at the hit test.
  `VOXCD_COVER(CoverFirstStopsBeforeTheLastSlot, first_stop && !slot_last_i)
  `VOXCD_COVER(CoverFirstSquashedSlot, squash)
  // A slot with every lane, one with some, and one with several records to emit (the pipeline holds for it).
  `VOXCD_COVER(CoverFullSlot, slot_valid_i && (&slot_lanes_i))
  `VOXCD_COVER(CoverPartSlot, slot_valid_i && !(&slot_lanes_i))
  `VOXCD_COVER(CoverSlotOfSeveralRecords, slot_busy)
  // A distance device's hit test: D below, at and above the threshold, for a point inside the map.
  if (Dist) begin : g_cover_dist
    logic [LANES-1:0] cov_below, cov_at, cov_above;
    always_comb begin
      for (int i = 0; i < LANES; i++) begin
        cov_below[i] = slot_lanes_i[i] && inside_i[i] &&
                   ($signed(dist_i[IW*i +: IW]) < $signed(thr_i));
        cov_at[i]    = slot_lanes_i[i] && inside_i[i] && (dist_i[IW*i +: IW] == thr_i);
        cov_above[i] = slot_lanes_i[i] && inside_i[i] &&
                   ($signed(dist_i[IW*i +: IW]) > $signed(thr_i));
      end
    end
    `VOXCD_COVER(CoverDistanceBelowThreshold, slot_valid_i && (|cov_below))
    `VOXCD_COVER(CoverDistanceAtThreshold, slot_valid_i && (|cov_at))
    `VOXCD_COVER(CoverDistanceAboveThreshold, slot_valid_i && (|cov_above))
  end

  assign out_ready_o  = out_ready;
  assign slot_busy_o  = slot_busy;
  assign emit_o       = emit;
  assign emit_done_o  = emit_done;
  assign first_hit_o  = first_hit;
  assign first_stop_o = first_stop;
  assign found_o      = found_q;
  assign found_seq_o  = found_seq_q;
  // The output slice holds records only behind its output register: out_valid covers both.
  assign busy_o       = out_valid;

endmodule
