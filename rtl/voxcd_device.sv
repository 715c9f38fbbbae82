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
//   job   in : one job per transfer, into a 2-entry queue (voxcd_fifo; job_ready_o is low only when it is full).
//   hit   out: {tag, point, x, y, z, state, dist}, ascending point order within a job.
//   done  out: {tag, hits, cycles, points, stalls} after the job's last hit record.
// At most one of hit_valid_o / done_valid_o is high in a cycle, and records leave in stream order.
//
// Structure: an issue stage takes LANES consecutive points of the head job per cycle (one lane group, a "slot")
// and reads them from LANES shell banks; LANES lanes (voxcd_lane) carry the slot through N = PipeSlots + Depth
// (+ DistSlots) slot registers, R0..R5 at Depth 0 (R0..R8 on a distance device; each unit of Depth adds a register
// stage to every lane); the hit-test stage at the last register emits the slot's records, one per cycle, into the
// output slice (voxcd_skid: an output register and a skid register). The whole pipeline
// advances together: it holds (a) while the output slice cannot take a record (its registered ready is low: both
// of its registers are full, because the consumer has held the waiting record; a stall, and only those cycles
// count as stalls) and (b) while the last slot register still has more than one record to emit. The consumer's
// ready reaches only the output slice, never the pipeline's enables. Jobs follow each other with no drain: the
// slot after a job's last one is the next job's first.
//
// Timing (the exact model is ref/timing.h): a job of c points takes max(1, ceil(c / LANES)) slots; a slot takes
// max(1, records) cycles at the hit test; the first slot of a job accepted in cycle a is there in cycle a + 1 + N,
// N slot registers as above. FIRST stops issuing at its first hit: the N - 1 slots already issued are squashed and
// the issue stage leaves the job with one empty slot.
//
// The output slice adds no latency to the always-ready case (a record is on the pins in the cycle after its
// emission, as from a plain output register), and with an always-ready consumer it never holds the pipeline.
//
// Memories are written through the two write ports while the device is idle (busy_o low).
//
// Ports are plain vectors, one per record field, so that every configuration is one source and the Verilated C++
// and SystemC ports are plain integers. The code keeps to the subset of SystemVerilog that Verilator and yosys
// both read (one-dimensional packed vectors, one-level structs, explicit package references).
module voxcd_device #(
  `VOXCD_DEVICE_PARAMS  // the widths, LANES, BANKS and Depth (voxcd_arch_pkg.sv)
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
  input  logic [1:0]               job_mode_i,         // voxcd_arch_pkg::mode_e
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
  output logic [voxcd_arch_pkg::CW-1:0] done_cycles_o,
  output logic [SAW:0]             done_points_o,
  output logic [voxcd_arch_pkg::CW-1:0] done_stalls_o,

  // High while a job is queued or in flight or a record waits.
  output logic                     busy_o,
  // Bank conflict cycles since reset (cycles in which R4 waited for a shared voxmap bank; 0 without BANKS).
  output logic [voxcd_arch_pkg::CW-1:0] conflicts_o
);

  localparam int unsigned CW    = voxcd_arch_pkg::CW;
  localparam bit          Dist  = SB > 2;                        // a distance device
  localparam int unsigned IW    = SB + 3 * WB;                   // D, the threshold
  // The slot registers, and the ones whose fields the lanes read (voxcd_lane; at Depth 0: R1, R2, R2, R3, R3, R4, R5).
  localparam bit          HasIn    = Depth > voxcd_arch_pkg::RankIn;
  localparam bit          HasSum   = Depth > voxcd_arch_pkg::RankSum;
  localparam bit          HasFloor = Depth > voxcd_arch_pkg::RankFloor;
  localparam bit          HasAddr  = Depth > voxcd_arch_pkg::RankAddr;
  localparam bit          HasRead  = Depth > voxcd_arch_pkg::RankRead;
  localparam int unsigned ProdR  = 1 + 32'(HasIn);            // the products (the lanes read t here)
  localparam int unsigned AccR   = ProdR + 1 + 32'(HasSum);   // the accumulators (n: the bounds)
  localparam int unsigned YzR    = AccR + 32'(HasFloor);      // what the y + ny*z product reads (ny)
  localparam int unsigned R3R    = YzR + 1;                   // the index and yz (nx)
  localparam int unsigned LinR   = R3R + 32'(HasAddr);        // what R4's address is computed from (map_base, hxy)
  localparam int unsigned AddrR  = LinR + 1;                  // R4: the voxmap address (the shared banks read it)
  localparam int unsigned WordR  = AddrR + 1;                 // R5: the voxmap word
  localparam int unsigned NumR   = WordR + 1 + 32'(HasRead) + (Dist ? voxcd_arch_pkg::DistSlots : 0);
  localparam int unsigned ThrW  = Dist ? IW : 1;                 // job fields a 2-bit device does not keep
  localparam int unsigned HxyW  = Dist ? 2 * DW + 1 : 1;
  localparam int unsigned LgL   = $clog2(LANES);
  localparam int unsigned RotW  = LgL > 0 ? LgL : 1;
  localparam int unsigned RowW  = SAW - LgL;                      // rows of one shell bank
  localparam int unsigned LaneW = LgL > 0 ? LgL : 1;
  localparam int unsigned SeqW  = $clog2(NumR + 2) + 1;           // tells apart every job in flight
  localparam int unsigned InFlW = $clog2(NumR + 3);               // counts the jobs in flight: at most NumR + 2
  localparam bit          Banked = BANKS > 0;                      // the lanes share one voxmap in BANKS banks
  localparam int unsigned NPar  = Dist ? 8 : 1;                    // words a lane reads per point (its requests)
  localparam int unsigned NReq  = LANES * NPar;                    // request r: lane r / NPar, parity bank r % NPar
  localparam int unsigned NumB  = Banked ? BANKS * NPar : 1;       // shared banks: word w in bank w % NumB
  localparam int unsigned LgB   = Banked ? $clog2(NumB) : 0;
  localparam int unsigned BankW = LgB > 0 ? LgB : 1;
  localparam int unsigned BRowW = MAW > LgB ? MAW - LgB : 1;       // rows of one shared bank (one at NumB = 2^MAW)

  // ---- Jobs, slots and output records ----
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
    logic                   fresh;        // accepted with every earlier job's completion record emitted
    logic [CW-1:0]          stamp;        // cycle in which the job was accepted
    logic [CW-1:0]          stall_stamp;  // stall cycles up to and including that cycle
  } job_t;
  localparam int unsigned JobW = TAGW + 2 + 4 + SAW + (SAW + 1) + MAW + 3 * (DW + 1) + 9 * MW + 3 * TW + ThrW +
                                 HxyW + 1 + 2 * CW;

  // What the slot registers after R0 keep of a slot's job (below): the map, and the fields of the hit test.
  typedef struct packed {
    logic [3*(DW+1)-1:0] n;
    logic [MAW-1:0]      map_base;
    logic [HxyW-1:0]     hxy;
  } map_t;
  typedef struct packed {
    logic [TAGW-1:0] tag;
    logic [1:0]      mode;
    logic [3:0]      mask;
    logic [ThrW-1:0] thr;
    logic            fresh;
    logic [CW-1:0]   stamp;
    logic [CW-1:0]   stall_stamp;
  } test_t;
  localparam int unsigned TestW = TAGW + 2 + 4 + ThrW + 1 + 2 * CW;

  typedef struct packed {
    logic              valid;   // a slot of a job (else an empty slot)
    logic [SeqW-1:0]   seq;     // job sequence number, to match FIRST's early stop
    logic              last;    // the job's last slot
    logic [SAW:0]      k;       // point index (relative to shell_base) of lane 0
    logic [LANES-1:0]  lanes;   // lanes holding a point of the job
    logic [RotW-1:0]   rot;     // shell bank of lane 0
  } meta_t;
  localparam int unsigned MetaW = 1 + SeqW + 1 + (SAW + 1) + LANES + RotW;

  // One output record, hit or completion, as it waits in the output slice (the fields of the other kind are
  // don't-cares).
  typedef struct packed {
    logic              is_done;  // a completion record (else a hit record)
    logic [TAGW-1:0]   tag;
    logic [SAW-1:0]    point;
    logic [3*DW-1:0]   voxel;    // {z, y, x}
    logic [1:0]        state;
    logic [IW-1:0]     distance;
    logic [SAW:0]      hits;
    logic [SAW:0]      points;
    logic [CW-1:0]     cycles;
    logic [CW-1:0]     stalls;
  } record_t;
  localparam int unsigned RecordW = 1 + TAGW + SAW + 3 * DW + 2 + IW + 2 * (SAW + 1) + 2 * CW;

  // ---- Cycle and stall counters (free-running) ----
  logic          stall;                       // this cycle the pipeline is held by the output slice
  logic [CW-1:0] now_q;                       // this cycle's number
  logic [InFlW-1:0] in_flight_q;              // jobs accepted whose completion record has not been emitted
  logic             emit_done;                // a completion record enters the output slice (below)
  logic [CW-1:0] stall_total_d, stall_total_q;  // stall cycles before this one (_d: up to and including it)
  assign stall_total_d = stall_total_q + CW'(stall);
  `VOXCD_FF(now_q, now_q + 1'b1, '0)
  `VOXCD_FF(stall_total_q, stall_total_d, '0)
  `VOXCD_FF(in_flight_q, in_flight_q + InFlW'(job_valid_i && job_ready_o) - InFlW'(emit_done), '0)

  // ---- Job queue (voxcd_fifo, 2 entries) ----
  job_t        job_in, head_job;
  logic        head_valid;  // the queue holds a job: the issue stage's head job
  logic        head_pop;    // the issue stage is done with the head job
  logic [DW:0] hx_in, hy_in;  // H = (n>>1) + 1, the half-grid's extent
  assign hx_in = (job_nx_i >> 1) + (DW + 1)'(1);
  assign hy_in = (job_ny_i >> 1) + (DW + 1)'(1);

  // One assignment, in job_t's field order (so that a simulator packs it only where the queue stores it).
  assign job_in = {job_tag_i, job_mode_i, job_mask_i, job_shell_base_i, job_shell_count_i, job_map_base_i,
                   job_nz_i, job_ny_i, job_nx_i,
                   job_m22_i, job_m21_i, job_m20_i, job_m12_i, job_m11_i, job_m10_i, job_m02_i, job_m01_i, job_m00_i,
                   job_t2_i, job_t1_i, job_t0_i,
                   Dist ? ThrW'(job_threshold_i) : ThrW'(0),
                   Dist ? HxyW'(HxyW'(hx_in) * HxyW'(hy_in)) : HxyW'(0),
                   in_flight_q == '0, now_q, stall_total_d};

  voxcd_fifo #(
    .Depth(2),
    .Width(JobW)
  ) u_job_queue (
    .clk_i  (clk_i),
    .rst_ni (rst_ni),
    .valid_i(job_valid_i),
    .ready_o(job_ready_o),
    .data_i (job_in),
    .valid_o(head_valid),
    .ready_i(head_pop),
    .data_o (head_job)
  );

  // ---- Pipeline control ----
  // The last register (the hit test) advances when its records are out (advance_out); the registers before it and
  // the issue stage too unless R4 still waits for a shared voxmap bank (advance), in which case the last register
  // takes an empty slot. Without shared banks the two are the same.
  logic            advance;     // R0 .. R4 and the issue stage advance
  logic            advance_out; // the last register advances
  logic            first_stop;  // the last register holds the first hit of a FIRST job: stop issuing it
  logic [SeqW-1:0] first_stop_seq;

  // ---- Issue stage ----
  logic [SAW:0]    next_point_d, next_point_q;  // next point of the head job
  logic [SeqW-1:0] head_seq_d, head_seq_q;      // sequence number of the head job
  logic            head_last_slot;              // the head job's remaining points fit one slot
  logic            head_stopped;                // FIRST has found the head job's hit: issue no more of it
  logic [SAW:0]    head_remaining;
  logic [SAW:0]    first_addr;                  // shell address of lane 0
  logic [RotW-1:0] rot;

  assign head_remaining = head_job.shell_count - next_point_q;
  assign head_last_slot = head_remaining <= (SAW + 1)'(LANES);
  assign head_stopped   = first_stop && (first_stop_seq == head_seq_q);
  assign head_pop       = advance && head_valid && (head_stopped || head_last_slot);
  assign first_addr     = (SAW + 1)'(head_job.shell_base) + next_point_q;
  assign rot            = RotW'(32'(first_addr) % LANES);

  always_comb begin
    next_point_d = next_point_q;
    head_seq_d   = head_seq_q;
    if (head_pop) begin
      next_point_d = '0;
      head_seq_d   = head_seq_q + 1'b1;
    end else if (advance && head_valid) begin
      next_point_d = next_point_q + (SAW + 1)'(LANES);
    end
  end

  `VOXCD_FF(next_point_q, next_point_d, '0)
  `VOXCD_FF(head_seq_q, head_seq_d, '0)

  meta_t issue;
  always_comb begin
    issue       = '0;
    issue.valid = head_valid && !head_stopped;
    issue.seq   = head_seq_q;
    issue.last  = head_last_slot;
    issue.k     = next_point_q;
    issue.rot   = rot;
    for (int i = 0; i < LANES; i++) issue.lanes[i] = (next_point_q + (SAW + 1)'(i)) < head_job.shell_count;
  end

  // ---- Slot registers R0 .. R(N-1): the slot's bookkeeping and its job, shifting when the pipeline advances ----
  // R0 .. R4 (AddrR) advance with the issue stage (advance); R5 (WordR) and the registers after it with the last
  // register (advance_out), R5 taking an empty slot while R4 waits for a shared voxmap bank. Without shared banks
  // the two enables are the same. Each register is a register of its own (g_slot[s]: a simulator keeps it in its own
  // words and orders the chain with no copy; an array of them would be copied through temporaries every cycle).
  logic [NumR-1:0] slot_valid;  // the valid bit of each slot register
  for (genvar s = 0; s < NumR; s++) begin : g_slot
    logic [MetaW-1:0] meta_q, meta_in;
    logic             shift;
    if (s == 0) begin : g_issue
      assign meta_in = issue;
    end else if (s == WordR) begin : g_word
      assign meta_in = advance ? g_slot[s - 1].meta_q : '0;  // '0: an empty slot
    end else begin : g_next
      assign meta_in = g_slot[s - 1].meta_q;
    end
    assign shift = (s <= AddrR) ? advance : advance_out;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni)    meta_q <= '0;
      else if (shift) meta_q <= meta_in;
    end
    assign slot_valid[s] = meta_q[MetaW - 1];
  end

  // The job travels with its slot, each register keeping what the stages from it on read: R0 the whole job (the
  // lanes read M there, or from IN's M register), R1 .. ProdR the translation (read at ProdR), R1 .. LinR the map
  // (n read at AccR, ny at YzR, nx at R3R, map_base and hxy at LinR), and R1 .. R(N-1) the fields of the hit test.
  // Job fields are read only where their slot is valid: no reset.
  localparam int unsigned MapW = 3 * (DW + 1) + MAW + HxyW;
  job_t  r0_job_q;
  test_t r0_test, r5_test, last_test;
  map_t  acc_map, yz_map, r3_map, lin_map;  // the map fields of the registers AccR, YzR, R3R, LinR
  assign r0_test = {r0_job_q.tag, r0_job_q.mode, r0_job_q.mask, r0_job_q.thr, r0_job_q.fresh, r0_job_q.stamp,
                    r0_job_q.stall_stamp};
  always_ff @(posedge clk_i) begin
    if (advance) r0_job_q <= head_job;
  end
  // The matrix the lanes' multipliers read: R0's, or with IN one register later, beside the lanes' registered points
  // (one register for every lane: the same M for the whole slot).
  logic [9*MW-1:0] prod_m;
  voxcd_stage #(.Width(9*MW), .Enable(HasIn)) u_in_m (.clk_i(clk_i), .en_i(advance), .d_i(r0_job_q.m), .q_o(prod_m));
  // Four chains of registers, Rs's at [s*Width +: Width] of each (R0's at 0): the hit test's fields in two (the
  // job's labels, and its 64 bits of stamps: each fits a simulator's word), the translation and the map. The hit
  // test's registers after R4 advance with the output (advance_out).
  localparam int unsigned InfoW = TestW - 2*CW;
  logic [NumR*InfoW-1:0]     info_r;
  logic [NumR*2*CW-1:0]      stamps_r;
  logic [(ProdR+1)*3*TW-1:0] t_r;
  logic [(LinR+1)*MapW-1:0]  map_r;
  assign {info_r[0 +: InfoW], stamps_r[0 +: 2*CW]} = r0_test;
  assign t_r[0 +: 3*TW]                            = r0_job_q.t;
  assign map_r[0 +: MapW]                          = {r0_job_q.n, r0_job_q.map_base, r0_job_q.hxy};
  for (genvar s = 1; s < NumR; s++) begin : g_test
    logic en;
    assign en = (s <= AddrR) ? advance : advance_out;
    voxcd_stage #(.Width(InfoW)) u_info (
      .clk_i(clk_i), .en_i(en), .d_i(info_r[(s-1)*InfoW +: InfoW]), .q_o(info_r[s*InfoW +: InfoW]));
    voxcd_stage #(.Width(2*CW)) u_stamps (
      .clk_i(clk_i), .en_i(en), .d_i(stamps_r[(s-1)*2*CW +: 2*CW]), .q_o(stamps_r[s*2*CW +: 2*CW]));
  end
  for (genvar s = 1; s <= ProdR; s++) begin : g_t
    voxcd_stage #(.Width(3*TW)) u_t (
      .clk_i(clk_i), .en_i(advance), .d_i(t_r[(s-1)*3*TW +: 3*TW]), .q_o(t_r[s*3*TW +: 3*TW]));
  end
  for (genvar s = 1; s <= LinR; s++) begin : g_map
    voxcd_stage #(.Width(MapW)) u_map (
      .clk_i(clk_i), .en_i(advance), .d_i(map_r[(s-1)*MapW +: MapW]), .q_o(map_r[s*MapW +: MapW]));
  end
  assign r5_test   = {info_r[WordR*InfoW +: InfoW], stamps_r[WordR*2*CW +: 2*CW]};
  assign last_test = {info_r[(NumR-1)*InfoW +: InfoW], stamps_r[(NumR-1)*2*CW +: 2*CW]};
  assign acc_map   = map_r[AccR*MapW +: MapW];
  assign yz_map    = map_r[YzR*MapW +: MapW];
  assign r3_map    = map_r[R3R*MapW +: MapW];
  assign lin_map   = map_r[LinR*MapW +: MapW];

  // What each stage reads of its slot's bookkeeping: R0's, R4's, R5's and the last register's, where the hit test
  // is (R5 at Depth 0, or R8 on a distance device).
  meta_t r0_slot, r4_slot, r5_slot, last_slot;  // r4_slot, r5_slot: the shared voxmap banks' (BANKS > 0)
  assign r0_slot   = g_slot[0].meta_q;
  assign r4_slot   = g_slot[AddrR].meta_q;
  assign r5_slot   = g_slot[WordR].meta_q;
  assign last_slot = g_slot[NumR - 1].meta_q;

  // ---- Shell banks: address a is in bank a % LANES, row a / LANES ----
  logic [3*PW-1:0] bank_rdata [LANES];
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
      .re_i   (advance),
      .raddr_i(row),
      .rdata_o(bank_rdata[b])
    );
  end

  // ---- Lanes ----
  logic [NReq-1:0]       lane_read;     // R4: request r's point is inside its map and reads a voxmap word
  logic [NReq*MAW-1:0]   lane_addr;     // R4: the word it reads (lane r / NPar; parity bank r % NPar on a distance
                                        // device)
  logic [NReq*MEMW-1:0]  lane_word;     // R5: the word from the shared banks (Banked)
  logic [LANES-1:0]      lane_inside;
  logic [LANES-1:0]      lane_inside5;  // R5's points before READ (2-bit lanes)
  logic [LANES*2-1:0]    lane_state5;
  logic [LANES*2-1:0]    lane_state;
  logic [LANES*3*DW-1:0] lane_voxel;
  logic [LANES*IW-1:0]   lane_dist;

  for (genvar l = 0; l < LANES; l++) begin : g_lane
    logic [3*PW-1:0] point;
    assign point = bank_rdata[RotW'(32'(r0_slot.rot) + l) & RotW'(LANES - 1)];
    voxcd_lane #(
      `VOXCD_LANE_PARAM_MAP,
      .SharedMap(Banked)
    ) u_lane (
      .clk_i      (clk_i),
      .en_i       (advance),
      .en_out_i   (advance_out),
      .addr_o     (lane_addr[NPar*MAW*l +: NPar*MAW]),
      .read_o     (lane_read[NPar*l +: NPar]),
      .word_i     (lane_word[NPar*MEMW*l +: NPar*MEMW]),
      .map_we_i   (map_we_i),
      .map_waddr_i(map_waddr_i),
      .map_wdata_i(map_wdata_i),
      .point_i    (point),
      .m_i        (prod_m),
      .t_i        (t_r[ProdR*3*TW +: 3*TW]),
      .n_i        (acc_map.n),
      .ny_i       (yz_map.n[DW+1 +: DW+1]),
      .nx_i       (r3_map.n[DW:0]),
      .map_base_i (lin_map.map_base),
      .hxy_i      ((2 * DW + 1)'(lin_map.hxy)),
      .inside5_o  (lane_inside5[l]),
      .state5_o   (lane_state5[2*l +: 2]),
      .inside_o   (lane_inside[l]),
      .state_o    (lane_state[2*l +: 2]),
      .dist_o     (lane_dist[IW*l +: IW]),
      .voxel_o    (lane_voxel[3*DW*l +: 3*DW])
    );
  end

  logic             bank_wait;     // R4 has lanes left after this cycle's round (shared voxmap banks, below)
  logic [CW-1:0]    conflicts_q;   // bank conflict cycles since reset

  // ---- Hit test and record emission at the last register (R5, R8 on a distance device) ----
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
  logic [SAW:0]     slot_hits, slot_points;
  logic [SAW:0]     hits_d, hits_q, points_d, points_q;  // of the current job, over its slots before this one
  logic             out_ready;             // the output slice takes a record (a register: no path from *_ready_i)
  logic             emit;                  // a record enters the output slice

  always_comb begin
    for (int i = 0; i < LANES; i++) begin
      if (Dist) lane_hit[i] = last_slot.lanes[i] && lane_inside[i] &&
                              ($signed(lane_dist[IW*i +: IW]) <= $signed(IW'(last_test.thr)));
      else      lane_hit[i] = last_slot.lanes[i] && lane_inside[i] && last_test.mask[lane_state[2*i +: 2]];
    end
  end

  always_comb begin
    is_first     = last_test.mode == voxcd_arch_pkg::ModeFirst;
    squash       = last_slot.valid && found_q && (found_seq_q == last_slot.seq);
    records_left = '0;
    done_due     = 1'b0;
    if (last_slot.valid && !squash) begin
      if (last_test.mode == voxcd_arch_pkg::ModeAll) records_left = lane_hit & ~emitted_q;
      else if (is_first)                       records_left = lane_hit & (~lane_hit + 1'b1) & ~emitted_q;  // lowest
      done_due = last_slot.last || (is_first && (|lane_hit));
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
      slot_hits   = slot_hits + (SAW + 1)'(lane_hit[i]);
      slot_points = slot_points + (SAW + 1)'(last_slot.lanes[i]);
    end
    if (is_first) slot_hits = (SAW + 1)'(|lane_hit);
  end

  assign stall          = !out_ready;
  assign advance_out    = out_ready && !slot_busy;
  assign advance        = advance_out && !bank_wait;
  assign emit           = out_ready && ((|records_left) || done_due);
  assign emit_done      = emit && !(|records_left);
  assign first_stop     = advance_out && last_slot.valid && !squash && is_first && (|lane_hit);
  assign first_stop_seq = last_slot.seq;

  always_comb begin
    emitted_d   = emitted_q;
    found_d     = found_q;
    found_seq_d = found_seq_q;
    hits_d      = hits_q;
    points_d    = points_q;
    if (out_ready && (|records_left)) emitted_d = emitted_q | (LANES'(1) << emit_lane);
    if (advance_out) begin
      emitted_d = '0;
      if (first_stop) begin
        found_d     = 1'b1;
        found_seq_d = last_slot.seq;
      end else if (last_slot.valid && (last_slot.seq != found_seq_q)) begin
        found_d = 1'b0;
      end
      if (last_slot.valid && !squash) begin
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

  // ---- Shared voxmap banks (BANKS > 0): word w is in bank w % NumB, row w / NumB ----
  // NumB = BANKS on a 2-bit device; on a distance device each of the 8 parity banks is split BANKS ways (8 * BANKS
  // banks), and each lane makes 8 requests, one word of each parity bank. The slot in R4 reads in rounds, one in each
  // cycle in which the last register lets the pipeline advance: in a round each bank reads the word of the lowest
  // request still waiting for it, and every waiting request that wants that word takes it. R4 leaves in its last
  // round; before that R5 takes empty slots (a bank conflict cycle each). So a slot with at most r distinct words in
  // any one bank reaches the hit test r - 1 cycles late; a slot of a FIRST job that has found its hit reads nothing
  // (it is squashed: on a 2-bit device the hit is seen at the hit test, or with READ in R5, before the slot behind it
  // reads; on a distance device at the hit test, after the slots behind it read in the slot registers between).
  // ref/banks.h counts the same.
  // A word read in an earlier round waits in early_q and moves to held_q when the slot enters R5; the words of the
  // last round stay on the banks' outputs while the slot is in R5 (the banks read only when R5 advances).
  if (Banked) begin : g_banks
    logic                 r4_squashed;   // R4 belongs to a FIRST job whose hit is found or at the hit test now
    logic                 r5_first_hit;  // R5 (not the last register: HasRead, 2-bit) holds a FIRST job's hit
    logic [NReq-1:0]      want;          // requests of R4 that read a word
    logic [NReq-1:0]      served_d, served_q;  // requests of R4 that have their word (earlier rounds)
    logic [NReq-1:0]      waiting, granted;
    logic [NumB-1:0]      map_re;
    logic [NumB*MAW-1:0]  map_word;     // the word each bank reads this round
    logic [NumB*MEMW-1:0] map_rdata;
    logic [NReq-1:0]      early_read_q;  // requests whose word the banks read last cycle, in an earlier round
    logic [NReq*MEMW-1:0] early_q, early_now, held_q;
    logic [NReq-1:0]      last_round_q;  // requests of R5 whose word was read in R4's last round
    logic [NReq*BankW-1:0] r5_bank_q;    // and the bank that read it

    // A 2-bit device with READ sees a FIRST job's hit in R5, before the slot behind it reads; a distance device
    // only at the hit test, after the interpolation (ref/banks.h: first_read_window).
    always_comb begin
      r5_first_hit = 1'b0;
      if (HasRead && !Dist && r5_slot.valid && r5_test.mode == voxcd_arch_pkg::ModeFirst) begin
        for (int l = 0; l < LANES; l++) begin
          r5_first_hit = r5_first_hit || (r5_slot.lanes[l] && lane_inside5[l] && r5_test.mask[lane_state5[2*l +: 2]]);
        end
      end
    end
    assign r4_squashed = (found_q && (found_seq_q == r4_slot.seq)) ||
                         (last_slot.valid && !squash && is_first && (|lane_hit) && (last_slot.seq == r4_slot.seq)) ||
                         (r5_first_hit && (r5_slot.seq == r4_slot.seq));
    for (genvar r = 0; r < NReq; r++) begin : g_want
      assign want[r] = r4_slot.valid && !r4_squashed && r4_slot.lanes[r / NPar] && lane_read[r];
    end
    assign waiting = want & ~served_q;

    // Each bank's word this round: the lowest waiting request's that falls in it.
    always_comb begin
      map_re   = '0;
      map_word = '0;
      for (int r = NReq - 1; r >= 0; r--) begin
        if (waiting[r]) begin
          map_re[32'(lane_addr[MAW*r +: BankW]) % NumB] = 1'b1;
          map_word[MAW*(32'(lane_addr[MAW*r +: BankW]) % NumB) +: MAW] = lane_addr[MAW*r +: MAW];
        end
      end
      for (int r = 0; r < NReq; r++) begin
        granted[r] = waiting[r] &&
                     (map_word[MAW*(32'(lane_addr[MAW*r +: BankW]) % NumB) +: MAW] == lane_addr[MAW*r +: MAW]);
      end
    end
    assign bank_wait = |(waiting & ~granted);

    for (genvar b = 0; b < NumB; b++) begin : g_bank
      voxcd_ram #(
        .Width(MEMW),
        .AddrW(BRowW)
      ) u_map (
        .clk_i  (clk_i),
        .we_i   (map_we_i && ((32'(map_waddr_i) % NumB) == b)),
        .waddr_i(BRowW'(map_waddr_i >> LgB)),
        .wdata_i(map_wdata_i),
        .re_i   (advance_out && map_re[b]),
        .raddr_i(BRowW'(map_word[MAW*b +: MAW] >> LgB)),
        .rdata_o(map_rdata[MEMW*b +: MEMW])
      );
    end

    always_comb begin
      served_d = served_q;
      if (advance)          served_d = '0;
      else if (advance_out) served_d = served_q | granted;
      for (int r = 0; r < NReq; r++) begin
        early_now[MEMW*r +: MEMW] = early_read_q[r]
            ? map_rdata[MEMW*(32'(lane_addr[MAW*r +: BankW]) % NumB) +: MEMW] : early_q[MEMW*r +: MEMW];
        lane_word[MEMW*r +: MEMW] = last_round_q[r]
            ? map_rdata[MEMW*r5_bank_q[BankW*r +: BankW] +: MEMW] : held_q[MEMW*r +: MEMW];
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        served_q     <= '0;
        early_read_q <= '0;
        last_round_q <= '0;
        conflicts_q  <= '0;
      end else begin
        served_q     <= served_d;
        early_read_q <= (advance_out && !advance) ? granted : '0;
        if (advance_out) last_round_q <= advance ? granted : '0;
        conflicts_q  <= conflicts_q + CW'(advance_out && !advance);
      end
    end
    // Words: no reset (read only for requests that read).
    always_ff @(posedge clk_i) begin
      early_q <= early_now;
      if (advance) begin
        held_q <= early_now;
        for (int r = 0; r < NReq; r++) r5_bank_q[BankW*r +: BankW] <= BankW'(32'(lane_addr[MAW*r +: BankW]) % NumB);
      end
    end
  end else begin : g_copies
    assign bank_wait   = 1'b0;
    assign conflicts_q = '0;
    assign lane_word   = '0;
    logic unused_banks;  // each lane reads its own copy
    assign unused_banks = ^{lane_read, lane_addr};
  end
  assign conflicts_o = conflicts_q;

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
  assign job_age           = now_q - last_test.stamp;
  assign window_from_job   = last_test.fresh;
  assign cycles            = window_from_job ? job_age : since_done_q;
  assign stalls_since_job  = stall_total_q - last_test.stall_stamp;
  assign stalls_since_done = stall_total_q - stalls_at_done_q;
  assign stalls            = window_from_job ? stalls_since_job : stalls_since_done;

  always_comb begin
    since_done_d     = emit_done ? CW'(1) : ((since_done_q == '1) ? since_done_q : since_done_q + 1'b1);
    stalls_at_done_d = emit_done ? stall_total_d : stalls_at_done_q;
  end

  `VOXCD_FF(since_done_q, since_done_d, '1)
  `VOXCD_FF(stalls_at_done_q, stalls_at_done_d, '0)

  // ---- Output slice: the record of this cycle, then voxcd_skid ----
  record_t emit_record, out_record;
  logic    out_valid, out_taken;
  always_comb begin
    emit_record.is_done = !(|records_left);
    emit_record.tag     = last_test.tag;
    emit_record.point   = SAW'(last_slot.k + (SAW + 1)'(emit_lane));
    emit_record.voxel   = lane_voxel[3*DW*emit_lane +: 3*DW];
    emit_record.state   = lane_state[2*emit_lane +: 2];
    emit_record.distance = lane_dist[IW*emit_lane +: IW];  // 0 on a 2-bit device
    emit_record.hits    = hits_q + slot_hits;
    emit_record.points  = points_q + slot_points;
    emit_record.cycles  = cycles;
    emit_record.stalls  = stalls;
  end

  // The consumer's ready selects by the kind of the waiting record; it reaches only the slice.
  assign out_taken = out_record.is_done ? done_ready_i : hit_ready_i;

  voxcd_skid #(
    .Width(RecordW)
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

  // The output slice holds records only behind its output register: out_valid covers both.
  assign busy_o = head_valid || out_valid || (|slot_valid);

  // Fields that only some stages read.
  logic unused;
  assign unused = ^{r0_slot, r4_slot, r5_slot, r5_test, last_slot.rot, r0_job_q, acc_map, yz_map, r3_map, lin_map,
                    last_test, job_threshold_i, hx_in, hy_in, lane_inside5, lane_state5};

  // ---- Assertions (Verilator runs them with --assert; voxcd_assert.sv) ----
  // Parameter sanity, at elaboration.
  `VOXCD_ASSERT_INIT(LanesPowerOfTwo, (LANES & (LANES - 1)) == 0 && LANES <= 64)
  `VOXCD_ASSERT_INIT(ShellBankHasARow, SAW >= LgL)
  `VOXCD_ASSERT_INIT(TranslationHasIntegerBits, MF + PF < TW)
  `VOXCD_ASSERT_INIT(MemWordPowerOfTwo, (MEMW & (MEMW - 1)) == 0 && MEMW >= 2 && MEMW <= 64)
  `VOXCD_ASSERT_INIT(AccumulatorHoldsIndex,
                     ((MW + PW + 2 > TW) ? MW + PW + 2 : TW) + 1 - (MF + PF) >= DW + 1)
  `VOXCD_ASSERT_INIT(ValueWidthKnown, SB == 2 || SB == 4 || SB == 8 || SB == 16)
  `VOXCD_ASSERT_INIT(DistanceBanksFit, !Dist || (SB <= MEMW && MAW >= 3))
  `VOXCD_ASSERT_INIT(WeightBitsFit, !Dist || (WB >= 1 && WB <= MF + PF && WB <= 16))
  `VOXCD_ASSERT_INIT(BanksPowerOfTwo, (BANKS & (BANKS - 1)) == 0 && BANKS <= 64 && LgB <= MAW)
  `VOXCD_ASSERT_INIT(DepthInRange, Depth <= voxcd_arch_pkg::MaxDepth)
  `VOXCD_ASSERT_INIT(SlotsMatchTheTimingModel,
                     NumR == voxcd_arch_pkg::PipeSlots + Depth + (Dist ? voxcd_arch_pkg::DistSlots : 0))
  `VOXCD_ASSERT_INIT(StructWidthsMatch, JobW == $bits(job_t) && MetaW == $bits(meta_t) && TestW == $bits(test_t) &&
                                        RecordW == $bits(record_t))

  // The streams: records hold while their consumer is not ready; one record at a time, in stream order.
  `VOXCD_ASSERT(HitHeldWhileStalled, !$past(hit_valid_o && !hit_ready_i) ||
                (hit_valid_o && {hit_tag_o, hit_point_o, hit_x_o, hit_y_o, hit_z_o, hit_state_o, hit_dist_o} ==
                                $past({hit_tag_o, hit_point_o, hit_x_o, hit_y_o, hit_z_o, hit_state_o, hit_dist_o})))
  `VOXCD_ASSERT(DoneHeldWhileStalled, !$past(done_valid_o && !done_ready_i) ||
                (done_valid_o && {done_tag_o, done_hits_o, done_cycles_o, done_points_o, done_stalls_o} ==
                                 $past({done_tag_o, done_hits_o, done_cycles_o, done_points_o, done_stalls_o})))
  `VOXCD_ASSERT(OneRecordAtATime, !(hit_valid_o && done_valid_o))
  // The pipeline holds whenever the output slice cannot take a record; a record is never dropped.
  `VOXCD_ASSERT(EmitOnlyWhenReady, !(advance || emit) || out_ready)
  `VOXCD_ASSERT(PopOnlyAHeadJob, !head_pop || head_valid)
  // A job is in the queue or has a slot in R0 .. R(N-1) until its completion record: at most NumR + 2 are in flight.
  `VOXCD_ASSERT(InFlightBounded, 32'(in_flight_q) <= NumR + 2 && (in_flight_q != '0 || !emit_done))
  // R0 .. R4 advance only with the last register, and only when every lane of R4 has its word.
  `VOXCD_ASSERT(AdvanceWithTheLastRegister, !advance || (advance_out && !bank_wait))
  // The memories are loaded while the device is idle.
  `VOXCD_ASSERT(WriteOnlyWhileIdle, !((shell_we_i || map_we_i) && busy_o))
  // Every accepted job has a valid mode and map dimensions in 1 .. 2^DW.
  `VOXCD_ASSERT(JobModeValid, !(job_valid_i && job_ready_o) || job_mode_i != 2'd3)
  `VOXCD_ASSERT(JobDimsValid, !(job_valid_i && job_ready_o) ||
                (job_nx_i != 0 && job_ny_i != 0 && job_nz_i != 0 && job_nx_i <= (DW + 1)'(1 << DW) &&
                 job_ny_i <= (DW + 1)'(1 << DW) && job_nz_i <= (DW + 1)'(1 << DW)))

endmodule
