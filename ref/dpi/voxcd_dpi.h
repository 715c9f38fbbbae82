/* voxcd_dpi.h: the SystemVerilog DPI-C reference of the voxcd device, as C declarations.
 *
 * A reference device is a golden model for a scoreboard: make one of a configuration, load its memories as the
 * device's write ports do, submit the jobs the device accepts, and pop the records the device must produce, in
 * stream order, with the completion records' cycles from the cycle model (ref/timing.h). voxcd_dpi_pkg.sv imports
 * exactly these functions; docs/dpi.md is the guide.
 *
 * Only DPI-C's standard types, so that any simulator can call them:
 *   SV chandle = void*, SV string = const char*, SV int = int, SV longint = long long, SV output arguments are
 *   pointers. Unsigned fields (tags, addresses, counts) travel as their 32-bit pattern in an int; map words as
 *   their 64-bit pattern in a long long; signed fields (M, t, shell coordinates, a job's threshold and a hit's
 *   distance) as signed values.
 *
 * Errors: no C++ exception leaves these functions. A function returning int returns -1 when it fails (a handle of
 * 0, an argument that does not fit its field, a job reading memory never written, ...); voxcd_dpi_error(h) then
 * gives the message, naming the function and what is wrong. voxcd_dpi_new returns 0 when it fails and
 * voxcd_dpi_error(0) says why.
 */
#ifndef VOXCD_DPI_H
#define VOXCD_DPI_H

#ifdef __cplusplus
extern "C" {
#endif

/* Record kinds returned by voxcd_dpi_pop. */
#define VOXCD_DPI_NONE 0
#define VOXCD_DPI_HIT 1
#define VOXCD_DPI_DONE 2

/* ---- The reference device ---- */

/* A reference device of the configuration `pairs`: "NAME VALUE" pairs as on a vector file's config line, e.g.
 * "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 16 MAW 18 TAGW 16"; any subset in any order, missing
 * names take the defaults of docs/contract.md, "" is the default device. Its memories start unwritten. Returns 0
 * for a configuration no device can have or text that does not parse (voxcd_dpi_error(0) says which parameter). */
void* voxcd_dpi_new(const char* pairs);
/* Frees the device (0 is ignored). */
void voxcd_dpi_free(void* h);
/* The message of the last call on h that failed ("" if none has); h = 0: of the last voxcd_dpi_new that failed,
 * or of the last call that was given a handle of 0. Valid until the next failing call on the same handle. */
const char* voxcd_dpi_error(void* h);
/* The value of one parameter of the device's configuration by name ("PW" .. "TAGW", "SB", "WB", "BANKS", "DEPTH",
 * "BL", and the derived "IW" = SB + 3*WB), or -1 for another name. */
int voxcd_dpi_param(void* h, const char* name);
/* The whole configuration, every parameter named: "PW 24 PF 8 ... TAGW 16", then "SB 8 WB 8" on a distance
 * device, "BANKS B", "DEPTH D" and "BL B" where they are not 0 ("" for h = 0). */
const char* voxcd_dpi_config(void* h);

/* ---- Memories, as the write ports load them ---- */

/* Shell word `addr` = the point (x, y, z): signed PW-bit values (the port's three fields, sign-extended). */
int voxcd_dpi_write_shell(void* h, int addr, long long x, long long y, long long z);
/* Voxmap word `addr` = `word` (no bits at MEMW and above). */
int voxcd_dpi_write_map(void* h, int addr, long long word);

/* ---- Jobs and the expected stream ---- */

/* Submits one job, as the device accepts it: its records are computed now from the memories as they are, and
 * queued behind those of the jobs before it. mode 0 ALL, 1 FIRST, 2 COUNT; mask bit s: state s is a hit; M and t
 * signed (MW bits with MF fraction bits, TW bits with MF+PF); threshold signed, IW = SB + 3*WB bits: on a distance
 * device (SB > 2) a point is a hit when its interpolated distance D <= threshold, on a 2-bit device it must be 0.
 * The job must read only words that were written (docs/contract.md). Returns the number of records the job adds
 * (its hits, then 1 completion), or -1. */
int voxcd_dpi_submit(void* h, int tag, int mode, int mask, int shell_base, int shell_count, int map_base, int nx,
                     int ny, int nz, long long m00, long long m01, long long m02, long long m10, long long m11,
                     long long m12, long long m20, long long m21, long long m22, long long t0, long long t1,
                     long long t2, long long threshold);
/* voxcd_dpi_submit with a sparse device's fields (docs/contract.md, "Sparse voxmaps and shells"): sparse (bit 0: the
 * map is sparse, a table at map_base and bricks at brick_base; bit 1: the shell is sparse, shell_count words of shell
 * bricks), brick_base and brick_units (0, 0 for a dense map). A sparse map's brick words [brick_base, brick_base +
 * brick_units * UW) must have been written too. With sparse, brick_base and brick_units 0 it is voxcd_dpi_submit. */
int voxcd_dpi_submit_sparse(void* h, int tag, int mode, int mask, int shell_base, int shell_count, int map_base,
                            int nx, int ny, int nz, long long m00, long long m01, long long m02, long long m10,
                            long long m11, long long m12, long long m20, long long m21, long long m22, long long t0,
                            long long t1, long long t2, long long threshold, int sparse, int brick_base,
                            int brick_units);
/* Pops the next expected record in stream order: each job's hit records in ascending point order, then its
 * completion record; jobs in submission order. Returns VOXCD_DPI_HIT (tag, point, x, y, z, state and distance are set:
 * distance is the interpolated distance D on a distance device, 0 on a 2-bit one),
 * VOXCD_DPI_DONE (tag, hits, cycles and points are set), VOXCD_DPI_NONE when every record of the submitted jobs
 * has been popped, or -1. A completion record's cycles are what the device counts with an always-ready consumer:
 * compare them with its cycles minus its stalls. points: the points the job looked up (FIRST stops early). */
int voxcd_dpi_pop(void* h, int* tag, int* point, int* x, int* y, int* z, int* state, int* hits, long long* cycles,
                  long long* points, long long* distance);
/* Expected records not popped yet. */
int voxcd_dpi_pending(void* h);
/* Jobs submitted since the device was made. */
int voxcd_dpi_jobs(void* h);
/* The device went idle (nothing queued or in flight) before the next job: that job's cycles count from its own
 * acceptance, as a stream's first job's do. Without it, the next job is taken to follow the previous one back to
 * back (presented while the previous one was still queued or running). Returns 0. */
int voxcd_dpi_restart(void* h);

/* ---- Stimulus: random memories and jobs with hard cases (ref/vector_gen.h) ---- */

/* Draws a memory image and `jobs` valid jobs for it from `seed` (deterministic), for the device's configuration,
 * with a random cloud of `cloud_points` points in the shell (0 is allowed). It only stores them for the getters
 * below: the testbench writes the image through the device's ports and voxcd_dpi_write_*, and submits the jobs
 * the device accepts. A second call replaces the first. Returns 0, or -1 (the image does not fit the memories). */
int voxcd_dpi_generate(void* h, long long seed, int jobs, int cloud_points);
/* Words of the generated shell and voxmap images (addresses 0 .. n-1), and generated jobs. */
int voxcd_dpi_gen_shell_words(void* h);
int voxcd_dpi_gen_map_words(void* h);
int voxcd_dpi_gen_jobs(void* h);
/* Generated shell word / map word `addr`. Returns 0, or -1 for an address outside the image. */
int voxcd_dpi_gen_shell(void* h, int addr, long long* x, long long* y, long long* z);
int voxcd_dpi_gen_map(void* h, int addr, long long* word);
/* Generated job `index` (0 .. voxcd_dpi_gen_jobs - 1), its fields as voxcd_dpi_submit takes them. Returns 0 or -1. */
int voxcd_dpi_gen_job(void* h, int index, int* tag, int* mode, int* mask, int* shell_base, int* shell_count,
                      int* map_base, int* nx, int* ny, int* nz, long long* m00, long long* m01, long long* m02,
                      long long* m10, long long* m11, long long* m12, long long* m20, long long* m21,
                      long long* m22, long long* t0, long long* t1, long long* t2, long long* threshold);
/* Generated job `index`'s sparse device fields, as voxcd_dpi_submit_sparse takes them (all 0 on a dense device).
 * Returns 0 or -1. */
int voxcd_dpi_gen_job_sparse(void* h, int index, int* sparse, int* brick_base, int* brick_units);

#ifdef __cplusplus
}
#endif

#endif /* VOXCD_DPI_H */
