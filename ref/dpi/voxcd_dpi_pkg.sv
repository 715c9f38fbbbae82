// voxcd_dpi_pkg: the reference device of voxcd as DPI-C imports, the golden model of a scoreboard.
//
// Link the shared library libvoxcd_dpi (CMake: voxcd::dpi). voxcd_dpi.h, beside this file, declares the same
// functions in C and documents each; docs/dpi.md is the guide. In short:
//   h = voxcd_dpi_new("PW 24 ... LANES 4")        a reference device (null on error: voxcd_dpi_error(null))
//   voxcd_dpi_write_shell / voxcd_dpi_write_map    what the device's write ports take
//   voxcd_dpi_submit(h, <the job's fields>)        what the device's job port accepts
//   voxcd_dpi_pop(h, ...)                          the next record the device must produce, in stream order
// Functions returning int return -1 on error; voxcd_dpi_error(h) then says what and where.
// Unsigned fields travel as their bit pattern in an int, map words as theirs in a longint.
package voxcd_dpi_pkg;

  // Names for the numbers the functions take and return; a testbench uses those it needs.
  /* verilator lint_off UNUSEDPARAM */
  // Return values of voxcd_dpi_pop.
  localparam int RecordNone = 0;
  localparam int RecordHit  = 1;
  localparam int RecordDone = 2;

  // Job modes.
  localparam int ModeAll   = 0;
  localparam int ModeFirst = 1;
  localparam int ModeCount = 2;

  // A job's sparse bits (voxcd_dpi_submit_sparse).
  localparam int SparseMap   = 1;
  localparam int SparseShell = 2;
  /* verilator lint_on UNUSEDPARAM */

  // ---- The reference device ----
  import "DPI-C" function chandle voxcd_dpi_new(input string pairs);
  import "DPI-C" function void voxcd_dpi_free(input chandle h);
  import "DPI-C" function string voxcd_dpi_error(input chandle h);
  import "DPI-C" function int voxcd_dpi_param(input chandle h, input string name);
  import "DPI-C" function string voxcd_dpi_config(input chandle h);

  // ---- Memories, as the write ports load them ----
  import "DPI-C" function int voxcd_dpi_write_shell(input chandle h, input int addr,
                                                    input longint x, input longint y, input longint z);
  import "DPI-C" function int voxcd_dpi_write_map(input chandle h, input int addr, input longint word);

  // ---- Jobs and the expected stream ----
  import "DPI-C" function int voxcd_dpi_submit(input chandle h, input int tag, input int mode, input int mask,
                                               input int shell_base, input int shell_count, input int map_base,
                                               input int nx, input int ny, input int nz,
                                               input longint m00, input longint m01, input longint m02,
                                               input longint m10, input longint m11, input longint m12,
                                               input longint m20, input longint m21, input longint m22,
                                               input longint t0, input longint t1, input longint t2,
                                               input longint threshold);
  // A sparse device's job (BL > 0): the fields of voxcd_dpi_submit, then sparse (bit 0 map, bit 1 shell), brick_base
  // and brick_units. Dense jobs may keep voxcd_dpi_submit.
  import "DPI-C" function int voxcd_dpi_submit_sparse(input chandle h, input int tag, input int mode, input int mask,
                                                      input int shell_base, input int shell_count,
                                                      input int map_base, input int nx, input int ny, input int nz,
                                                      input longint m00, input longint m01, input longint m02,
                                                      input longint m10, input longint m11, input longint m12,
                                                      input longint m20, input longint m21, input longint m22,
                                                      input longint t0, input longint t1, input longint t2,
                                                      input longint threshold, input int sparse,
                                                      input int brick_base, input int brick_units);
  import "DPI-C" function int voxcd_dpi_pop(input chandle h, output int tag, output int point,
                                            output int x, output int y, output int z, output int state,
                                            output int hits, output longint cycles, output longint points,
                                            output longint distance);
  import "DPI-C" function int voxcd_dpi_pending(input chandle h);
  import "DPI-C" function int voxcd_dpi_jobs(input chandle h);
  import "DPI-C" function int voxcd_dpi_restart(input chandle h);

  // ---- Stimulus: random memories and jobs with hard cases ----
  import "DPI-C" function int voxcd_dpi_generate(input chandle h, input longint seed, input int jobs,
                                                 input int cloud_points);
  import "DPI-C" function int voxcd_dpi_gen_shell_words(input chandle h);
  import "DPI-C" function int voxcd_dpi_gen_map_words(input chandle h);
  import "DPI-C" function int voxcd_dpi_gen_jobs(input chandle h);
  import "DPI-C" function int voxcd_dpi_gen_shell(input chandle h, input int addr,
                                                  output longint x, output longint y, output longint z);
  import "DPI-C" function int voxcd_dpi_gen_map(input chandle h, input int addr, output longint word);
  import "DPI-C" function int voxcd_dpi_gen_job(input chandle h, input int index,
                                                output int tag, output int mode, output int mask,
                                                output int shell_base, output int shell_count,
                                                output int map_base, output int nx, output int ny, output int nz,
                                                output longint m00, output longint m01, output longint m02,
                                                output longint m10, output longint m11, output longint m12,
                                                output longint m20, output longint m21, output longint m22,
                                                output longint t0, output longint t1, output longint t2,
                                                output longint threshold);
  import "DPI-C" function int voxcd_dpi_gen_job_sparse(input chandle h, input int index, output int sparse,
                                                       output int brick_base, output int brick_units);

endpackage
