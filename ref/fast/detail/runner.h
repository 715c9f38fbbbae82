// Internal to FastRunner: its state and its steps (fast/fast.h is the interface; FastRunner holds one Impl). The
// steps are defined by concern: the memories and direct runs in fast.cpp, the scheduling of a batch over pieces and
// tasks in schedule.cpp, the 2-bit kernels in two_bit.cpp, distance maps in distance.cpp, sparse maps in
// sparse_map.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/fast/hits.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

namespace detail {
struct NodeQuads;
struct SparseCopy;
struct ShellCursor;
struct ShellArrays;

constexpr size_t kChunk = 2048;  // points per piece
constexpr size_t kBlock = 256;   // points per vector block inside a piece
// Points per task (runs of consecutive pieces, so that the many small jobs of a simulation frame make tasks of a
// few microseconds: about 1.5 ns a point).
constexpr size_t kTaskPoints = 2048;
}  // namespace detail

struct FastRunner::Impl {
  Impl(const DeviceConfig& cfg, unsigned threads);

  // FastRunner's operations (fast.h says what each does).
  void load(const DeviceMemory& mem);
  void write_shell(uint64_t first, const ShellWord* words, size_t n);
  void write_map(uint64_t first, const uint64_t* words, size_t n);
  void set_node_copy_limit(uint64_t bytes);
  uint64_t node_copy_bytes() const;
  BankCycles bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const;
  uint64_t job_points(const Job& job) const;
  JobSlots job_slots(const Job& job) const;
  void run_hits(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out, bool cycles) const;
  void run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits, uint32_t& count) const;

  // A piece of a job: points [begin, end), at most kChunk of them. A task is a run of consecutive pieces.
  struct Piece {
    size_t job;
    uint32_t begin, end;
    uint32_t count = 0;    // hits (ALL, COUNT) or, FIRST, 0 or 1
    size_t task = 0;       // its task, and the index of its first record in the task's hits
    size_t first = 0, records = 0;
    size_t out = 0;        // where its records go in the stream (those the stream keeps)
    JobHits sum;           // of its records, for the timing
    size_t at = SIZE_MAX;  // a sparse shell's: its cursor in piece_at_
  };
  const detail::ShellCursor* cursor_of(const Piece& p) const;
  struct alignas(64) TaskResult {
    std::vector<Record> hits;  // the hit records of its pieces, in order
    HitColumns columns;        // a piece's hits as the kernels write them
  };

  void set_shell_word(size_t k, const ShellWord& w);
  // The shell memory's copies the kernels read (fast/detail/point_blocks.h).
  detail::ShellArrays shell_arrays() const;
  // run_into (validate: every job first) and run_validated_into.
  void run_jobs(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles, bool validate);
  // The parts of run_jobs: the jobs cut into pieces (returns their points); on one thread; on the pool, the tasks'
  // lookups, then where each piece's kept records and each completion record go (returns the stream's length), then
  // task t's records and completions.
  size_t make_pieces(const std::vector<Job>& jobs);
  void run_serial(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles, bool validate);
  // run_serial's cycles: every completion record of `out` (the batch's stream) timed (ref/timing.h).
  void annotate(const std::vector<Job>& jobs, std::vector<Record>& out) const;
  void run_tasks(const std::vector<Job>& jobs, bool cycles, bool validate);
  size_t place_records(const std::vector<Job>& jobs);
  void finish_task(size_t t, const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) const;
  // Job j's hits and the summary of its kept records, from its pieces (all done).
  void job_result(const std::vector<Job>& jobs, size_t j, bool cycles, uint32_t& hits, JobHits& sum) const;
  // Looks up points [begin, end) of job j: appends their hit records (ALL: every one; FIRST: the first, then stops)
  // to `hits` and adds their number to `count`. A sparse shell's points from the cursor `at` (at `begin`), or from
  // its first word.
  void run_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& count,
                 const detail::ShellCursor* at = nullptr) const;
  // run_chunk of a sparse shell on a dense 2-bit map (its points generated a block at a time).
  void run_sparse_shell_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& count,
                              const detail::ShellCursor* at) const;
  // run_chunk on a distance voxmap (SB > 2), in fast/distance.cpp: the vector kernel where distance_vector(j), else
  // one point at a time.
  void run_distance_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& count,
                          const detail::ShellCursor* at) const;
  bool distance_vector(const Job& j) const;
  // run_chunk on a sparse map, in fast/sparse_map.cpp: the 2-bit kernel, the distance copy's kernel, or one point at
  // a time; and the copy of a sparse distance map (built at the first call; null where none serves).
  void run_sparse_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& count,
                        const detail::ShellCursor* at) const;
  const detail::SparseCopy* sparse_copy(const Job& j) const;
  void run_sparse_points(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& count,
                         const detail::ShellCursor* at) const;
  // The walk over a sparse-shell job's words (fast/detail/sparse_shell.h): its points, the cursors at every kChunk
  // points, its slots where `slots`.
  uint64_t walk_sparse_shell(const Job& j, std::vector<detail::ShellCursor>* cursors, JobSlots* slots) const;
  // The node-quad copy of job j's map, built at the first call (thread-safe); null where the kernel cannot take it
  // (widths, SB > 8) or it would pass the limit.
  const detail::NodeQuads* node_quads(const Job& j) const;
  // Drops the copies of maps (dense and sparse) made from any of voxmap words [first, end).
  void drop_node_quads(uint64_t first, uint64_t end);
  // The vector kernel on the parity banks, or with `quads` on that copy.
  void run_distance_vector(const Job& j, const detail::NodeQuads* quads, uint32_t begin, uint32_t end,
                           HitColumns& hits, uint32_t& count, const detail::ShellCursor* at) const;

  // The state.
  DeviceConfig cfg_;
  Path path_ = Path::Double;
  int slot_bits_ = 0;
  double tf_scale_ = 1;  // 2^-TF (std::ldexp is a library call; run_chunk needs it per job)
  bool keep_int64_ = false;  // the int64 arrays serve the int64 path and the double path's maps of 2^31 voxels
  std::shared_ptr<ThreadPool> pool_;
  std::vector<ShellWord> shell_;
  std::vector<uint64_t> map_;
  // The double path's coordinates as int32 (PW <= 32): half the memory traffic of doubles; the kernel converts
  // them exactly.
  std::vector<int32_t> sx_, sy_, sz_;
  std::vector<int64_t> ix_, iy_, iz_;
  std::vector<Piece> pieces_;
  // Where the pieces of sparse shells begin (fast/detail/sparse_shell.h; Piece::at); per job of the batch, its slots
  // (a sparse shell's from its words) and its points.
  std::vector<detail::ShellCursor> piece_at_;
  std::vector<JobSlots> batch_slots_;
  std::vector<size_t> first_piece_;  // per job, and one past the last
  std::vector<size_t> task_first_;   // per task its first piece, and one past the last
  std::vector<size_t> done_at_;      // per job, where its completion record goes in the stream
  std::vector<TaskResult> results_;
  // The node-quad copies (fast/distance.cpp), built by const lookups on any thread: under copies_mutex_.
  uint64_t copy_limit_ = kNodeCopyLimit;
  mutable std::mutex copies_mutex_;
  mutable std::vector<std::unique_ptr<detail::NodeQuads>> copies_;
  mutable std::vector<std::unique_ptr<detail::SparseCopy>> sparse_copies_;  // sparse distance maps' (fast/sparse_map.cpp)
  mutable uint64_t copy_bytes_ = 0;
  HitColumns serial_hits_;  // run_serial's hits of a piece
};

}  // namespace voxcd
