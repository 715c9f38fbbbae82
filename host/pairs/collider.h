// Pair tests on a device (internal to host): object types loaded in the device image (pairs/image.h), the relative
// pose of each pair quantised into jobs (A's shell in B's voxmap, and B's shell in A's on request), the jobs run back
// to back, and the hits routed back to their pairs as contacts in world coordinates (pairs/contact.h, and as flat
// arrays pairs/contacts.h). docs/pairs.md states the error bounds.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "voxcd/host/device/device.h"
#include "voxcd/host/device/parts.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/contact.h"
#include "voxcd/host/pairs/contacts.h"
#include "voxcd/host/pairs/detail/shell_order.h"
#include "voxcd/host/pairs/image.h"
#include "voxcd/host/pairs/pose.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

namespace detail {
class EmptySpace;
struct SortedHit;
}  // namespace detail

struct PairRequest {
  uint32_t a = 0, b = 0;  // object types, as PairCollider numbers them
  RigidPose pose_a, pose_b;
};

struct PairOptions {
  Mode mode = Mode::All;
  uint8_t hit_mask = kDefaultHitMask;
  bool both_directions = true;  // also B's shell in A's voxmap (needed to see A deep inside B's hollow, ...)
  // Submit only the shell points that can hit in the other object's voxmap: the shell's clusters of up to
  // kClusterPoints consecutive points whose box, through the quantised pose, meets a voxel of the voxmap's grid that
  // could give a hit (a state in the hit mask; on a distance device, a cell whose nodes reach the threshold), found
  // in a pyramid of the voxmap's empty space (host/pairs/detail/cull.h, empty_space.h). Each run of kept clusters is
  // one job. The points left out could not hit on the device, so contacts and hits never depend on it; lookups and
  // device cycles do. docs/pairs.md.
  bool cull = true;
  // Distance device: a point is a contact where the other object's interpolated distance is at most `margin`
  // world units (0: touching or inside). RangeError when it does not fit the job's threshold (beyond the band).
  double margin = 0;
  // A sparse distance field (refined bricks): also detect where the other object's distance is at most `margin` plus
  // the shell's covering reach (sqrt(3) shell spacings, the farthest a surface point lies from its shell point, plus
  // 1/4 of the field's voxel), so that no collision falls between the shell's points; such a hit beyond the margin is
  // a speculative contact, placed on the other object's surface (the field's zero, by Newton steps along its
  // gradient) with depth -D (the separation, negative). docs/pairs.md, "Sparse distance voxmaps".
  bool speculative = true;
};

// Where a job came from: its pair, its direction, the slot of its first point in the type's shell as the device
// holds it (a hit's point index is relative to that; PairCollider::shell_point gives the shell's point of a slot), and
// its points (its shell_count, but for a sparse shell, whose shell_count counts words).
struct JobSource {
  uint32_t pair = 0;
  bool a_in_b = true;
  uint32_t first = 0;
  uint32_t points = 0;
};

class PairCollider {
 public:
  // Loads the types into the device (its config must fit them: see fit_memory). The host's part of a query (the
  // jobs of many pairs, the culling of a large shell, the contacts of many hits) runs on `pool`, by default the
  // device's (the cpu backend's threads); results never depend on it.
  PairCollider(std::unique_ptr<Device> device, std::vector<std::shared_ptr<const ObjectType>> types,
               std::shared_ptr<ThreadPool> pool = nullptr);

  // Jobs for the requests, in order: per pair A-in-B, then B-in-A when both directions are asked. The device holds
  // each shell in blocks of nearby points (detail::block_order); a direction is one job without opt.cull (FIRST: one
  // per block), zero or more (runs of slots in ascending order; FIRST: within one block) with it. RangeError naming
  // the pair when a pose is not finite or does not fit the fixed-point formats.
  std::vector<Job> jobs(const std::vector<PairRequest>& pairs, const PairOptions& opt = {}) const;
  void jobs(const std::vector<PairRequest>& pairs, const PairOptions& opt, std::vector<Job>& out,
            std::vector<JobSource>& sources) const;
  // Runs every pair's jobs back to back on the device and routes the hits to their pairs. Contacts, hits and
  // cycles are the same whatever the threads.
  std::vector<PairResult> collide(const std::vector<PairRequest>& pairs, const PairOptions& opt = {});
  // The same into `out`, reusing its capacity (and the collider's buffers): for callers that query every frame.
  void collide(const std::vector<PairRequest>& pairs, const PairOptions& opt, std::vector<PairResult>& out);
  // The same into flat arrays (the same contacts, hits, lookups and cycles): no Contact is constructed, and arrays
  // kept from batch to batch allocate nothing.
  void collide(const std::vector<PairRequest>& pairs, const PairOptions& opt, ContactArrays& out);

  // A batch in parts, for a device that runs parts (the cpu backend: Device::runs_parts): the caller splits the
  // batch into consecutive runs of pairs, calls collide_part for each on threads of its own (each part with a Part of
  // its own, kept from batch to batch for its buffers), then join_parts with every part in order. The results are
  // those collide() gives for the whole batch: a part's first job is timed as if it began a stream until join_parts
  // counts it after the previous part's last job.
  // Working buffers of tallying a batch (host/pairs/collide_batch.cpp).
  struct Scratch;
  // What a pair's jobs found: PairResult's numbers and how many contacts it has.
  struct PairTally {
    uint32_t hits = 0;
    uint64_t lookups = 0, cycles = 0;
    size_t contacts = 0;
  };
  struct Part {
    std::vector<Job> jobs;
    std::vector<JobSource> sources;
    std::vector<uint64_t> bits;
    HitColumns hits;                    // the part's hits, and what each job gave
    std::vector<JobOutcome> outcomes;
    std::vector<size_t> first_job;
    std::vector<Eigen::Matrix3d> rot_a, rot_b;
    std::vector<PairTally> tally;
    std::shared_ptr<Scratch> scratch;
    // For join_parts: whether the part had a job; the pair of its first job, and its first and last jobs' spans.
    bool any = false;
    PairResult* first_result = nullptr;
    JobSpan first, last;
  };
  bool runs_parts() const { return parts_ != nullptr; }
  // Pairs [pairs, pairs + n) of a batch, the first of them pair `base` of the batch (in messages and
  // Contact::pair): their results into [out, out + n). Errors as collide()'s. Calls for different parts may run at
  // once.
  void collide_part(const PairRequest* pairs, size_t n, size_t base, const PairOptions& opt, PairResult* out,
                    Part& part) const;
  // After every part of a batch, the parts in batch order.
  void join_parts(Part* const* parts, size_t n) const;

  Device& device() { return *device_; }
  const std::shared_ptr<ThreadPool>& pool() const { return pool_; }
  // On the pool above these sizes (each part a few microseconds of work): pairs of a batch (a pair's jobs take about
  // a microsecond), clusters of one shell (32 points each), hits of a batch that make contacts and of a part.
  static constexpr size_t kParallelPairs = 8;
  static constexpr size_t kParallelClusters = 1024;
  static constexpr size_t kParallelContacts = 256;
  static constexpr size_t kContactPiece = 256;
  // Groups of this many points (or one pair) of a batch run one after the other (PairCollider::run_groups).
  static constexpr size_t kGroupPoints = 16384;
  // A group of this many points or more runs in pieces on the pool; points per piece and (at least) per task.
  static constexpr size_t kParallelPoints = 4096, kPiecePoints = 2048, kTaskPoints = 2048;
  const ObjectType& type(uint32_t i) const { return *types_.at(i); }
  // The shell point of type i in slot k of the device's copy of its shell (a job's first + a hit's point).
  uint32_t shell_point(uint32_t i, uint32_t k) const { return order_.at(i).at(k); }
  size_t types() const { return types_.size(); }
  const DeviceImage& image() const { return image_; }

 private:
  std::unique_ptr<Device> device_;
  const PartRunner* parts_ = nullptr;  // device_'s, when its backend runs parts (host/device/parts.h)
  std::vector<std::shared_ptr<const ObjectType>> types_;
  std::shared_ptr<ThreadPool> pool_;
  // A run of hits (held in `cols`) of one direction of a pair that make contacts, in contact order (with their shell
  // points), and the place of the first in the pair's contacts.
  struct ContactRun {
    const HitColumns* cols;
    const detail::SortedHit* hits;
    size_t n;
    uint32_t pair;
    bool a_in_b;
    size_t at;
  };
  // The jobs of a batch (all_jobs_), then the batch in groups of consecutive pairs: each group's jobs (jobs_) run,
  // what they found (tally_, runs_, rot_a_, rot_b_), then emit(p0, p1) for its pairs [p0, p1), which writes their
  // results and contacts. A bad pose is refused before anything runs; a DeviceError leaves the results of the
  // groups before it written.
  template <class Emit>
  void run_groups(const std::vector<PairRequest>& pairs, const PairOptions& opt, const Emit& emit);
  // A group of pairs [p0, p1) (its jobs in jobs_) as one stream from the device.
  void run_stream(const std::vector<PairRequest>& pairs, size_t p0, size_t p1, const PairOptions& opt);
  // A group of `points` shell points or more on a device that runs parts, with a pool: the jobs in pieces on the
  // pool, each piece's hit records kept where its task put them, each job timed from its pieces (ref/timing.h): no
  // stream is put together.
  void run_pieces(const std::vector<PairRequest>& pairs, size_t p0, size_t p1, const PairOptions& opt);
  // A device that runs no parts: the group's jobs as one stream of records, turned into hits_ and outcomes_
  // (DeviceError when the completions do not match the jobs).
  void run_records(const std::vector<Job>& js);
  // A job's slots on the device (ref/timing.h): a sparse shell's from the words the image holds.
  JobSlots slots_of(const Job& j) const;
  // The pieces and tasks of run_pieces.
  void plan_pieces();
  // run_pieces' records that make contacts, their places, the pairs' contacts and hits (FIRST), and the runs.
  void keep_pieces(const std::vector<PairRequest>& pairs, size_t p0, size_t p1, const PairOptions& opt);
  static Scratch& scratch(std::shared_ptr<Scratch>& s);
  // The contacts of runs_ through `out(pair)`, the writer of a pair's contacts (on the pool when they are many).
  template <class Out>
  void write_contacts(const std::vector<PairRequest>& pairs, const PairOptions& opt, const Out& out);
  // Per pair of [p0, p1) of a stream (its jobs [first_job[i], first_job[i + 1]), what each gave `outs[j]`, their
  // hits in `hits`): which hits make contacts, in contact order into the scratch's runs, its hits, lookups, cycles
  // and contacts; the rotations of the pairs with contacts. Returns the contacts.
  size_t tally(const PairRequest* pairs, size_t p0, size_t p1, const PairOptions& opt, const JobSource* sources,
               const size_t* first_job, const JobOutcome* outs, const HitColumns& hits,
               PairTally* out, Eigen::Matrix3d* rot_a, Eigen::Matrix3d* rot_b, Scratch& scratch) const;
  // The jobs of pair i, appended to out and sources (tags: their index in `out`); bits: add_runs' scratch.
  void pair_jobs(size_t i, const PairRequest& r, const PairOptions& opt, std::vector<Job>& out,
                 std::vector<JobSource>& sources, std::vector<uint64_t>& bits) const;
  // The culled runs of one direction of one pair, appended to out and sources.
  void add_runs(const Job& whole, uint32_t shell_type, uint32_t map_type, const JobSource& src, std::vector<Job>& out,
                std::vector<JobSource>& sources, std::vector<uint64_t>& bits) const;
  // The contacts of hits [hits, hits + n) (held in `cols`) of one direction (a_in_b) of the pair `req` (its
  // rotations Ra, Rb; its index `pair`), hit k written through `to` as contact k (host/pairs/detail/contact_out.h;
  // instantiated in contacts.cpp); speculative ones (opt.speculative) projected onto the other surface.
  template <class Out>
  void make_contacts(const PairRequest& req, uint32_t pair, bool a_in_b, const HitColumns& cols,
                     const detail::SortedHit* hits, size_t n, const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb,
                     const PairOptions& opt, const Out& to) const;
  // The world distance beyond opt.margin to which a job of type s's shell in type m's field detects (0 but for
  // speculative contacts on a sparse distance field).
  double speculative_reach(uint32_t s, uint32_t m, const PairOptions& opt) const;

  // Per type, its shell as the device holds it (in blocks: detail::block_order) in clusters of up to
  // kClusterPoints consecutive slots of one block (a sparse shell: whole blocks, each from its origin word): the first
  // slot of each (one past the end last), its block, its first word (a sparse shell; then the words), and its box in
  // the shell's grid (centre and half-extent per axis).
  struct Clusters {
    std::vector<uint32_t> first, block, word;
    std::vector<double> centre[3], half[3];
  };
  static constexpr uint32_t kClusterPoints = 32;
  static Clusters clusters_of(const std::vector<std::array<uint32_t, 3>>& cells, const detail::ShellOrder& order);
  static constexpr uint32_t kMergeGap = 32;
  // The runs of kept clusters (bit k of bits: cluster k kept) as emit(first cluster, end cluster) calls, in order;
  // runs closer than kMergeGap points merged, or with first_mode (FIRST) runs within one block.
  template <class Emit>
  static void runs_of(const Clusters& cl, const std::vector<uint64_t>& bits, bool first_mode, const Emit& emit);

  DeviceImage image_;
  std::vector<Clusters> clusters_;
  std::vector<std::shared_ptr<const detail::EmptySpace>> space_;  // per type, its voxmap's empty space
  // Per type, the shell's point in each slot of the device's copy, the first slot of each block (then the size), and
  // for a sparse shell the first word of each block (then the words).
  std::vector<std::vector<uint32_t>> order_, block_first_, block_word_;
  // Scratch of jobs() (per task of the pool: its jobs, their sources and add_runs' bits of which clusters
  // survive), kept to avoid allocations per pair: jobs() is const but, like collide(), not to be called on one
  // collider from two threads at once.
  struct alignas(64) JobsTask {
    std::vector<Job> jobs;
    std::vector<JobSource> sources;
    std::vector<uint64_t> bits;
  };
  mutable std::vector<JobsTask> jobs_tasks_;
  std::vector<Job> all_jobs_, jobs_;  // the batch's jobs, and those of the group running
  std::vector<JobSource> all_sources_, sources_;
  JobSpan first_span_, last_span_;    // of the group's first and last jobs
  std::vector<Record> records_;      // run_records' stream
  HitColumns hits_;                 // the group's hits, and what each of its jobs gave
  std::vector<JobOutcome> outcomes_;
  std::vector<size_t> first_job_;
  std::vector<PartSlot<size_t>> kept_parts_;
  std::vector<PairTally> tally_;
  std::vector<ContactRun> runs_;
  std::vector<std::shared_ptr<Scratch>> scratch_;  // per part of a tally on the pool
  size_t kept_total_ = 0;  // contacts of the batch
  std::vector<Eigen::Matrix3d> rot_a_, rot_b_;
  // run_pieces: points [begin, end) of a job; its task, where its hits are in the task's columns and then in hits_;
  // its hits, the summary of its records.
  struct Piece {
    size_t job = 0;
    uint32_t begin = 0, end = 0;
    size_t task = 0, first = 0, records = 0, at = 0;
    uint32_t count = 0;
    JobHits sum;
  };
  std::vector<Piece> pieces_;
  std::vector<JobSlots> piece_slots_;  // run_pieces: each job's slots
  std::vector<size_t> job_first_piece_, task_first_piece_, contact_count_;
  std::vector<PartSlot<HitColumns>> piece_hits_;
};

}  // namespace voxcd
