// voxcd_device: the voxel collision detection accelerator (docs/hardware.md has the diagram).
//
// Contract (docs/contract.md): for each job {tag, mode, mask, shell_base, shell_count, map_base, n, M, t,
// threshold}, every shell point p of the job is transformed exactly (acc = M*p + t), floored to a voxel index,
// bounds-checked at full width and looked up in the voxmap; a point inside the map whose voxel state has its bit in
// the mask is a hit. On a distance device (SB > 2) the voxmap holds signed node distances in 8 parity banks, the
// lookup interpolates the eight nodes around the cell to D (SB + 3*WB bits, exact), and an inside point with
// D <= threshold is a hit (the mask plays no part). ALL reports every hit, FIRST the lowest-index one, COUNT none;
// then a completion record per job. With SB = 2 the threshold is unused and hit_dist_o is 0.
//
// Streams (valid/ready; a transfer happens in a cycle where both are high):
//   job   in : one job per transfer, into a 2-entry queue (job_ready_o is low only when the queue is full).
//   hit   out: {tag, point, x, y, z, state, dist}, ascending point order within a job.
//   done  out: {tag, hits, cycles, points, stalls} after the job's last hit record.
// At most one of hit_valid_o / done_valid_o is high in a cycle, and records leave in stream order.
//
// Structure: an issue stage takes LANES consecutive points of the head job per cycle (one lane group, a "slot")
// and reads them from LANES shell banks; LANES lanes (voxcd_lane) carry the slot through registers R0..R5 (R0..R8
// on a distance device: PipeSlots + DistSlots); the hit-test stage at the last register emits the slot's records,
// one per cycle, into the output register. The whole pipeline
// advances together: it holds (a) while the output register is full and its consumer is not ready (a stall, and
// only those cycles count as stalls) and (b) while the R5 slot still has more than one record to emit. Jobs
// follow each other with no drain: the slot after a job's last one is the next job's first.
//
// Timing (the exact model is ref/timing.h): a job of c points takes max(1, ceil(c / LANES)) slots; a slot takes
// max(1, records) cycles at the hit test; the first slot of a job accepted in cycle a is there in cycle a + 1 + N,
// N = PipeSlots (+ DistSlots on a distance device). FIRST stops issuing at its first hit: the N - 1 slots already
// issued are squashed and the issue stage leaves the job with one empty slot.
//
// Memories are written through the two write ports while the device is idle (busy_o low).
//
// Ports are plain vectors, one per record field, so that every configuration is one source and the Verilated C++
// and SystemC ports are plain integers. The code keeps to the subset of SystemVerilog that Verilator and yosys
// both read (one-dimensional packed vectors, one-level structs, explicit package references).
module voxcd_device #(
  parameter int unsigned PW    = voxcd_pkg::PW,
  parameter int unsigned PF    = voxcd_pkg::PF,
  parameter int unsigned MW    = voxcd_pkg::MW,
  parameter int unsigned MF    = voxcd_pkg::MF,
  parameter int unsigned TW    = voxcd_pkg::TW,
  parameter int unsigned DW    = voxcd_pkg::DW,
  parameter int unsigned MEMW  = voxcd_pkg::MEMW,
  parameter int unsigned LANES = voxcd_pkg::LANES,
  parameter int unsigned SAW   = voxcd_pkg::SAW,
  parameter int unsigned MAW   = voxcd_pkg::MAW,
  parameter int unsigned TAGW  = voxcd_pkg::TAGW,
  parameter int unsigned SB    = voxcd_pkg::SB,
  parameter int unsigned WB    = voxcd_pkg::WB
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,

  // Shell memory write port: word = {z, y, x}, each PW-bit signed with PF fraction bits.
  input  logic                     shell_we_i,
  input  logic [SAW-1:0]           shell_waddr_i,
  input  logic [3*PW-1:0]          shell_wdata_i,
  // Voxmap memory write port.
  input  logic                     map_we_i,
  input  logic [MAW-1:0]           map_waddr_i,
  input  logic [MEMW-1:0]          map_wdata_i,

  // Job stream.
  input  logic                     job_valid_i,
  output logic                     job_ready_o,
  input  logic [TAGW-1:0]          job_tag_i,
  input  logic [1:0]               job_mode_i,         // voxcd_pkg::mode_e
  input  logic [3:0]               job_mask_i,
  input  logic [SAW-1:0]           job_shell_base_i,
  input  logic [SAW:0]             job_shell_count_i,
  input  logic [MAW-1:0]           job_map_base_i,
  input  logic [DW:0]              job_nx_i,
  input  logic [DW:0]              job_ny_i,
  input  logic [DW:0]              job_nz_i,
  input  logic [MW-1:0]            job_m00_i, job_m01_i, job_m02_i,
  input  logic [MW-1:0]            job_m10_i, job_m11_i, job_m12_i,
  input  logic [MW-1:0]            job_m20_i, job_m21_i, job_m22_i,
  input  logic [TW-1:0]            job_t0_i, job_t1_i, job_t2_i,
  input  logic [SB+3*WB-1:0]       job_threshold_i,    // signed; distance devices (SB > 2) only

  // Hit stream.
  output logic                     hit_valid_o,
  input  logic                     hit_ready_i,
  output logic [TAGW-1:0]          hit_tag_o,
  output logic [SAW-1:0]           hit_point_o,
  output logic [DW-1:0]            hit_x_o,
  output logic [DW-1:0]            hit_y_o,
  output logic [DW-1:0]            hit_z_o,
  output logic [1:0]               hit_state_o,
  output logic [SB+3*WB-1:0]       hit_dist_o,         // signed D; 0 on a 2-bit device

  // Completion stream.
  output logic                     done_valid_o,
  input  logic                     done_ready_i,
  output logic [TAGW-1:0]          done_tag_o,
  output logic [SAW:0]             done_hits_o,
  output logic [voxcd_pkg::CW-1:0] done_cycles_o,
  output logic [SAW:0]             done_points_o,
  output logic [voxcd_pkg::CW-1:0] done_stalls_o,

  // High while a job is queued or in flight or a record waits.
  output logic                     busy_o
);

  localparam int unsigned CW    = voxcd_pkg::CW;
  localparam bit          Dist  = SB > 2;                        // a distance device
  localparam int unsigned IW    = SB + 3 * WB;                   // D, the threshold
  localparam int unsigned NumR  = voxcd_pkg::PipeSlots + (Dist ? voxcd_pkg::DistSlots : 0);  // R0 .. R5 (R8)
  localparam int unsigned ThrW  = Dist ? IW : 1;                 // job fields a 2-bit device does not keep
  localparam int unsigned HxyW  = Dist ? 2 * DW + 1 : 1;
  localparam int unsigned LgL   = $clog2(LANES);
  localparam int unsigned RotW  = LgL > 0 ? LgL : 1;
  localparam int unsigned RowW  = SAW - LgL;                      // rows of one shell bank
  localparam int unsigned LaneW = LgL > 0 ? LgL : 1;
  localparam int unsigned SeqW  = $clog2(NumR + 2) + 1;           // tells apart every job in flight

  // ---- Jobs and slots ----
  typedef struct packed {
    logic [TAGW-1:0]        tag;
    logic [1:0]             mode;
    logic [3:0]             mask;
    logic [SAW-1:0]         shell_base;
    logic [SAW:0]           shell_count;
    logic [MAW-1:0]         map_base;
    logic [3*(DW+1)-1:0]    n;      // {nz, ny, nx}
    logic [9*MW-1:0]        m;      // {m22, m21, ..., m00}
    logic [3*TW-1:0]        t;      // {t2, t1, t0}
    logic [ThrW-1:0]        thr;    // the threshold (distance devices; else 0)
    logic [HxyW-1:0]        hxy;    // Hx*Hy = ((nx>>1)+1) * ((ny>>1)+1), the z step of a bank's half-index (else 0)
    logic [CW-1:0]          stamp;  // cycle in which the job was accepted
  } job_t;
  localparam int unsigned JobW = TAGW + 2 + 4 + SAW + (SAW + 1) + MAW + 3 * (DW + 1) + 9 * MW + 3 * TW + ThrW +
                                 HxyW + CW;

  typedef struct packed {
    logic              valid;   // a slot of a job (else an empty slot)
    logic [SeqW-1:0]   seq;     // job sequence number, to match FIRST's early stop
    logic              last;    // the job's last slot
    logic [SAW:0]      k;       // point index (relative to shell_base) of lane 0
    logic [LANES-1:0]  lanes;   // lanes holding a point of the job
    logic [RotW-1:0]   rot;     // shell bank of lane 0
  } meta_t;
  localparam int unsigned MetaW = 1 + SeqW + 1 + (SAW + 1) + LANES + RotW;

  // ---- Cycle counter ----
  logic [CW-1:0] now_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) now_q <= '0;
    else         now_q <= now_q + 1'b1;
  end

  // ---- Job queue (2 entries) ----
  logic [JobW-1:0] fifo_q [2];
  logic [1:0]      fifo_cnt_q;
  logic            push, pop;
  job_t            job_in;
  logic [DW:0]     hx_in, hy_in;  // H = (n>>1) + 1, the half-grid's extent
  assign hx_in = (job_nx_i >> 1) + (DW + 1)'(1);
  assign hy_in = (job_ny_i >> 1) + (DW + 1)'(1);

  always_comb begin
    job_in.tag         = job_tag_i;
    job_in.mode        = job_mode_i;
    job_in.mask        = job_mask_i;
    job_in.shell_base  = job_shell_base_i;
    job_in.shell_count = job_shell_count_i;
    job_in.map_base    = job_map_base_i;
    job_in.n           = {job_nz_i, job_ny_i, job_nx_i};
    job_in.m           = {job_m22_i, job_m21_i, job_m20_i, job_m12_i, job_m11_i, job_m10_i,
                          job_m02_i, job_m01_i, job_m00_i};
    job_in.t           = {job_t2_i, job_t1_i, job_t0_i};
    job_in.thr         = '0;
    job_in.hxy         = '0;
    if (Dist) begin
      job_in.thr = ThrW'(job_threshold_i);
      job_in.hxy = HxyW'(HxyW'(hx_in) * HxyW'(hy_in));
    end
    job_in.stamp       = now_q;
  end

  assign job_ready_o = fifo_cnt_q != 2'd2;
  assign push        = job_valid_i && job_ready_o;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      fifo_cnt_q <= '0;
    end else begin
      fifo_cnt_q <= fifo_cnt_q + {1'b0, push} - {1'b0, pop};
    end
  end

  always_ff @(posedge clk_i) begin
    if (pop) fifo_q[0] <= fifo_q[1];
    if (push) fifo_q[1'(fifo_cnt_q - {1'b0, pop})] <= job_in;
  end

  // ---- Pipeline control ----
  logic            adv;       // every slot register advances
  logic            kill;      // the last register holds the first hit of a FIRST job: stop issuing it
  logic [SeqW-1:0] kill_seq;

  // ---- Issue stage ----
  job_t            head;
  logic            have;
  logic [SAW:0]    k_q;        // next point of the head job
  logic [SeqW-1:0] seq_q;      // sequence number of the head job
  logic            last_slot;  // the head job's remaining points fit one slot
  logic            kill_head;
  logic [SAW:0]    remaining;
  logic [SAW:0]    first_addr; // shell address of lane 0
  logic [RotW-1:0] rot;

  assign head       = fifo_q[0];
  assign have       = fifo_cnt_q != 2'd0;
  assign remaining  = head.shell_count - k_q;
  assign last_slot  = remaining <= (SAW + 1)'(LANES);
  assign kill_head  = kill && (kill_seq == seq_q);
  assign pop        = adv && have && (kill_head || last_slot);
  assign first_addr = (SAW + 1)'(head.shell_base) + k_q;
  assign rot        = RotW'(32'(first_addr) % LANES);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      k_q   <= '0;
      seq_q <= '0;
    end else if (adv && have) begin
      if (pop) begin
        k_q   <= '0;
        seq_q <= seq_q + 1'b1;
      end else begin
        k_q <= k_q + (SAW + 1)'(LANES);
      end
    end
  end

  meta_t issue;
  always_comb begin
    issue       = '0;
    issue.valid = have && !kill_head;
    issue.seq   = seq_q;
    issue.last  = last_slot;
    issue.k     = k_q;
    issue.rot   = rot;
    for (int i = 0; i < LANES; i++) issue.lanes[i] = (k_q + (SAW + 1)'(i)) < head.shell_count;
  end

  // ---- Slot registers R0 .. R5 (R8): the slot's bookkeeping and its job ----
  logic [MetaW-1:0] meta_q [NumR];
  logic [JobW-1:0]  sjob_q [NumR];
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      for (int s = 0; s < NumR; s++) meta_q[s] <= '0;
    end else if (adv) begin
      meta_q[0] <= issue;
      for (int s = 1; s < NumR; s++) meta_q[s] <= meta_q[s - 1];
    end
  end
  always_ff @(posedge clk_i) begin
    if (adv) begin
      sjob_q[0] <= head;
      for (int s = 1; s < NumR; s++) sjob_q[s] <= sjob_q[s - 1];
    end
  end

  // What each stage reads of its slot; m5 and j5 are the last register's (R5, or R8 on a distance device).
  meta_t m0, m5;
  job_t  j0, j1, j2, j3, j5;
  assign m0 = meta_q[0];
  assign m5 = meta_q[NumR - 1];
  assign j0 = sjob_q[0];
  assign j1 = sjob_q[1];
  assign j2 = sjob_q[2];
  assign j3 = sjob_q[3];
  assign j5 = sjob_q[NumR - 1];

  // ---- Shell banks: address a is in bank a % LANES, row a / LANES ----
  logic [LANES*3*PW-1:0] bank_rdata;
  for (genvar b = 0; b < LANES; b++) begin : g_bank
    // The LANES consecutive addresses of a slot fall one in each bank: bank b holds the one (b - rot) mod LANES
    // after the first.
    logic [SAW:0]    addr;
    logic [RowW-1:0] row;
    assign addr = first_addr + (SAW + 1)'(RotW'(RotW'(b) - rot));
    assign row  = RowW'(addr >> LgL);
    voxcd_ram #(
      .Width(3 * PW),
      .AddrW(RowW)
    ) u_shell (
      .clk_i  (clk_i),
      .we_i   (shell_we_i && ((32'(shell_waddr_i) % LANES) == b)),
      .waddr_i(RowW'(shell_waddr_i >> LgL)),
      .wdata_i(shell_wdata_i),
      .re_i   (adv),
      .raddr_i(row),
      .rdata_o(bank_rdata[b*3*PW +: 3*PW])
    );
  end

  // ---- Lanes ----
  logic [LANES-1:0]      lane_inside;
  logic [LANES*2-1:0]    lane_state;
  logic [LANES*3*DW-1:0] lane_voxel;
  logic [LANES*IW-1:0]   lane_dist;

  for (genvar l = 0; l < LANES; l++) begin : g_lane
    logic [3*PW-1:0] point;
    assign point = bank_rdata[((32'(m0.rot) + l) % LANES) * 3 * PW +: 3 * PW];
    voxcd_lane #(
      .PW(PW), .PF(PF), .MW(MW), .MF(MF), .TW(TW), .DW(DW), .MEMW(MEMW), .MAW(MAW), .SB(SB), .WB(WB)
    ) u_lane (
      .clk_i      (clk_i),
      .en_i       (adv),
      .map_we_i   (map_we_i),
      .map_waddr_i(map_waddr_i),
      .map_wdata_i(map_wdata_i),
      .point_i    (point),
      .m_i        (j0.m),
      .t_i        (j1.t),
      .n_i        (j2.n),
      .nx_i       (j3.n[DW:0]),
      .map_base_i (j3.map_base),
      .hxy_i      ((2 * DW + 1)'(j3.hxy)),
      .inside_o   (lane_inside[l]),
      .state_o    (lane_state[2*l +: 2]),
      .dist_o     (lane_dist[IW*l +: IW]),
      .voxel_o    (lane_voxel[3*DW*l +: 3*DW])
    );
  end

  // ---- Hit test and record emission at the last register (R5, R8 on a distance device) ----
  logic [LANES-1:0] hit;        // lanes whose point is a hit
  logic [LANES-1:0] emitted_q;  // hit records of the R5 slot already emitted (ALL)
  logic             found_q;    // a FIRST job's hit has been emitted; its later slots are squashed
  logic [SeqW-1:0]  found_seq_q;
  logic             squash;
  logic             is_first;
  logic [LANES-1:0] pend;       // hit records still to emit for the R5 slot
  logic             need_done;  // the R5 slot ends its job
  logic             more;       // after this cycle's record the slot has another one
  logic [LaneW-1:0] sel;        // lowest lane in pend
  logic [SAW:0]     group_hits, group_points;
  logic [SAW:0]     hits_q, points_q;  // of the current job, over its slots before R5
  logic             out_valid_q, out_done_q, out_ready, out_free, stall, load;

  always_comb begin
    for (int i = 0; i < LANES; i++) begin
      if (Dist) hit[i] = m5.lanes[i] && lane_inside[i] && ($signed(lane_dist[IW*i +: IW]) <= $signed(IW'(j5.thr)));
      else      hit[i] = m5.lanes[i] && lane_inside[i] && j5.mask[lane_state[2*i +: 2]];
    end
  end

  always_comb begin
    is_first  = j5.mode == voxcd_pkg::ModeFirst;
    squash    = m5.valid && found_q && (found_seq_q == m5.seq);
    pend      = '0;
    need_done = 1'b0;
    if (m5.valid && !squash) begin
      if (j5.mode == voxcd_pkg::ModeAll) pend = hit & ~emitted_q;
      else if (is_first)                 pend = hit & (~hit + 1'b1) & ~emitted_q;  // the lowest hit
      need_done = m5.last || (is_first && (|hit));
    end
    sel = '0;
    for (int i = LANES - 1; i >= 0; i--) begin
      if (pend[i]) sel = LaneW'(i);
    end
    // More than one record left: two or more hits, or a hit and the completion.
    more = ((pend & (pend - 1'b1)) != '0) || ((|pend) && need_done);
    group_hits   = '0;
    group_points = '0;
    for (int i = 0; i < LANES; i++) begin
      group_hits   = group_hits + (SAW + 1)'(hit[i]);
      group_points = group_points + (SAW + 1)'(m5.lanes[i]);
    end
    if (is_first) group_hits = (SAW + 1)'(|hit);
  end

  assign out_ready = out_done_q ? done_ready_i : hit_ready_i;
  assign out_free  = !out_valid_q || out_ready;
  assign stall     = out_valid_q && !out_ready;
  assign adv       = out_free && !more;
  assign load      = out_free && ((|pend) || need_done);
  assign kill      = adv && m5.valid && !squash && is_first && (|hit);
  assign kill_seq  = m5.seq;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      emitted_q   <= '0;
      found_q     <= 1'b0;
      found_seq_q <= '0;
      hits_q      <= '0;
      points_q    <= '0;
    end else begin
      if (out_free && (|pend)) emitted_q <= emitted_q | (LANES'(1) << sel);
      if (adv) begin
        emitted_q <= '0;
        if (kill) begin
          found_q     <= 1'b1;
          found_seq_q <= m5.seq;
        end else if (m5.valid && (m5.seq != found_seq_q)) begin
          found_q <= 1'b0;
        end
        if (m5.valid && !squash) begin
          hits_q   <= need_done ? '0 : hits_q + group_hits;
          points_q <= need_done ? '0 : points_q + group_points;
        end
      end
    end
  end

  // ---- Cycle and stall accounting of the completion records ----
  // cycles: from the later of the job's acceptance and the previous completion record's emission, to this one's.
  // stalls: cycles since the previous completion's emission in which the output register was held by its consumer.
  logic [CW-1:0] since_done_q, stall_cnt_q, job_age, cycles;
  logic          done_load;
  assign done_load = load && !(|pend);
  assign job_age   = now_q - j5.stamp;
  assign cycles    = (job_age < since_done_q) ? job_age : since_done_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      since_done_q <= '1;
      stall_cnt_q  <= '0;
    end else begin
      since_done_q <= done_load ? CW'(1) : ((since_done_q == '1) ? since_done_q : since_done_q + 1'b1);
      stall_cnt_q  <= done_load ? '0 : stall_cnt_q + CW'(stall);
    end
  end

  // ---- Output register ----
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      out_valid_q <= 1'b0;
      out_done_q  <= 1'b0;
    end else if (out_free) begin
      out_valid_q <= load;
      out_done_q  <= done_load;
    end
  end

  always_ff @(posedge clk_i) begin
    if (load) begin
      hit_tag_o     <= j5.tag;
      hit_point_o   <= SAW'(m5.k + (SAW + 1)'(sel));
      hit_x_o       <= lane_voxel[3*DW*sel + 0*DW +: DW];
      hit_y_o       <= lane_voxel[3*DW*sel + 1*DW +: DW];
      hit_z_o       <= lane_voxel[3*DW*sel + 2*DW +: DW];
      hit_state_o   <= lane_state[2*sel +: 2];
      hit_dist_o    <= lane_dist[IW*sel +: IW];  // 0 on a 2-bit device
      done_tag_o    <= j5.tag;
      done_hits_o   <= hits_q + group_hits;
      done_points_o <= points_q + group_points;
      done_cycles_o <= cycles;
      done_stalls_o <= stall_cnt_q;
    end
  end

  assign hit_valid_o  = out_valid_q && !out_done_q;
  assign done_valid_o = out_valid_q && out_done_q;

  always_comb begin
    busy_o = have || out_valid_q;
    for (int s = 0; s < NumR; s++) busy_o = busy_o || meta_q[s][MetaW-1];  // the valid bit
  end

  // Fields that only some stages read.
  logic unused;
  assign unused = ^{m0, m5.rot, j0, j1, j2, j3, j5, job_threshold_i, hx_in, hy_in};

`ifndef SYNTHESIS
  // ---- Assertions (Verilator runs them with --assert) ----
  // Parameter sanity, at elaboration.
  if ((LANES & (LANES - 1)) != 0 || LANES > 64) begin : g_bad_lanes
    $error("LANES = %0d must be a power of two, at most 64", LANES);
  end
  if (SAW < LgL) begin : g_bad_saw
    $error("SAW = %0d leaves less than one row per shell bank for LANES = %0d", SAW, LANES);
  end
  if (MF + PF >= TW) begin : g_bad_tw
    $error("TW = %0d leaves no integer bit above TF = MF + PF = %0d", TW, MF + PF);
  end
  if ((MEMW & (MEMW - 1)) != 0 || MEMW < 2 || MEMW > 64) begin : g_bad_memw
    $error("MEMW = %0d must be a power of two in 2..64", MEMW);
  end
  if (((MW + PW + 2 > TW) ? MW + PW + 2 : TW) + 1 - (MF + PF) < DW + 1) begin : g_bad_dw
    $error("the accumulator's integer part cannot hold DW = %0d", DW);
  end
  if (SB != 2 && SB != 4 && SB != 8 && SB != 16) begin : g_bad_sb
    $error("SB = %0d must be 2, 4, 8 or 16", SB);
  end
  if (Dist && (SB > MEMW || MAW < 3)) begin : g_bad_dist_mem
    $error("a distance device needs SB = %0d <= MEMW = %0d and MAW = %0d >= 3 (8 banks)", SB, MEMW, MAW);
  end
  if (Dist && (WB < 1 || WB > MF + PF || WB > 16)) begin : g_bad_wb
    $error("WB = %0d must be in 1..min(TF = %0d, 16)", WB, MF + PF);
  end
  if (JobW != $bits(job_in) || MetaW != $bits(issue)) begin : g_bad_widths
    $error("JobW or MetaW does not match its struct");
  end

  // Records stay put while their consumer is not ready.
  logic                           hold_hit_q, hold_done_q;
  logic [TAGW+SAW+3*DW+2+IW-1:0]  hit_prev_q;
  logic [TAGW+2*(SAW+1)+2*CW-1:0] done_prev_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      hold_hit_q  <= 1'b0;
      hold_done_q <= 1'b0;
    end else begin
      hold_hit_q  <= hit_valid_o && !hit_ready_i;
      hold_done_q <= done_valid_o && !done_ready_i;
      hit_prev_q  <= {hit_tag_o, hit_point_o, hit_x_o, hit_y_o, hit_z_o, hit_state_o, hit_dist_o};
      done_prev_q <= {done_tag_o, done_hits_o, done_cycles_o, done_points_o, done_stalls_o};
      if (hold_hit_q) begin
        assert (hit_valid_o &&
                hit_prev_q == {hit_tag_o, hit_point_o, hit_x_o, hit_y_o, hit_z_o, hit_state_o, hit_dist_o})
          else $error("hit record changed while stalled");
      end
      if (hold_done_q) begin
        assert (done_valid_o &&
                done_prev_q == {done_tag_o, done_hits_o, done_cycles_o, done_points_o, done_stalls_o})
          else $error("completion record changed while stalled");
      end
      assert (!(hit_valid_o && done_valid_o)) else $error("hit and completion records valid together");
      assert (fifo_cnt_q <= 2'd2) else $error("job queue overflow");
      assert (!(push && fifo_cnt_q == 2'd2)) else $error("push into a full job queue");
      assert (!(pop && !have)) else $error("pop from an empty job queue");
      assert (!((shell_we_i || map_we_i) && busy_o)) else $error("memory written while jobs run");
      if (push) begin
        assert (job_mode_i != 2'd3) else $error("job %0d: mode 3 is invalid", job_tag_i);
        assert (job_nx_i != 0 && job_ny_i != 0 && job_nz_i != 0 &&
                job_nx_i <= (DW + 1)'(1 << DW) && job_ny_i <= (DW + 1)'(1 << DW) &&
                job_nz_i <= (DW + 1)'(1 << DW))
          else $error("job %0d: a map dimension is outside 1..2^DW", job_tag_i);
      end
    end
  end
`endif

endmodule
