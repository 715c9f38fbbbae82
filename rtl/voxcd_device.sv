// voxcd_device: the voxel collision detection accelerator (docs/hardware.md has the diagram).
//
// Contract (docs/contract.md): for each job {tag, mode, mask, shell_base, shell_count, map_base, n, M, t,
// threshold}, every shell point p of the job is transformed exactly (acc = M*p + t), floored to a voxel index,
// bounds-checked at full width and looked up in the voxmap; a point inside the map whose voxel state has its bit in
// the mask is a hit. On a distance device (SB > 2) the voxmap holds signed node distances in 8 parity banks, the
// lookup interpolates the eight nodes around the cell to D (SB + 3*WB bits, exact), and an inside point with
// D <= threshold is a hit (the mask plays no part). ALL reports every hit, FIRST the lowest-index one, COUNT none;
// then a completion record per job. With SB = 2 the threshold is unused and hit_dist_o is 0.
// A sparse device (BL > 0, docs/contract.md "Sparse voxmaps and shells") also takes a job's {sparse, brick_base,
// brick_units}: sparse bit 0, its map is a table of coarse cells, uniform or bricks (a lookup reads the table word,
// then the brick word); bit 1, its shell is shell_count shell words, brick words (a 64-bit mask of a 4 x 4 x 4 brick
// of points and a step from the previous brick) and origin words, whose points the device generates. A dense device
// (BL = 0) ignores the three fields (valid jobs have them 0).
//
// Streams (valid/ready; a transfer happens in a cycle where both are high):
//   job   in : one job per transfer, into a 2-entry queue (voxcd_fifo; job_ready_o is low only when it is full).
//   hit   out: {tag, point, x, y, z, state, dist}, ascending point order within a job.
//   done  out: {tag, hits, cycles, points, stalls} after the job's last hit record.
// At most one of hit_valid_o / done_valid_o is high in a cycle, and records leave in stream order. A hit's point
// counts the job's points (a sparse shell's: the points it generates), so on a sparse device it has SAW + 6 bits and
// hits and points SAW + 7 (a shell of 2^SAW brick words holds up to 64 * 2^SAW points).
//
// Structure: an issue stage takes LANES consecutive points of the head job per cycle (one lane group, a "slot")
// and reads them from LANES shell banks; LANES lanes (voxcd_lane) carry the slot through N = PipeSlots + Depth
// (+ DistSlots) slot registers, R0..R5 at Depth 0 (R0..R8 on a distance device; each unit of Depth adds a register
// stage to every lane); the hit-test stage at the last register (voxcd_hit_stage) emits the slot's records, one per
// cycle, into the output slice (voxcd_skid: an output register and a skid register). The whole pipeline
// advances together: it holds (a) while the output slice cannot take a record (its registered ready is low: both
// of its registers are full, because the consumer has held the waiting record; a stall, and only those cycles
// count as stalls) and (b) while the last slot register still has more than one record to emit. The consumer's
// ready reaches only the output slice, never the pipeline's enables. Jobs follow each other with no drain: the
// slot after a job's last one is the next job's first.
// A sparse device has SparseSlots (SparseDistSlots on a distance device) more slot registers: the shell word
// register W before R0, which the issue stage fills (a dense job's slot, read from the shell banks; or a sparse
// shell's word, which W expands into max(1, ceil(set bits / LANES)) slots, one a cycle, lane i of a slot taking its
// i-th lowest set bit not yet taken: voxcd_shell_expand), and the lanes' entry, [rows] and brick word registers
// after R5 (voxcd_lane). R0 then holds the slot's points in a register of its own.
//
// Timing (the exact model is ref/timing.h): a job of c points takes max(1, ceil(c / LANES)) slots (a sparse shell:
// the sum over its words); a slot takes max(1, records) cycles at the hit test; the first slot of a job accepted in
// cycle a is there in cycle a + 1 + N, N slot registers as above. FIRST stops issuing at its first hit: the N - 1
// slots already issued are squashed and the issue stage leaves the job with one empty slot.
//
// The output slice adds no latency to the always-ready case (a record is on the pins in the cycle after its
// emission, as from a plain output register), and with an always-ready consumer it never holds the pipeline.
//
// Memories are written through the two write ports while the device is idle (busy_o low).
//
// Ports are plain vectors, one per record field, so that every configuration is one source and the Verilated C++
// and SystemC ports are plain integers. The code keeps to the subset of SystemVerilog that Verilator and yosys
// both read (one-dimensional packed vectors, one-level structs, explicit package references).
`ifndef VOXCD_ASSERT_SVH
`include "voxcd_assert.svh"
`endif
`ifndef VOXCD_PARAMS_SVH
`include "voxcd_params.svh"
`endif
module voxcd_device #(
  `VOXCD_DEVICE_PARAMS  // the widths, LANES, BANKS, Depth and BL (voxcd_arch_pkg.sv)
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
  input  logic [1:0]               job_sparse_i,       // bit 0: a sparse map, bit 1: a sparse shell (BL > 0 only)
  input  logic [MAW-1:0]           job_brick_base_i,   // a sparse map's first brick word
  input  logic [MAW:0]             job_brick_units_i,  // its units of brick memory

  // Hit stream.
  output logic                     hit_valid_o,
  input  logic                     hit_ready_i,
  output logic [TAGW-1:0]          hit_tag_o,
  output logic [(BL > 0 ? SAW + 6 : SAW)-1:0] hit_point_o,
  output logic [DW-1:0]            hit_x_o,
  output logic [DW-1:0]            hit_y_o,
  output logic [DW-1:0]            hit_z_o,
  output logic [1:0]               hit_state_o,
  output logic [SB+3*WB-1:0]       hit_dist_o,         // signed D; 0 on a 2-bit device

  // Completion stream.
  output logic                     done_valid_o,
  input  logic                     done_ready_i,
  output logic [TAGW-1:0]          done_tag_o,
  output logic [(BL > 0 ? SAW + 6 : SAW):0] done_hits_o,
  output logic [voxcd_arch_pkg::CW-1:0] done_cycles_o,
  output logic [(BL > 0 ? SAW + 6 : SAW):0] done_points_o,
  output logic [voxcd_arch_pkg::CW-1:0] done_stalls_o,

  // High while a job is queued or in flight or a record waits.
  output logic                     busy_o,
  // Bank conflict cycles since reset (cycles in which a read stage waited for a shared voxmap bank; 0 without BANKS).
  output logic [voxcd_arch_pkg::CW-1:0] conflicts_o
);

  localparam int unsigned CW    = voxcd_arch_pkg::CW;
  localparam bit          Dist  = SB > 2;                        // a distance device
  localparam bit          Sparse = BL > 0;                       // a sparse device
  localparam int unsigned IW    = SB + 3 * WB;                   // D, the threshold
  localparam int unsigned PtW   = Sparse ? SAW + 6 : SAW;        // a point index (a sparse shell: 64 a word)
  // The slot registers, and the ones whose fields the lanes read (voxcd_lane; at Depth 0: R1, R2, R2, R3, R3, R4, R5;
  // one later on a sparse device, whose register 0 is W).
  localparam bit          HasIn    = Depth > voxcd_arch_pkg::RankIn;
  localparam bit          HasSum   = Depth > voxcd_arch_pkg::RankSum;
  localparam bit          HasFloor = Depth > voxcd_arch_pkg::RankFloor;
  localparam bit          HasAddr  = Depth > voxcd_arch_pkg::RankAddr;
  localparam bit          HasRead  = Depth > voxcd_arch_pkg::RankRead;
  localparam int unsigned R0R    = 32'(Sparse);               // R0 (after W on a sparse device)
  localparam int unsigned ProdR  = R0R + 1 + 32'(HasIn);      // the products (the lanes read t here)
  localparam int unsigned AccR   = ProdR + 1 + 32'(HasSum);   // the accumulators (n: the bounds)
  localparam int unsigned YzR    = AccR + 32'(HasFloor);      // what the y + ny*z product reads (ny)
  localparam int unsigned R3R    = YzR + 1;                   // the index and yz (nx)
  localparam int unsigned LinR   = R3R + 32'(HasAddr);        // what R4's address is computed from (map_base, hxy)
  localparam int unsigned AddrR  = LinR + 1;                  // R4: the voxmap address (the table port reads it)
  localparam int unsigned WordR  = AddrR + 1;                 // R5: the voxmap (table) word
  // A sparse device's entry E (and rows F on a distance device), whose last register the brick port reads, and the
  // brick word K; the register before READ (R5, or K), where a 2-bit device with READ sees a FIRST hit.
  localparam int unsigned BrickR = WordR + (Sparse ? (Dist ? 2 : 1) : 0);
  localparam int unsigned KR     = BrickR + 1;
  localparam int unsigned PreR   = Sparse ? KR : WordR;
  localparam int unsigned NumR   = PreR + 1 + 32'(HasRead) + (Dist ? voxcd_arch_pkg::DistSlots : 0);
  localparam int unsigned ThrW  = Dist ? IW : 1;                 // job fields a 2-bit device does not keep
  localparam int unsigned HxyW  = Dist ? 2 * DW + 1 : 1;
  localparam int unsigned SpW   = Sparse ? 2 : 1;                // job fields a dense device does not keep
  localparam int unsigned BbW   = Sparse ? MAW : 1;
  localparam int unsigned BuW   = Sparse ? MAW + 1 : 1;
  localparam int unsigned CxW   = Sparse ? DW + 1 : 1;
  localparam int unsigned BLW   = Sparse ? BL : 1;
  localparam int unsigned SlotPts = TX == 1 ? 1 : LANES;          // a dense-shell slot's points (brick lanes: 1)
  localparam int unsigned AccW  = ((MW + PW + 2 > TW) ? MW + PW + 2 : TW) + 1;  // DeviceConfig::acc_width()
  localparam int unsigned LgL   = $clog2(LANES);
  localparam int unsigned RotW  = LgL > 0 ? LgL : 1;
  localparam int unsigned RowW  = SAW - LgL;                      // rows of one shell bank
  localparam int unsigned SeqW  = $clog2(NumR + 2) + 1;           // tells apart every job in flight
  localparam int unsigned InFlW = $clog2(NumR + 3);               // counts the jobs in flight: at most NumR + 2
  localparam bit          Banked = BANKS > 0;                      // the lanes share one voxmap in BANKS banks
  localparam int unsigned NPar  = Dist ? 8 : 1;                    // words a lane reads per point (its requests)
  localparam int unsigned NReq  = LANES * NPar;                    // request r: lane r / NPar, parity bank r % NPar
  localparam int unsigned NumB  = Banked ? BANKS * NPar : 1;       // shared banks: word w in bank w % NumB
  localparam int unsigned LgB   = Banked ? $clog2(NumB) : 0;

  // ---- Jobs and slots (the output records: voxcd_hit_stage) ----
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
    logic [SpW-1:0]         sparse;       // bit 0 a sparse map, bit 1 a sparse shell (sparse devices; else 0)
    logic [BbW-1:0]         brick_base;   // a sparse map's bricks (sparse devices)
    logic [BuW-1:0]         brick_units;
    logic [2*CxW-1:0]       cxy;          // {Cy, Cx} = ceil(n / 2^BL): a sparse map's coarse extents
    logic                   fresh;        // accepted with every earlier job's completion record emitted
    logic [CW-1:0]          stamp;        // cycle in which the job was accepted
    logic [CW-1:0]          stall_stamp;  // stall cycles up to and including that cycle
  } job_t;
  localparam int unsigned JobW = TAGW + 2 + 4 + SAW + (SAW + 1) + MAW + 3 * (DW + 1) + 9 * MW + 3 * TW + ThrW +
                                 HxyW + SpW + BbW + BuW + 2 * CxW + 1 + 2 * CW;

  // What the slot registers after R0 keep of a slot's job (below): the map, and the fields of the hit test.
  typedef struct packed {
    logic [3*(DW+1)-1:0] n;
    logic [MAW-1:0]      map_base;
    logic [HxyW-1:0]     hxy;
    logic                coarse;  // a sparse map (its index products take the coarse cell)
    logic [2*CxW-1:0]    cxy;
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
    logic              last;    // the job's last slot (W holding a sparse shell word: the job's last word)
    logic [PtW:0]      k;       // point index (relative to shell_base; a sparse shell's generated points) of lane 0
    logic [LANES-1:0]  lanes;   // lanes holding a point of the job
    logic [RotW-1:0]   rot;     // shell bank of lane 0 (W holding a sparse shell word: the word's bank)
  } meta_t;
  localparam int unsigned MetaW = 1 + SeqW + 1 + (PtW + 1) + LANES + RotW;

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
  logic [DW:0] cx_in, cy_in;  // C = ceil(n / 2^BL), a sparse map's coarse extent
  assign hx_in = (job_nx_i >> 1) + (DW + 1)'(1);
  assign hy_in = (job_ny_i >> 1) + (DW + 1)'(1);
  assign cx_in = (job_nx_i + (DW + 1)'((1 << BLW) - 1)) >> BLW;
  assign cy_in = (job_ny_i + (DW + 1)'((1 << BLW) - 1)) >> BLW;

  // One assignment, in job_t's field order (so that a simulator packs it only where the queue stores it).
  assign job_in = {job_tag_i, job_mode_i, job_mask_i, job_shell_base_i, job_shell_count_i, job_map_base_i,
                   job_nz_i, job_ny_i, job_nx_i,
                   job_m22_i, job_m21_i, job_m20_i, job_m12_i, job_m11_i, job_m10_i, job_m02_i, job_m01_i, job_m00_i,
                   job_t2_i, job_t1_i, job_t0_i,
                   Dist ? ThrW'(job_threshold_i) : ThrW'(0),
                   Dist ? HxyW'(HxyW'(hx_in) * HxyW'(hy_in)) : HxyW'(0),
                   Sparse ? SpW'(job_sparse_i) : SpW'(0),
                   Sparse ? BbW'(job_brick_base_i) : BbW'(0),
                   Sparse ? BuW'(job_brick_units_i) : BuW'(0),
                   Sparse ? {CxW'(cy_in), CxW'(cx_in)} : (2 * CxW)'(0),
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
  // The last register (the hit test) advances when its records are out (advance_out). With shared banks a read stage
  // may wait for a bank: the brick stage (BrickR, sparse devices) first, then the table stage (R4). While the brick
  // stage waits, the registers up to it hold and K takes an empty slot (advance_mid low); while the table stage
  // waits, R0 .. R4 and the issue stage hold and R5 takes an empty slot (advance low). Without shared banks the three
  // enables are the same.
  logic            advance;     // the issue stage and the registers up to R4 advance
  logic            advance_mid; // R5 up to the brick stage advance (sparse devices; advance_out elsewhere)
  logic            advance_out; // K (R5 on a dense device) and the registers after it advance
  logic            table_wait;  // R4 has requests left after this cycle's round (shared voxmap banks)
  logic            brick_wait;  // the brick stage has requests left after this cycle's round
  logic            first_stop;  // the last register holds the first hit of a FIRST job: stop issuing it
  logic [SeqW-1:0] first_stop_seq;

  // ---- Issue stage ----
  logic [SAW:0]    next_point_d, next_point_q;  // next point (a sparse shell: word) of the head job
  logic [SeqW-1:0] head_seq_d, head_seq_q;      // sequence number of the head job
  logic            head_sparse_shell;           // the head job's shell is sparse
  logic            head_last_slot;              // the head job's remaining points fit one slot (a sparse shell: its
                                                // last word, or no word)
  logic            head_stopped;                // FIRST has found the head job's hit: issue no more of it
  logic            issue_taken;                 // the issue stage hands its slot (or shell word) on this cycle
  logic [SAW:0]    head_remaining;
  logic [SAW:0]    first_addr;                  // shell address of lane 0 (a sparse shell: of the word)
  logic [RotW-1:0] rot;

  assign head_sparse_shell = Sparse && head_job.sparse[SpW-1];
  assign head_remaining    = head_job.shell_count - next_point_q;
  assign head_last_slot    = head_sparse_shell ? head_remaining <= (SAW + 1)'(1)
                                               : head_remaining <= (SAW + 1)'(SlotPts);
  assign head_stopped      = first_stop && (first_stop_seq == head_seq_q);
  assign head_pop          = head_valid && (head_stopped ? advance : (issue_taken && head_last_slot));
  assign first_addr        = (SAW + 1)'(head_job.shell_base) + next_point_q;
  assign rot               = RotW'(32'(first_addr) % LANES);

  always_comb begin
    next_point_d = next_point_q;
    head_seq_d   = head_seq_q;
    if (head_pop) begin
      next_point_d = '0;
      head_seq_d   = head_seq_q + 1'b1;
    end else if (issue_taken && head_valid) begin
      next_point_d = next_point_q + (head_sparse_shell ? (SAW + 1)'(1) : (SAW + 1)'(SlotPts));
    end
  end

  `VOXCD_FF(next_point_q, next_point_d, '0)
  `VOXCD_FF(head_seq_q, head_seq_d, '0)

  // The slot (a sparse shell: the word) the issue stage offers; for a sparse shell's word, k and lanes are set in W.
  meta_t issue;
  always_comb begin
    issue       = '0;
    issue.valid = head_valid && !head_stopped;
    issue.seq   = head_seq_q;
    issue.last  = head_last_slot;
    issue.k     = (PtW + 1)'(next_point_q);
    issue.rot   = rot;
    for (int i = 0; i < LANES; i++)
      issue.lanes[i] = i < SlotPts && (next_point_q + (SAW + 1)'(i)) < head_job.shell_count;
    if (head_sparse_shell) issue.lanes = '0;
  end

  // ---- Slot registers R0 .. R(N-1) (W, R0, .. on a sparse device): bookkeeping and job, shifting with them ----
  // The registers up to R4 (AddrR) advance with the issue stage (advance); R5 up to the brick stage with advance_mid,
  // R5 taking an empty slot while R4 waits for a shared voxmap bank; K (R5 on a dense device) and the registers after
  // it with the last register (advance_out), K taking an empty slot while the brick stage waits. Each register is a
  // register of its own (g_slot[s]: a simulator keeps it in its own words and orders the chain with no copy; an array
  // of them would be copied through temporaries every cycle).
  meta_t w_next, w_out;         // sparse devices: W's content in the next cycle, and the slot W hands R0
  logic [NumR-1:0] slot_valid;  // the valid bit of each slot register
  for (genvar s = 0; s < NumR; s++) begin : g_slot
    logic [MetaW-1:0] meta_q, meta_in;
    logic             shift;
    if (s == 0) begin : g_issue
      assign meta_in = Sparse ? w_next : issue;
    end else if (Sparse && s == R0R) begin : g_r0
      assign meta_in = w_out;
    end else if (s == WordR) begin : g_word
      assign meta_in = advance ? g_slot[s - 1].meta_q : '0;  // '0: an empty slot
    end else if (Sparse && s == KR) begin : g_brick_word
      assign meta_in = advance_mid ? g_slot[s - 1].meta_q : '0;
    end else begin : g_next
      assign meta_in = g_slot[s - 1].meta_q;
    end
    assign shift = (s <= AddrR) ? advance : (Sparse && s <= BrickR) ? advance_mid : advance_out;
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni)    meta_q <= '0;
      else if (shift) meta_q <= meta_in;
    end
    assign slot_valid[s] = meta_q[MetaW - 1];
  end

  // ---- Shell banks: address a is in bank a % LANES, row a / LANES ----
  // The issue stage reads them: its slot's LANES points (into R0, or W on a sparse device), or a sparse shell's word
  // (into W, from bank a % LANES).
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
      .re_i   (issue_taken),
      .raddr_i(row),
      .rdata_o(bank_rdata[b])
    );
  end

  // The job of register 0 (R0; W on a sparse device) and of R0; the lanes' points.
  job_t            reg0_job_q, r0_job;
  meta_t           w_meta;     // sparse devices: W's slot register (g_slot[0]); declared here: yosys resolves struct
  job_t            r0_job_q;   // members only of module-level variables. R0's job register (sparse devices)
  logic [LANES*3*PW-1:0] lane_point;  // lane l's point at [l*3*PW +: 3*PW]
  logic [3*AccW-1:0] lane_base;       // brick lanes (TX = 1): the slot's base M o' + t in PROD, {z, y, x}
  logic            w_stop;  // sparse devices: FIRST stops W's job, W takes an empty slot
  always_ff @(posedge clk_i) begin
    if (issue_taken) reg0_job_q <= head_job;
  end

  if (Sparse) begin : g_w
    // ---- W: the shell word register (sparse devices) ----
    // W holds a dense job's slot for one cycle (its points on the shell banks' outputs), or a sparse shell's word
    // for as many cycles as it has slots: its mask's set bits LANES at a time (w_rem_q: those not yet in a slot after
    // the word's first), the brick origin moved by the word's step (or set by an origin word) for its points.
    localparam int unsigned Half = PF > 0 ? PF - 1 : 0;
    logic             w_word_q;    // W holds a sparse shell's word
    logic             w_first_q;   // W's slot is its word's first
    logic             w_jfirst_q;  // W's word is its job's first (the origin starts at 0)
    logic [63:0]      w_rem_q, rem, rem_next;
    logic [3*PW-1:0]  org_q, org_eff, org_set, org_moved;
    logic [3*PW-1:0]  word;        // the word on its bank's output
    logic             is_origin, word_done, w_free;
    logic [LANES-1:0] exp_lanes;
    logic [6*LANES-1:0] exp_bit;
    logic [PtW:0]     cnt;         // W's slot's points

    logic [RotW-1:0]  word_bank;
    assign w_meta    = g_slot[0].meta_q;
    assign word_bank = w_meta.rot;
    assign word      = bank_rdata[word_bank];
    assign is_origin = word[3*PW-1];
    assign rem       = w_first_q ? (is_origin ? 64'd0 : word[63:0]) : w_rem_q;

    voxcd_shell_expand #(.LANES(LANES)) u_expand (
      .rem_i  (rem),
      .lanes_o(exp_lanes),
      .bit_o  (exp_bit),
      .rem_o  (rem_next)
    );
    always_comb begin
      cnt = '0;
      for (int l = 0; l < LANES; l++) cnt = cnt + (PtW + 1)'(exp_lanes[l]);
    end
    assign word_done = rem_next == '0;
    assign w_free    = !w_word_q || word_done;

    // The brick origin of W's word: set by an origin word (z has PW - 1 bits), or the previous word's (0 for a job's
    // first) moved by the step s * 4 * 2^PF, each sum wrapping at PW bits.
    for (genvar i = 0; i < 3; i++) begin : g_origin
      logic [PW-1:0] base, step;
      assign base = w_jfirst_q ? '0 : org_q[i*PW +: PW];
      assign step = PW'($signed(word[64 + 2*i +: 2])) << (PF + 2);
      assign org_moved[i*PW +: PW] = base + step;
      if (i < 2) begin : g_xy
        assign org_set[i*PW +: PW] = word[i*PW +: PW];
      end else begin : g_z
        assign org_set[i*PW +: PW] = PW'($signed(word[2*PW +: PW-1]));
      end
    end
    assign org_eff = !w_first_q ? org_q : is_origin ? org_set : org_moved;

    // W's slot, to R0; a slot of a word that does not end the word takes every lane.
    always_comb begin
      w_out = w_meta;
      if (w_word_q) begin
        w_out.lanes = exp_lanes;
        w_out.last  = w_meta.last && word_done;
      end
    end
    assign w_stop = first_stop && w_meta.valid && (w_meta.seq == first_stop_seq) && !w_out.last;
    assign issue_taken = advance && w_free && !w_stop;

    // W's next content: its word's next slot, or what the issue stage offers (the k of a sparse shell's later word
    // follows W's slot), or an empty slot where FIRST stops the job.
    always_comb begin
      w_next = '0;
      if (w_stop) begin
        w_next = '0;
      end else if (!w_free) begin
        w_next   = w_meta;
        w_next.k = w_meta.k + cnt;
      end else begin
        w_next = issue;
        if (head_sparse_shell) w_next.k = next_point_q == '0 ? '0 : w_meta.k + cnt;
      end
    end

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        w_word_q <= 1'b0;
      end else if (advance) begin
        if (w_stop)           w_word_q <= 1'b0;
        else if (issue_taken) w_word_q <= head_valid && head_sparse_shell && head_job.shell_count != '0;
      end
    end
    // The word's state: read only while W holds a word, no reset.
    always_ff @(posedge clk_i) begin
      if (advance) begin
        w_rem_q <= rem_next;
        if (w_word_q) org_q <= org_eff;
        w_first_q  <= issue_taken;
        w_jfirst_q <= issue_taken && next_point_q == '0;
      end
    end

    // ---- R0: the slot's points (a dense slot's from the shell banks in lane order, or the word's); brick lanes
    // take {k, d} instead: the point's offset in the brick and the axes whose sum wrapped (a dense slot's one point
    // goes to the transform unit, lane 0 adding nothing to its base) ----
    for (genvar l = 0; l < LANES; l++) begin : g_point
      logic [3*PW-1:0] gen;
      logic [2:0]      wrapped;  // axis i's sum wrapped at PW bits (a non-negative origin, a negative point)
      for (genvar i = 0; i < 3; i++) begin : g_axis
        // Offset (b & 3, (b >> 2) & 3, b >> 4) of bit b in the shell brick, at the centre of its shell voxel.
        logic [1:0] d;
        assign d = exp_bit[6*l + 2*i +: 2];
        assign gen[i*PW +: PW] = org_eff[i*PW +: PW] + (PW'(d) << PF) + PW'(PF > 0 ? (1 << Half) : 0);
        assign wrapped[i] = !org_eff[i*PW + PW - 1] && gen[i*PW + PW - 1];
      end
      logic [3*PW-1:0] p_r0_q;  // a register of its own per lane (no array written from several processes)
      if (TX == 1) begin : g_brick_point
        always_ff @(posedge clk_i) begin
          if (advance) p_r0_q <= w_word_q ? (3*PW)'({wrapped, exp_bit[6*l +: 6]}) : '0;
        end
      end else begin : g_mul_point
        logic [RotW-1:0] src;  // the shell bank of lane l's point in a dense slot
        assign src = RotW'(32'(word_bank) + l);
        always_ff @(posedge clk_i) begin
          if (advance) p_r0_q <= w_word_q ? gen : bank_rdata[src];
        end
        logic unused_wrapped;  // lanes that multiply take the wrapped point itself
        assign unused_wrapped = ^wrapped;
      end
      assign lane_point[l*3*PW +: 3*PW] = p_r0_q;
    end

    // ---- The transform unit (brick lanes): the slot's base M o' + t, o' the word's origin plus the half voxel h
    // (PW + 1 bits: exact), or a dense slot's point; its products one register before PROD (R0, or IN), the base in
    // PROD, where the lanes add it to their terms ----
    if (TX == 1) begin : g_base
      localparam int unsigned OW = PW + 1;
      localparam int unsigned BpW = MW + OW;
      logic [3*OW-1:0] o_w;  // o' of W's slot
      for (genvar i = 0; i < 3; i++) begin : g_o
        assign o_w[i*OW +: OW] = w_word_q ? OW'($signed(org_eff[i*PW +: PW])) + OW'(PF > 0 ? (1 << Half) : 0)
                                          : OW'($signed(bank_rdata[word_bank][i*PW +: PW]));
      end
      logic [3*OW-1:0] o_p;  // o' where the products read it: W's, or R0's with IN
      logic [9*MW-1:0] m_p;  // and that slot's matrix
      if (HasIn) begin : g_o_r0
        logic [3*OW-1:0] o_r0_q;
        always_ff @(posedge clk_i) begin
          if (advance) o_r0_q <= o_w;
        end
        assign o_p = o_r0_q;
        assign m_p = r0_job.m;
      end else begin : g_o_w
        assign o_p = o_w;
        assign m_p = reg0_job_q.m;
      end
      for (genvar i = 0; i < 3; i++) begin : g_row
        logic [BpW-1:0]  bx_q, by_q, bz_q;  // the device's nine multipliers, three a coordinate
        logic [AccW-1:0] base_q;
        always_ff @(posedge clk_i) begin
          if (advance) begin
            bx_q <= BpW'($signed(m_p[(3*i+0)*MW +: MW])) * BpW'($signed(o_p[0*OW +: OW]));
            by_q <= BpW'($signed(m_p[(3*i+1)*MW +: MW])) * BpW'($signed(o_p[1*OW +: OW]));
            bz_q <= BpW'($signed(m_p[(3*i+2)*MW +: MW])) * BpW'($signed(o_p[2*OW +: OW]));
            base_q <= AccW'($signed(t_r[(ProdR-1)*3*TW + i*TW +: TW])) + AccW'($signed(bx_q)) +
                      AccW'($signed(by_q)) + AccW'($signed(bz_q));
          end
        end
        assign lane_base[i*AccW +: AccW] = base_q;
      end
    end else begin : g_no_base
      assign lane_base = '0;
    end
    always_ff @(posedge clk_i) begin
      if (advance) r0_job_q <= reg0_job_q;
    end
    assign r0_job = r0_job_q;

    // A slot of a word that does not end its word is full: a slot never spans two shell words.
    `VOXCD_ASSERT(ShellSlotWithinAWord, !(w_word_q && w_meta.valid && !word_done) || (&exp_lanes))
    // FIRST stops W's job only where nothing waits for a bank: the job's slots up to the hit read nothing then.
    `VOXCD_ASSERT(StopWhenIssuing, !w_stop || advance)
    // Coverage: a sparse shell's word that takes more than one slot, and FIRST stopping a job in the middle of one.
    `VOXCD_COVER(CoverShellWordOfSeveralSlots, advance && w_word_q && w_meta.valid && !word_done)
    `VOXCD_COVER(CoverFirstStopsAShellWord, w_stop && w_word_q && !word_done)
  end else begin : g_no_w
    assign issue_taken = advance;
    assign w_stop      = 1'b0;
    assign w_next      = '0;
    assign w_out       = '0;
    assign r0_job      = reg0_job_q;
    assign w_meta      = '0;
    assign r0_job_q    = '0;
    assign lane_base   = '0;
    for (genvar l = 0; l < LANES; l++) begin : g_point
      logic [RotW-1:0] src;  // the shell bank of lane l's point
      assign src = RotW'(32'(g_slot[0].meta_q[RotW-1:0]) + l);
      assign lane_point[l*3*PW +: 3*PW] = bank_rdata[src];
    end
  end

  // The job travels with its slot, each register keeping what the stages from it on read: R0 the whole job (the
  // lanes read M there, or from IN's M register), R1 .. ProdR the translation (read at ProdR), R1 .. LinR the map
  // (n read at AccR, ny at YzR, nx at R3R, map_base and hxy at LinR; a sparse map's coarse extents likewise), R1 ..
  // R5 a sparse map's bricks (read at R5), and R1 .. R(N-1) the fields of the hit test (on a sparse device the
  // registers are one later: R0 is register 1). Job fields are read only where their slot is valid: no reset.
  localparam int unsigned MapW   = 3 * (DW + 1) + MAW + HxyW + 1 + 2 * CxW;
  localparam int unsigned BrickW = 1 + BbW + BuW;
  test_t r0_test, pre_test, last_test;
  map_t  acc_map, yz_map, r3_map, lin_map;  // the map fields of the registers AccR, YzR, R3R, LinR
  logic [BrickW-1:0] word_bricks, stage_bricks;  // {sparse map, brick_base, brick_units} of R5 and the brick stage
  assign r0_test = {r0_job.tag, r0_job.mode, r0_job.mask, r0_job.thr, r0_job.fresh, r0_job.stamp,
                    r0_job.stall_stamp};
  // The matrix the lanes' multipliers read: R0's, or with IN one register later, beside the lanes' registered points
  // (one register for every lane: the same M for the whole slot).
  logic [9*MW-1:0] prod_m;
  voxcd_stage #(.Width(9*MW), .Enable(HasIn)) u_in_m (.clk_i(clk_i), .en_i(advance), .d_i(r0_job.m), .q_o(prod_m));
  // Five chains of registers, Rs's at [s*Width +: Width] of each (R0's at R0R): the hit test's fields in two (the
  // job's labels, and its 64 bits of stamps: each fits a simulator's word), the translation, the map and a sparse
  // map's bricks. Each register advances with its slot register.
  localparam int unsigned InfoW = TestW - 2*CW;
  logic [NumR*InfoW-1:0]     info_r;
  logic [NumR*2*CW-1:0]      stamps_r;
  logic [(ProdR+1)*3*TW-1:0] t_r;
  logic [(LinR+1)*MapW-1:0]  map_r;
  logic [(BrickR+1)*BrickW-1:0] bricks_r;
  assign {info_r[R0R*InfoW +: InfoW], stamps_r[R0R*2*CW +: 2*CW]} = r0_test;
  assign t_r[R0R*3*TW +: 3*TW]        = r0_job.t;
  assign map_r[R0R*MapW +: MapW]      = {r0_job.n, r0_job.map_base, r0_job.hxy, Sparse && r0_job.sparse[0],
                                         r0_job.cxy};
  assign bricks_r[R0R*BrickW +: BrickW] = {Sparse && r0_job.sparse[0], r0_job.brick_base, r0_job.brick_units};
  if (Sparse) begin : g_chain_w  // register W keeps nothing of these
    assign info_r[0 +: InfoW]     = '0;
    assign stamps_r[0 +: 2*CW]    = '0;
    assign t_r[0 +: 3*TW]         = '0;
    assign map_r[0 +: MapW]       = '0;
    assign bricks_r[0 +: BrickW]  = '0;
  end
  for (genvar s = R0R + 1; s < NumR; s++) begin : g_test
    logic en;
    assign en = (s <= AddrR) ? advance : (Sparse && s <= BrickR) ? advance_mid : advance_out;
    voxcd_stage #(.Width(InfoW)) u_info (
      .clk_i(clk_i), .en_i(en), .d_i(info_r[(s-1)*InfoW +: InfoW]), .q_o(info_r[s*InfoW +: InfoW]));
    voxcd_stage #(.Width(2*CW)) u_stamps (
      .clk_i(clk_i), .en_i(en), .d_i(stamps_r[(s-1)*2*CW +: 2*CW]), .q_o(stamps_r[s*2*CW +: 2*CW]));
  end
  for (genvar s = R0R + 1; s <= ProdR; s++) begin : g_t
    voxcd_stage #(.Width(3*TW)) u_t (
      .clk_i(clk_i), .en_i(advance), .d_i(t_r[(s-1)*3*TW +: 3*TW]), .q_o(t_r[s*3*TW +: 3*TW]));
  end
  for (genvar s = R0R + 1; s <= LinR; s++) begin : g_map
    voxcd_stage #(.Width(MapW)) u_map (
      .clk_i(clk_i), .en_i(advance), .d_i(map_r[(s-1)*MapW +: MapW]), .q_o(map_r[s*MapW +: MapW]));
  end
  if (Sparse) begin : g_bricks
    for (genvar s = R0R + 1; s <= BrickR; s++) begin : g_brick
      voxcd_stage #(.Width(BrickW)) u_bricks (
        .clk_i(clk_i), .en_i((s <= AddrR) ? advance : advance_mid), .d_i(bricks_r[(s-1)*BrickW +: BrickW]),
        .q_o(bricks_r[s*BrickW +: BrickW]));
    end
  end else begin : g_no_bricks
    for (genvar s = R0R + 1; s <= BrickR; s++) begin : g_brick
      assign bricks_r[s*BrickW +: BrickW] = '0;
    end
  end
  assign pre_test     = {info_r[PreR*InfoW +: InfoW], stamps_r[PreR*2*CW +: 2*CW]};
  assign last_test    = {info_r[(NumR-1)*InfoW +: InfoW], stamps_r[(NumR-1)*2*CW +: 2*CW]};
  assign acc_map      = map_r[AccR*MapW +: MapW];
  assign yz_map       = map_r[YzR*MapW +: MapW];
  assign r3_map       = map_r[R3R*MapW +: MapW];
  assign lin_map      = map_r[LinR*MapW +: MapW];
  assign word_bricks  = bricks_r[WordR*BrickW +: BrickW];
  assign stage_bricks = bricks_r[BrickR*BrickW +: BrickW];

  // What each stage reads of its slot's bookkeeping: R4's, the brick stage's, the register before READ's and the
  // last register's, where the hit test is.
  meta_t r4_slot, brick_slot, pre_slot, last_slot;  // r4_slot, brick_slot: the shared voxmap banks' (BANKS > 0)
  assign r4_slot    = g_slot[AddrR].meta_q;
  assign brick_slot = g_slot[BrickR].meta_q;
  assign pre_slot   = g_slot[PreR].meta_q;
  assign last_slot  = g_slot[NumR - 1].meta_q;

  // ---- Lanes ----
  logic [NReq-1:0]       lane_read;     // R4: request r's point is inside its map and reads a voxmap word
  logic [NReq*MAW-1:0]   lane_addr;     // R4: the word it reads (lane r / NPar; parity bank r % NPar on a distance
                                        // device)
  logic [NReq*MEMW-1:0]  lane_word;     // R5: the word from the shared banks (Banked)
  logic [NReq-1:0]       lane_bread;    // the brick stage: request r's point reads a brick word (sparse devices)
  logic [NReq*MAW-1:0]   lane_baddr;
  logic [NReq*MEMW-1:0]  lane_bword;    // K: the brick word from the shared banks
  logic [LANES-1:0]      lane_inside;
  logic [LANES-1:0]      lane_inside_pre;  // the register before READ (2-bit lanes)
  logic [LANES*2-1:0]    lane_state_pre;
  logic [LANES*2-1:0]    lane_state;
  logic [LANES*3*DW-1:0] lane_voxel;
  logic [LANES*IW-1:0]   lane_dist;

  for (genvar l = 0; l < LANES; l++) begin : g_lane
    voxcd_lane #(
      `VOXCD_LANE_PARAM_MAP,
      .SharedMap(Banked)
    ) u_lane (
      .clk_i        (clk_i),
      .en_i         (advance),
      .en_mid_i     (advance_mid),
      .en_out_i     (advance_out),
      .addr_o       (lane_addr[NPar*MAW*l +: NPar*MAW]),
      .read_o       (lane_read[NPar*l +: NPar]),
      .word_i       (lane_word[NPar*MEMW*l +: NPar*MEMW]),
      .baddr_o      (lane_baddr[NPar*MAW*l +: NPar*MAW]),
      .bread_o      (lane_bread[NPar*l +: NPar]),
      .bword_i      (lane_bword[NPar*MEMW*l +: NPar*MEMW]),
      .map_we_i     (map_we_i),
      .map_waddr_i  (map_waddr_i),
      .map_wdata_i  (map_wdata_i),
      .point_i      (lane_point[l*3*PW +: 3*PW]),
      .m_i          (prod_m),
      .t_i          (t_r[ProdR*3*TW +: 3*TW]),
      .base_i       (lane_base),
      .n_i          (acc_map.n),
      .ny_i         (yz_map.n[DW+1 +: DW+1]),
      .sparse_yz_i  (yz_map.coarse),
      .cy_i         ((DW + 1)'(yz_map.cxy[CxW +: CxW])),
      .nx_i         (r3_map.n[DW:0]),
      .sparse_r3_i  (r3_map.coarse),
      .cx_i         ((DW + 1)'(r3_map.cxy[0 +: CxW])),
      .map_base_i   (lin_map.map_base),
      .hxy_i        ((2 * DW + 1)'(lin_map.hxy)),
      .sparse_lin_i (lin_map.coarse),
      .brick_base_i (MAW'(word_bricks[BuW +: BbW])),
      .brick_units_i((MAW + 1)'(word_bricks[0 +: BuW])),
      .inside_pre_o (lane_inside_pre[l]),
      .state_pre_o  (lane_state_pre[2*l +: 2]),
      .inside_o     (lane_inside[l]),
      .state_o      (lane_state[2*l +: 2]),
      .dist_o       (lane_dist[IW*l +: IW]),
      .voxel_o      (lane_voxel[3*DW*l +: 3*DW])
    );
  end

  logic [CW-1:0]    conflicts;     // bank conflict cycles since reset (voxcd_shared_banks)

  // ---- Hit test and record emission at the last register (R5, R8 on a distance device; K, or the registers after it,
  // on a sparse one), and the output slice: voxcd_hit_stage ----
  logic             out_ready;   // the output slice takes a record (a register: no path from *_ready_i)
  logic             slot_busy;   // after this cycle's record the last slot has another one to emit
  logic             emit;        // a record enters the output slice
  logic             first_hit;   // the last slot holds the first hit of a FIRST job
  logic             found;       // a FIRST job's hit has been emitted (its job: found_seq); its later slots squashed
  logic [SeqW-1:0]  found_seq;
  logic             out_valid;   // a record waits in the output slice
  voxcd_hit_stage #(
    .LANES(LANES), .TAGW(TAGW), .SAW(SAW), .DW(DW), .SB(SB), .WB(WB), .BL(BL), .SeqW(SeqW)
  ) u_hit_stage (
    .clk_i             (clk_i),
    .rst_ni            (rst_ni),
    .advance_out_i     (advance_out),
    .slot_valid_i      (last_slot.valid),
    .slot_seq_i        (last_slot.seq),
    .slot_last_i       (last_slot.last),
    .slot_k_i          (last_slot.k),
    .slot_lanes_i      (last_slot.lanes),
    .tag_i             (last_test.tag),
    .mode_i            (last_test.mode),
    .mask_i            (last_test.mask),
    .thr_i             (IW'(last_test.thr)),
    .fresh_i           (last_test.fresh),
    .stamp_i           (last_test.stamp),
    .stall_stamp_i     (last_test.stall_stamp),
    .inside_i          (lane_inside),
    .state_i           (lane_state),
    .voxel_i           (lane_voxel),
    .dist_i            (lane_dist),
    .now_i             (now_q),
    .stall_total_i     (stall_total_q),
    .stall_total_next_i(stall_total_d),
    .out_ready_o       (out_ready),
    .slot_busy_o       (slot_busy),
    .emit_o            (emit),
    .emit_done_o       (emit_done),
    .first_hit_o       (first_hit),
    .first_stop_o      (first_stop),
    .found_o           (found),
    .found_seq_o       (found_seq),
    .busy_o            (out_valid),
    .hit_valid_o       (hit_valid_o),
    .hit_ready_i       (hit_ready_i),
    .hit_tag_o         (hit_tag_o),
    .hit_point_o       (hit_point_o),
    .hit_x_o           (hit_x_o),
    .hit_y_o           (hit_y_o),
    .hit_z_o           (hit_z_o),
    .hit_state_o       (hit_state_o),
    .hit_dist_o        (hit_dist_o),
    .done_valid_o      (done_valid_o),
    .done_ready_i      (done_ready_i),
    .done_tag_o        (done_tag_o),
    .done_hits_o       (done_hits_o),
    .done_cycles_o     (done_cycles_o),
    .done_points_o     (done_points_o),
    .done_stalls_o     (done_stalls_o)
  );

  // ---- Pipeline control: the enables (above) ----
  assign stall          = !out_ready;
  assign advance_out    = out_ready && !slot_busy;
  assign advance_mid    = advance_out && !brick_wait;
  assign advance        = advance_mid && !table_wait;
  assign first_stop_seq = last_slot.seq;

  // ---- Shared voxmap banks (BANKS > 0, voxcd_shared_banks): the lanes read one voxmap; else each its own copy ----
  if (Banked) begin : g_banks
    voxcd_shared_banks #(
      .LANES(LANES), .MEMW(MEMW), .MAW(MAW), .SB(SB), .BANKS(BANKS), .Depth(Depth), .BL(BL), .SeqW(SeqW)
    ) u_shared_banks (
      .clk_i         (clk_i),
      .rst_ni        (rst_ni),
      .map_we_i      (map_we_i),
      .map_waddr_i   (map_waddr_i),
      .map_wdata_i   (map_wdata_i),
      .advance_i     (advance),
      .advance_mid_i (advance_mid),
      .advance_out_i (advance_out),
      .r4_valid_i    (r4_slot.valid),
      .r4_seq_i      (r4_slot.seq),
      .r4_lanes_i    (r4_slot.lanes),
      .brick_valid_i (brick_slot.valid),
      .brick_seq_i   (brick_slot.seq),
      .brick_lanes_i (brick_slot.lanes),
      .brick_sparse_i(stage_bricks[BrickW-1]),
      .pre_valid_i   (pre_slot.valid),
      .pre_seq_i     (pre_slot.seq),
      .pre_lanes_i   (pre_slot.lanes),
      .pre_mode_i    (pre_test.mode),
      .pre_mask_i    (pre_test.mask),
      .inside_pre_i  (lane_inside_pre),
      .state_pre_i   (lane_state_pre),
      .found_i       (found),
      .found_seq_i   (found_seq),
      .last_hit_i    (first_hit),
      .last_seq_i    (last_slot.seq),
      .read_i        (lane_read),
      .addr_i        (lane_addr),
      .word_o        (lane_word),
      .bread_i       (lane_bread),
      .baddr_i       (lane_baddr),
      .bword_o       (lane_bword),
      .table_wait_o  (table_wait),
      .brick_wait_o  (brick_wait),
      .conflicts_o   (conflicts)
    );
  end else begin : g_copies
    assign table_wait  = 1'b0;
    assign brick_wait  = 1'b0;
    assign conflicts = '0;
    for (genvar l = 0; l < LANES; l++) begin : g_no_word  // lane by lane: a wide device's are over 8k bits
      assign lane_word[NPar*MEMW*l +: NPar*MEMW]  = '0;
      assign lane_bword[NPar*MEMW*l +: NPar*MEMW] = '0;
    end
    logic unused_banks;  // each lane reads its own copy
    assign unused_banks = ^{lane_read, lane_addr, lane_bread, lane_baddr, lane_inside_pre, lane_state_pre, first_hit,
                            found, found_seq};
  end
  assign conflicts_o = conflicts;

  // The output slice holds records only behind its output register: out_valid covers both.
  assign busy_o = head_valid || out_valid || (|slot_valid);

  // Fields that only some stages read.
  logic unused;
  assign unused = ^{r4_slot, brick_slot, pre_slot, pre_test, last_slot.rot, reg0_job_q, r0_job, acc_map, yz_map,
                    r3_map, lin_map, last_test, job_threshold_i, hx_in, hy_in, cx_in, cy_in, job_sparse_i,
                    job_brick_base_i, job_brick_units_i, word_bricks, stage_bricks, w_next, w_out, w_stop, bricks_r,
                    info_r[0 +: InfoW], stamps_r[0 +: 2*CW], t_r[0 +: 3*TW], map_r[0 +: MapW], lane_inside_pre,
                    lane_state_pre, w_meta, r0_job_q};

  // ---- Assertions (Verilator runs them with --assert; voxcd_assert.svh) ----
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
  `VOXCD_ASSERT_INIT(BrickLanesOnASparseDevice, TX == 0 || (TX == 1 && BL > 0))
  `VOXCD_ASSERT_INIT(BrickLevelsKnown, BL == 0 || (BL >= 2 && BL <= 4))
  `VOXCD_ASSERT_INIT(SparseWidthsFit, !Sparse || (3 * PW >= 72 && MEMW >= 8 && (!Dist || MF + PF >= WB + 3)))
  `VOXCD_ASSERT_INIT(SlotsMatchTheTimingModel,
                     NumR == voxcd_arch_pkg::PipeSlots + Depth + (Dist ? voxcd_arch_pkg::DistSlots : 0) +
                             (Sparse ? (Dist ? voxcd_arch_pkg::SparseDistSlots : voxcd_arch_pkg::SparseSlots) : 0))
  `VOXCD_ASSERT_INIT(StructWidthsMatch, JobW == $bits(job_t) && MetaW == $bits(meta_t) && TestW == $bits(test_t))

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
  // The registers up to a read stage advance only with the ones after it, and only when that stage has its words.
  `VOXCD_ASSERT(AdvanceWithTheLastRegister, !advance || (advance_mid && !table_wait))
  `VOXCD_ASSERT(AdvanceBrickStage, !advance_mid || (advance_out && !brick_wait))
  // The memories are loaded while the device is idle.
  `VOXCD_ASSERT(WriteOnlyWhileIdle, !((shell_we_i || map_we_i) && busy_o))
  // Every accepted job has a valid mode and map dimensions in 1 .. 2^DW, and sparse fields only on a sparse device.
  `VOXCD_ASSERT(JobModeValid, !(job_valid_i && job_ready_o) || job_mode_i != 2'd3)
  `VOXCD_ASSERT(JobDimsValid, !(job_valid_i && job_ready_o) ||
                (job_nx_i != 0 && job_ny_i != 0 && job_nz_i != 0 && job_nx_i <= (DW + 1)'(1 << DW) &&
                 job_ny_i <= (DW + 1)'(1 << DW) && job_nz_i <= (DW + 1)'(1 << DW)))
  `VOXCD_ASSERT(JobSparseOnlyOnASparseDevice, !(job_valid_i && job_ready_o) || Sparse ||
                (job_sparse_i == '0 && job_brick_base_i == '0 && job_brick_units_i == '0))

  // ---- Functional coverage (docs/verification.md, "Functional coverage"): counted in the coverage models ----
  // Signals named cov_* are read by cover properties only (bench/mutation leaves them out: no output can change).
  // Back-pressure on each stream, a stall while a completion record waits with a later job's slots in the
  // registers, and stalls with the job queue full.
  `VOXCD_COVER(CoverHitStreamHeld, hit_valid_o && !hit_ready_i)
  `VOXCD_COVER(CoverDoneStreamHeld, done_valid_o && !done_ready_i)
  `VOXCD_COVER(CoverStallAcrossAJobBoundary, stall && done_valid_o && !done_ready_i && (|slot_valid))
  `VOXCD_COVER(CoverStallWithTheQueueFull, stall && !job_ready_o)
  // Jobs back to back: the issue stage takes the next job's first slot in the cycle after the last one's.
  logic cov_head_popped_q;
  `VOXCD_FF(cov_head_popped_q, head_pop, 1'b0)
  `VOXCD_COVER(CoverJobsBackToBack, cov_head_popped_q && head_valid && issue_taken)
  `VOXCD_COVER(CoverTwoJobsQueued, !job_ready_o)
  // Memories written between jobs (the device idle after records have left).
  `VOXCD_COVER(CoverMapWrite, map_we_i)
  `VOXCD_COVER(CoverShellWrite, shell_we_i)
  // A sparse device's brick stage: a slot of a sparse map whose lanes' cells are all bricks, all uniform, or both.
  if (Sparse) begin : g_cover_sparse
    logic [LANES-1:0] cov_brick_cells;
    logic             cov_sparse_map_slot;
    for (genvar l = 0; l < LANES; l++) begin : g_cell
      assign cov_brick_cells[l] = brick_slot.lanes[l] && lane_bread[NPar*l];
    end
    assign cov_sparse_map_slot = brick_slot.valid && stage_bricks[BrickW-1] && (|brick_slot.lanes);
    `VOXCD_COVER(CoverSparseMapSlotOfBricks, cov_sparse_map_slot && cov_brick_cells == brick_slot.lanes)
    `VOXCD_COVER(CoverSparseMapSlotOfUniformCells, cov_sparse_map_slot && cov_brick_cells == '0)
    `VOXCD_COVER(CoverSparseMapSlotOfBoth, cov_sparse_map_slot && cov_brick_cells != '0 && cov_brick_cells != brick_slot.lanes)
    `VOXCD_COVER(CoverDenseMapSlot, brick_slot.valid && !stage_bricks[BrickW-1])
  end

endmodule
