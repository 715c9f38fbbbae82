// tb_voxcd_dpi: a scoreboard testbench for the voxcd device with the DPI-C reference (voxcd_dpi_pkg) as its
// golden model (docs/dpi.md).
//
// It draws a memory image and random jobs with hard cases from a seed (voxcd_dpi_generate), writes the image
// through the device's write ports, drives the jobs back to back with random ready on both output streams, and
// checks every record. Monitors on the input ports tell the reference what the device takes (words written, jobs
// accepted); each record the device hands over is compared with the next one the reference expects: hit records
// on every field (the interpolated distance too, on a distance device: SB > 2), completion records on tag and
// hits, and (+timing=1) on cycles minus stalls and on points against the cycle model. It ends with one summary
// line, "tb_voxcd_dpi: PASS: ..." or "tb_voxcd_dpi: FAIL: ...", and a failure stops the simulation with $fatal (a
// non-zero exit status).
//
// The device is `VOXCD_DUT (voxcd_device unless defined otherwise): any implementation of docs/contract.md with
// voxcd_device's parameters and ports can take its place. The clock is an input (the simulator's main drives it);
// everything happens at its rising edges.
//
// Plusargs (defaults in brackets):
//   +seed=S          stimulus and back-pressure seed [1]
//   +jobs=N          random jobs [1000]
//   +cloud=P         points of the random cloud in the shell image [2000]
//   +stall=PCT       chance in percent that a stream's ready is low in a cycle [25]
//   +burst=N         after every N jobs, let the device go idle before the next (0: never) [0]
//   +timing=0|1      compare cycles minus stalls, and points, with the cycle model [1]
//   +config=TEXT     the reference's configuration [the parameters, "PW 24 ... TAGW 16 SB 2 WB 8"]; must match the
//                    device
//   +norestart       do not tell the reference about idle gaps (voxcd_dpi_restart): shows why it is needed
//   +corrupt_hit=K   flip bit 0 of the expected x of hit record K (from 0): the scoreboard must catch it
//   +corrupt_done=K  add 1 to the expected cycles of completion record K (from 0): likewise
//   +max_errors=N    stop after N mismatches [10]
`ifndef VOXCD_DUT
`define VOXCD_DUT voxcd_device
`endif

module tb_voxcd_dpi #(
  // The device's parameters (docs/contract.md; the defaults are the contract's).
  parameter int unsigned PW    = 24,
  parameter int unsigned PF    = 8,
  parameter int unsigned MW    = 18,
  parameter int unsigned MF    = 16,
  parameter int unsigned TW    = 48,
  parameter int unsigned DW    = 10,
  parameter int unsigned MEMW  = 64,
  parameter int unsigned LANES = 4,
  parameter int unsigned SAW   = 16,
  parameter int unsigned MAW   = 18,
  parameter int unsigned TAGW  = 16,
  parameter int unsigned SB    = 2,
  parameter int unsigned WB    = 8,
  parameter int unsigned Depth = 0   // the device's pipeline depth (DEPTH in the reference's configuration)
) (
  input logic clk_i
);
  import voxcd_dpi_pkg::*;

  localparam int unsigned CW = 32;          // width of the completion records' cycles and stalls
  localparam int unsigned IW = SB + 3 * WB;  // a job's threshold, a hit's distance (signed)

  // ---- The device ----
  logic                rst_n;
  logic                shell_we;
  logic [SAW-1:0]      shell_waddr;
  logic [3*PW-1:0]     shell_wdata;
  logic                map_we;
  logic [MAW-1:0]      map_waddr;
  logic [MEMW-1:0]     map_wdata;
  logic                job_valid, job_ready;
  logic [TAGW-1:0]     job_tag;
  logic [1:0]          job_mode;
  logic [3:0]          job_mask;
  logic [SAW-1:0]      job_shell_base;
  logic [SAW:0]        job_shell_count;
  logic [MAW-1:0]      job_map_base;
  logic [DW:0]         job_nx, job_ny, job_nz;
  logic [MW-1:0]       job_m [9];  // row-major: m00, m01, .., m22
  logic [TW-1:0]       job_t [3];
  logic [IW-1:0]       job_threshold;
  logic                hit_valid, hit_ready;
  logic [TAGW-1:0]     hit_tag;
  logic [SAW-1:0]      hit_point;
  logic [DW-1:0]       hit_x, hit_y, hit_z;
  logic [1:0]          hit_state;
  logic [IW-1:0]       hit_dist;
  logic                done_valid, done_ready;
  logic [TAGW-1:0]     done_tag;
  logic [SAW:0]        done_hits, done_points;
  logic [CW-1:0]       done_cycles, done_stalls, conflicts;
  logic                busy;

  `VOXCD_DUT #(
    .PW(PW), .PF(PF), .MW(MW), .MF(MF), .TW(TW), .DW(DW), .MEMW(MEMW), .LANES(LANES), .SAW(SAW), .MAW(MAW),
    .TAGW(TAGW), .SB(SB), .WB(WB), .Depth(Depth)
  ) u_dut (
    .clk_i            (clk_i),
    .rst_ni           (rst_n),
    .shell_we_i       (shell_we),
    .shell_waddr_i    (shell_waddr),
    .shell_wdata_i    (shell_wdata),
    .map_we_i         (map_we),
    .map_waddr_i      (map_waddr),
    .map_wdata_i      (map_wdata),
    .job_valid_i      (job_valid),
    .job_ready_o      (job_ready),
    .job_tag_i        (job_tag),
    .job_mode_i       (job_mode),
    .job_mask_i       (job_mask),
    .job_shell_base_i (job_shell_base),
    .job_shell_count_i(job_shell_count),
    .job_map_base_i   (job_map_base),
    .job_nx_i         (job_nx),
    .job_ny_i         (job_ny),
    .job_nz_i         (job_nz),
    .job_m00_i        (job_m[0]),
    .job_m01_i        (job_m[1]),
    .job_m02_i        (job_m[2]),
    .job_m10_i        (job_m[3]),
    .job_m11_i        (job_m[4]),
    .job_m12_i        (job_m[5]),
    .job_m20_i        (job_m[6]),
    .job_m21_i        (job_m[7]),
    .job_m22_i        (job_m[8]),
    .job_t0_i         (job_t[0]),
    .job_t1_i         (job_t[1]),
    .job_t2_i         (job_t[2]),
    .job_threshold_i  (job_threshold),
    .job_sparse_i     (2'd0),             // the reference draws dense jobs: a dense device (BL = 0) takes no other
    .job_brick_base_i (MAW'(0)),
    .job_brick_units_i((MAW + 1)'(0)),
    .hit_valid_o      (hit_valid),
    .hit_ready_i      (hit_ready),
    .hit_tag_o        (hit_tag),
    .hit_point_o      (hit_point),
    .hit_x_o          (hit_x),
    .hit_y_o          (hit_y),
    .hit_z_o          (hit_z),
    .hit_state_o      (hit_state),
    .hit_dist_o       (hit_dist),
    .done_valid_o     (done_valid),
    .done_ready_i     (done_ready),
    .done_tag_o       (done_tag),
    .done_hits_o      (done_hits),
    .done_cycles_o    (done_cycles),
    .done_points_o    (done_points),
    .done_stalls_o    (done_stalls),
    .busy_o           (busy),
    .conflicts_o      (conflicts)
  );
  logic unused_conflicts;  // the device keeps a voxmap copy per lane: no bank conflicts
  assign unused_conflicts = ^conflicts;

  // ---- Options ----
  longint seed         = 1;
  int     n_jobs       = 1000;
  int     cloud        = 2000;
  int     stall_pct    = 25;
  int     burst        = 0;
  int     timing       = 1;
  int     restart      = 1;
  int     corrupt_hit  = -1;
  int     corrupt_done = -1;
  int     max_errors   = 10;
  string  cfg_text;

  // ---- State ----
  chandle h;  // the reference device
  int     n_shell, n_map, n_load;
  typedef enum logic [2:0] { PhReset, PhLoad, PhRun, PhDrain, PhEnd } phase_e;
  phase_e          phase       = PhReset;
  longint unsigned rng;
  longint          cycle       = 0;
  longint          idle        = 0;  // cycles without a word written, a job accepted or a record taken
  longint          stalls      = 0;
  int              addr        = 0;
  int              next_job    = 0;
  int              jobs_done   = 0;
  int              hit_records = 0;
  int              errors      = 0;
  int              gaps        = 0;
  bit              finished    = 1'b0;
  logic            progress;

  // The reference's next record (voxcd_dpi_pop).
  int     kind, e_tag, e_point, e_x, e_y, e_z, e_state, e_hits;
  longint e_cycles, e_points, e_dist;
  longint got_dist;  // the device's hit_dist_o, sign-extended
  // A generated job and memory word, as the DPI functions return them: their int and longint are wider than the
  // fields they fill, and the generator's values fit those fields.
  /* verilator lint_off UNUSEDSIGNAL */
  int     g_tag, g_mode, g_mask, g_base, g_count, g_map, g_nx, g_ny, g_nz;
  longint g_m [9];
  longint g_t [3];
  longint g_threshold;
  longint gx, gy, gz, gword;
  /* verilator lint_on UNUSEDSIGNAL */

  // The testbench's bookkeeping (counts, the reference's record, the random state) is read in program order by
  // the process below and the functions it calls, and by nothing else, so it is assigned with '='; the device's
  // inputs with '<='.
  /* verilator lint_off BLKSEQ */

  // Stops the run with a message (once). Where $fatal returns (Verilator with fatalOnError off), `finished`
  // stops the clocked process.
  function automatic void fail(input string msg);
    if (finished) return;
    finished = 1'b1;
    $fatal(1, "tb_voxcd_dpi: %s", msg);
  endfunction

  // A DPI call's result: 0, and the run stops with the reference's message, when the call failed.
  function automatic bit need(input int rc, input string what);
    if (rc >= 0) return 1'b1;
    fail($sformatf("%s failed: %s", what, voxcd_dpi_error(h)));
    return 1'b0;
  endfunction

  // Makes the reference device of the configuration and the stimulus; 0 when the run cannot start.
  function automatic bit setup();
    string names [14];
    int    values [14];
    names  = '{"PW", "PF", "MW", "MF", "TW", "DW", "MEMW", "LANES", "SAW", "MAW", "TAGW", "SB", "WB", "DEPTH"};
    values = '{PW, PF, MW, MF, TW, DW, MEMW, LANES, SAW, MAW, TAGW, SB, WB, Depth};
    h = voxcd_dpi_new(cfg_text);
    if (h == null) begin
      fail(voxcd_dpi_error(null));
      return 1'b0;
    end
    for (int i = 0; i < 14; i++) begin
      if (voxcd_dpi_param(h, names[i]) != values[i]) begin
        fail($sformatf("the reference's configuration (%s) has %s %0d, the device %0d", cfg_text, names[i],
                       voxcd_dpi_param(h, names[i]), values[i]));
        return 1'b0;
      end
    end
    if (!need(voxcd_dpi_generate(h, seed, n_jobs, cloud), "voxcd_dpi_generate")) return 1'b0;
    n_shell = voxcd_dpi_gen_shell_words(h);
    n_map   = voxcd_dpi_gen_map_words(h);
    n_load  = n_shell > n_map ? n_shell : n_map;
    return 1'b1;
  endfunction

  // Prints the summary line and ends the run (once).
  function automatic void finish_run();
    string line;
    if (finished) return;
    line = {$sformatf("%sLANES %0d, seed %0d: %0d of %0d jobs, %0d hit records and %0d completion records checked, ",
                      SB > 2 ? $sformatf("SB %0d WB %0d ", SB, WB) : "", LANES, seed, jobs_done, n_jobs,
                      hit_records, jobs_done),
            $sformatf("%0d idle gaps, %0d stall cycles, %0d cycles", gaps, stalls, cycle)};
    if (errors == 0) begin
      $display("tb_voxcd_dpi: PASS: %s", line);
      finished = 1'b1;
      $finish;
    end else begin
      $display("tb_voxcd_dpi: FAIL: %s; %0d mismatches", line, errors);
      fail($sformatf("%0d mismatches (the first is printed above)", errors));
    end
  endfunction

  function automatic void mismatch(input string what);
    if (finished) return;
    $display("tb_voxcd_dpi: MISMATCH at cycle %0d, job %0d: %s", cycle, jobs_done, what);
    errors = errors + 1;
    if (errors >= max_errors) finish_run();
  endfunction

  // Random back-pressure: xorshift64, the same sequence on every simulator.
  function automatic longint unsigned xorshift(input longint unsigned s);
    longint unsigned x = s;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  endfunction

  // Puts generated job `k` on the job port.
  task automatic drive_job(input int k);
    void'(need(voxcd_dpi_gen_job(h, k, g_tag, g_mode, g_mask, g_base, g_count, g_map, g_nx, g_ny, g_nz,
                                 g_m[0], g_m[1], g_m[2], g_m[3], g_m[4], g_m[5], g_m[6], g_m[7], g_m[8],
                                 g_t[0], g_t[1], g_t[2], g_threshold), "voxcd_dpi_gen_job"));
    job_valid       <= 1'b1;
    job_tag         <= TAGW'(g_tag);
    job_mode        <= 2'(g_mode);
    job_mask        <= 4'(g_mask);
    job_shell_base  <= SAW'(g_base);
    job_shell_count <= (SAW + 1)'(g_count);
    job_map_base    <= MAW'(g_map);
    job_nx          <= (DW + 1)'(g_nx);
    job_ny          <= (DW + 1)'(g_ny);
    job_nz          <= (DW + 1)'(g_nz);
    for (int i = 0; i < 9; i++) job_m[i] <= MW'(g_m[i]);
    for (int i = 0; i < 3; i++) job_t[i] <= TW'(g_t[i]);
    job_threshold   <= IW'(g_threshold);
  endtask

  initial begin
    void'($value$plusargs("seed=%d", seed));
    void'($value$plusargs("jobs=%d", n_jobs));
    void'($value$plusargs("cloud=%d", cloud));
    void'($value$plusargs("stall=%d", stall_pct));
    void'($value$plusargs("burst=%d", burst));
    void'($value$plusargs("timing=%d", timing));
    void'($value$plusargs("corrupt_hit=%d", corrupt_hit));
    void'($value$plusargs("corrupt_done=%d", corrupt_done));
    void'($value$plusargs("max_errors=%d", max_errors));
    if ($test$plusargs("norestart")) restart = 0;
    cfg_text = $sformatf("PW %0d PF %0d MW %0d MF %0d TW %0d DW %0d MEMW %0d LANES %0d SAW %0d MAW %0d TAGW %0d %s",
                         PW, PF, MW, MF, TW, DW, MEMW, LANES, SAW, MAW, TAGW,
                         $sformatf("SB %0d WB %0d DEPTH %0d", SB, WB, Depth));
    void'($value$plusargs("config=%s", cfg_text));
    rng        = ($unsigned(seed) ^ 64'h9e37_79b9_7f4a_7c15) | 64'd1;
    rst_n      = 1'b0;
    shell_we   = 1'b0;
    map_we     = 1'b0;
    job_valid  = 1'b0;
    hit_ready  = 1'b1;
    done_ready = 1'b1;
    if (setup())
      $display("tb_voxcd_dpi: seed %0d (+seed=%0d repeats this run), %0d jobs, ready low %0d%% of cycles, %s",
               seed, seed, n_jobs, stall_pct,
               $sformatf("%0d shell and %0d voxmap words; %s", n_shell, n_map, voxcd_dpi_config(h)));
  end

  final if (h != null) voxcd_dpi_free(h);

  always @(posedge clk_i) if (!finished) begin
    cycle    <= cycle + 1;
    progress  = 1'b0;

    // ---- Monitors: what the device takes at this edge, it takes from the values before it ----
    if (shell_we) begin
      void'(need(voxcd_dpi_write_shell(h, int'(shell_waddr), longint'($signed(shell_wdata[0*PW +: PW])),
                                       longint'($signed(shell_wdata[1*PW +: PW])),
                                       longint'($signed(shell_wdata[2*PW +: PW]))), "voxcd_dpi_write_shell"));
      progress = 1'b1;
    end
    if (map_we) begin
      void'(need(voxcd_dpi_write_map(h, int'(map_waddr), longint'(map_wdata)), "voxcd_dpi_write_map"));
      progress = 1'b1;
    end
    if (job_valid && job_ready) begin
      void'(need(voxcd_dpi_submit(h, int'(job_tag), int'(job_mode), int'(job_mask), int'(job_shell_base),
                                  int'(job_shell_count), int'(job_map_base), int'(job_nx), int'(job_ny),
                                  int'(job_nz), longint'($signed(job_m[0])), longint'($signed(job_m[1])),
                                  longint'($signed(job_m[2])), longint'($signed(job_m[3])),
                                  longint'($signed(job_m[4])), longint'($signed(job_m[5])),
                                  longint'($signed(job_m[6])), longint'($signed(job_m[7])),
                                  longint'($signed(job_m[8])), longint'($signed(job_t[0])),
                                  longint'($signed(job_t[1])), longint'($signed(job_t[2])),
                                  longint'($signed(job_threshold))),
                 "voxcd_dpi_submit"));
      progress = 1'b1;
    end

    // ---- Scoreboard: every record the device hands over against the reference's next one ----
    if (hit_valid && hit_ready) begin
      kind = voxcd_dpi_pop(h, e_tag, e_point, e_x, e_y, e_z, e_state, e_hits, e_cycles, e_points, e_dist);
      void'(need(kind, "voxcd_dpi_pop"));
      if (hit_records == corrupt_hit) e_x = e_x ^ 1;
      got_dist = longint'($signed(hit_dist));
      if (kind != RecordHit)
        mismatch($sformatf("expected %s, got hit tag %0d point %0d voxel (%0d %0d %0d) state %0d dist %0d",
                           kind == RecordDone ? $sformatf("done tag %0d", e_tag) : "no more records",
                           hit_tag, hit_point, hit_x, hit_y, hit_z, hit_state, got_dist));
      else if (e_tag != int'(hit_tag) || e_point != int'(hit_point) || e_x != int'(hit_x) || e_y != int'(hit_y) ||
               e_z != int'(hit_z) || e_state != int'(hit_state) || e_dist != got_dist)
        mismatch({$sformatf("hit record %0d: expected hit tag %0d point %0d voxel (%0d %0d %0d) state %0d dist %0d, ",
                            hit_records, e_tag, e_point, e_x, e_y, e_z, e_state, e_dist),
                  $sformatf("got hit tag %0d point %0d voxel (%0d %0d %0d) state %0d dist %0d",
                            hit_tag, hit_point, hit_x, hit_y, hit_z, hit_state, got_dist)});
      hit_records = hit_records + 1;
      progress    = 1'b1;
    end
    if (done_valid && done_ready) begin
      kind = voxcd_dpi_pop(h, e_tag, e_point, e_x, e_y, e_z, e_state, e_hits, e_cycles, e_points, e_dist);
      void'(need(kind, "voxcd_dpi_pop"));
      if (jobs_done == corrupt_done) e_cycles = e_cycles + 1;
      if (kind != RecordDone)
        mismatch($sformatf("expected %s, got done tag %0d hits %0d",
                           kind == RecordHit ? $sformatf("hit tag %0d point %0d", e_tag, e_point) : "no more records",
                           done_tag, done_hits));
      else if (e_tag != int'(done_tag) || e_hits != int'(done_hits))
        mismatch($sformatf("completion record %0d: expected done tag %0d hits %0d, got done tag %0d hits %0d",
                           jobs_done, e_tag, e_hits, done_tag, done_hits));
      else if (timing != 0 && (e_cycles != longint'(done_cycles) - longint'(done_stalls) ||
                               e_points != longint'(done_points)))
        mismatch({$sformatf("completion record %0d (tag %0d): expected cycles %0d points %0d, ",
                            jobs_done, e_tag, e_cycles, e_points),
                  $sformatf("got cycles %0d - stalls %0d = %0d points %0d", done_cycles, done_stalls,
                            longint'(done_cycles) - longint'(done_stalls), done_points)});
      stalls    = stalls + longint'(done_stalls);
      jobs_done = jobs_done + 1;
      progress  = 1'b1;
    end

    // ---- Random ready on both output streams ----
    rng         = xorshift(rng);
    hit_ready  <= int'(rng % 100) >= stall_pct;
    done_ready <= int'((rng >> 32) % 100) >= stall_pct;

    // ---- Drivers ----
    case (phase)
      PhReset: if (cycle == 2) begin
        rst_n <= 1'b1;
        phase <= PhLoad;
      end
      PhLoad: begin
        // One shell word and one voxmap word a cycle, at the same address.
        if (addr < n_load) begin
          shell_we <= addr < n_shell;
          map_we   <= addr < n_map;
          if (addr < n_shell) begin
            void'(need(voxcd_dpi_gen_shell(h, addr, gx, gy, gz), "voxcd_dpi_gen_shell"));
            shell_waddr <= SAW'(addr);
            shell_wdata <= {PW'(gz), PW'(gy), PW'(gx)};
          end
          if (addr < n_map) begin
            void'(need(voxcd_dpi_gen_map(h, addr, gword), "voxcd_dpi_gen_map"));
            map_waddr <= MAW'(addr);
            map_wdata <= MEMW'(gword);
          end
          addr <= addr + 1;
        end else begin
          shell_we <= 1'b0;
          map_we   <= 1'b0;
          if (n_jobs > 0) drive_job(0);
          phase <= n_jobs > 0 ? PhRun : PhEnd;
        end
      end
      PhRun: if (job_valid && job_ready) begin
        next_job <= next_job + 1;
        if (next_job + 1 == n_jobs) begin
          job_valid <= 1'b0;
          phase     <= PhEnd;
        end else if (burst > 0 && (next_job + 1) % burst == 0) begin
          job_valid <= 1'b0;
          phase     <= PhDrain;
        end else begin
          drive_job(next_job + 1);
        end
      end
      PhDrain: if (!busy) begin
        // The device is idle: the next job starts a new stream.
        if (restart != 0) void'(need(voxcd_dpi_restart(h), "voxcd_dpi_restart"));
        gaps      = gaps + 1;
        drive_job(next_job);
        phase <= PhRun;
      end
      default: begin  // PhEnd: every job accepted; wait for the device to finish and go idle
        if (jobs_done == n_jobs && !busy) begin
          if (voxcd_dpi_pending(h) != 0)
            mismatch($sformatf("%0d expected records never came", voxcd_dpi_pending(h)));
          finish_run();
        end
      end
    endcase

    // A job takes at most a cycle per point and record plus the pipeline; allow far more before giving up.
    idle <= progress || phase == PhReset || phase == PhLoad ? 0 : idle + 1;
    if (idle > 1000 + 64 * (longint'(1) << SAW)) begin
      mismatch($sformatf("no progress for %0d cycles (%0d of %0d jobs accepted, %0d expected records pending)",
                         idle, voxcd_dpi_jobs(h), n_jobs, voxcd_dpi_pending(h)));
      finish_run();
    end
  end
  /* verilator lint_on BLKSEQ */

endmodule
