// FastRunner: the device contract computed fast, bit-exact with ref/. ref/pipeline.h remains the specification;
// this is an implementation checked against it (tests/ref/test_fast.cpp compares its streams with run_stream's
// on every arithmetic path below). The cpu backend (host/device/cpu.cpp) and the SystemC loosely-timed model
// (sysc/tlm_target.cpp) both compute jobs with it.
//
// Distance voxmaps (SB > 2) take fast/distance.cpp's paths: a vector kernel in doubles where every value is exact (the
// default widths), else 64- and 128-bit integers one point at a time. At SB <= 8 the vector kernel reads a second
// copy of the map that FastRunner builds at the first job on it (fast/detail/node_quads.h: a cell's eight nodes in
// eight consecutive bytes, 4 bytes a cell), within node_copy_limit() bytes for all maps together; a map written
// again (write_map, load) loses its copy, and a map whose copy would pass the limit is read from its parity banks.
// Three arithmetic paths, chosen by the widths, give the same bits as ref/:
//  - double: when the accumulator fits 53 bits (the default widths: 49), every product M*p and every partial sum
//    is an integer below 2^53, so double arithmetic is exact (fused multiply-adds included), and so is
//    floor(acc * 2^-TF). This path vectorises (AVX-512, or AVX2 and FMA, where the processor has them, chosen at
//    run time).
//  - int64: when the accumulator fits 63 bits.
//  - wide: otherwise, ref/'s own stage functions on 128-bit integers.
// Sparse maps and shells (docs/contract.md, "Sparse voxmaps and shells"; sparse devices, BL > 0) take the same paths:
//  - a sparse shell's points are generated from its words a block at a time (fast/sparse_shell.cpp) into the arrays
//    the kernels read; its pieces and chunks are runs of points (a job's point k is its k-th generated point) and its
//    slots, for the cycles, follow its words.
//  - a sparse map on the double path is read from a copy built at the first job on it (fast/detail/sparse_copy.h): its
//    table resolved, one 32-bit entry a cell (a 2-bit map's: the brick's first word, or the uniform state; a distance
//    map's: the brick's level and its first node quad, every brick laid out in node quads). A lookup is two gathers:
//    the cell's entry, then the brick word (2-bit, sixteen points a step) or the sub-cell's eight nodes (distance),
//    software-pipelined so that a group's second read overlaps the next group's first (fast/sparse_kernel.cpp,
//    fast/sparse_distance_kernel.cpp). The copies count against node_copy_limit() with the dense maps' and are
//    dropped like them; without one (the limit; a distance map at SB = 16 or IW > 51) a 2-bit map is read as the
//    contract lays it out (the table word, its code and rank, then the brick word, by gathers) and a distance map one
//    point at a time, as every sparse map is on the int64 and wide paths (fast/sparse_reader.cpp).
// Jobs are split into chunks of points spread over a thread pool; chunk results are merged in order, so the
// stream is the same for any thread count. A batch of fewer than kParallelMinPoints points runs on the calling
// thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/fast/hits.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

class ThreadPool;

class FastRunner {
 public:
  enum class Path { Double, Int64, Wide };

  // threads: workers including the calling thread (0 = one per hardware thread, 1 = the caller alone). Results
  // never depend on it. Throws ConfigError for an invalid configuration.
  explicit FastRunner(const DeviceConfig& cfg, unsigned threads = 1);
  // On a pool shared with the caller's own loops (null: the calling thread alone).
  FastRunner(const DeviceConfig& cfg, std::shared_ptr<ThreadPool> pool);
  ~FastRunner();
  FastRunner(const FastRunner&) = delete;
  FastRunner& operator=(const FastRunner&) = delete;

  const DeviceConfig& config() const;
  Path path() const;
  static const char* path_name(Path p);  // "double", "int64", "wide"
  // The double path's kernel on this processor: "avx512", "avx2" or "baseline"; and the distance path's.
  static const char* double_kernel();
  static const char* distance_kernel();
  // The sparse maps' kernels on this processor (2-bit; distance on the copy): "avx512", "avx2" or "baseline".
  static const char* sparse_kernel();
  static const char* sparse_distance_kernel();
  unsigned threads() const;
  // The pool the batches run on (null without one).
  const std::shared_ptr<ThreadPool>& pool() const;
  // Batches of fewer points than this run on the calling thread: below it, the chunks are too few to share
  // (a loop on the pool costs about a microsecond; 4,096 points take about 5).
  static constexpr size_t kParallelMinPoints = 4096;

  // Replaces both memories (validate_memory first: throws JobError, leaving the memories as they were).
  void load(const DeviceMemory& mem);
  // Writes words [first, first + n) of one memory, growing it (new words in between are zero), as the write port
  // does. Throws JobError, writing nothing, when a word does not fit its format or the memory's depth.
  void write_shell(uint64_t first, const ShellWord* words, size_t n);
  void write_map(uint64_t first, const uint64_t* words, size_t n);
  uint64_t shell_words() const;
  uint64_t map_words() const;
  const std::vector<ShellWord>& shell() const;
  const std::vector<uint64_t>& map() const;
  // The bytes the copies of maps may take together, dense distance maps' in cell order and sparse maps' with their
  // tables resolved (default kNodeCopyLimit; 0: none, every map read as the contract lays it out), and the bytes they
  // take now. Results never depend on either. Setting the limit drops the copies.
  static constexpr uint64_t kNodeCopyLimit = uint64_t{1} << 30;
  void set_node_copy_limit(uint64_t bytes);
  uint64_t node_copy_limit() const;
  uint64_t node_copy_bytes() const;
  // On a banked device, the job's bank cycles given its hits' summary and its completion's hits (ref/banks.h).
  BankCycles bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const;
  // The points of a job valid for the loaded shell memory: shell_count for a dense shell, the points its words
  // generate for a sparse one (the range of run_piece's begin and end). And its slots (ref/timing.h, job_slots).
  uint64_t job_points(const Job& job) const;
  JobSlots job_slots(const Job& job) const;

  // Validates every job against the loaded memories (throws JobError before running any), runs them in order
  // and replaces `out` (reusing its capacity) with the stream run_stream gives. With `cycles`, every completion
  // record carries annotate_cycles' cycles, points and stalls (ref/timing.h). The working buffers live on between
  // calls: a caller that runs batch after batch allocates nothing once they have grown.
  void run_into(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles = true);
  // run_into without the validation, for a caller that has validated every job (validate_job) against the memories
  // as they are now, as the SystemC target does when a descriptor arrives. An invalid job is undefined behaviour.
  void run_validated_into(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles = true);
  std::vector<Record> run(const std::vector<Job>& jobs, bool cycles = true);
  // Jobs [jobs, jobs + n) on the calling thread alone, every one validated before any runs (JobError): their hits in
  // columns into `hits` and what each gave into `out` (both replaced), with `cycles` the timing model's cycles and
  // spans of the jobs as a stream of their own. The hits of run_into's stream, in its order, with no Record made:
  // for a caller that turns hits into contacts (PairCollider) or runs the parts of a batch on its own threads. Calls
  // on different outputs may run at once (it only reads the runner).
  void run_hits(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out, bool cycles = true) const;
  // Points [begin, end) of one job on the calling thread: their hits appended to `hits` (FIRST: up to the first),
  // their number added to `count`; the job validated first when `validate` (JobError). For a caller that splits the
  // jobs of a batch itself; calls may run at once. A sparse shell's points are its generated points
  // (job_points): a piece of one walks its words from the first to `begin`.
  void run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits, uint32_t& count) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxcd
