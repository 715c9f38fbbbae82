// A backend that computes on the host (the cpu backend) and runs parts of a batch on the calling thread, with no
// Record made, for a host that turns hits into contacts or splits its batches itself (PairCollider). Not part of the
// public API (not installed): the installed Device is name, configuration, load and run.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "voxcd/host/device/device.h"
#include "voxcd/ref/fast/hits.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

class ThreadPool;  // ref/util/thread_pool.h

class PartRunner {
 public:
  virtual ~PartRunner() = default;
  // The pool the backend computes on, for the host's work around it; null when it computes on the calling thread.
  virtual std::shared_ptr<ThreadPool> pool() const = 0;
  // The hits of jobs [jobs, jobs + n), every one validated first (JobError), in columns into `hits` and what each job
  // gave into `out` (both replaced; its cycles those of the jobs as a stream of their own); calls for different parts
  // may run at once.
  virtual void run_part(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out) const = 0;
  // The same for points [begin, end) of one job: their hits appended to `hits` (FIRST: up to the first), their
  // number added to `count`, the job validated first when `validate`.
  virtual void run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits,
                         uint32_t& count) const = 0;
  // On a banked device (DeviceConfig::BANKS), a job's bank cycles given its hits' summary and its completion's hits,
  // for a host that times parts itself (ref/banks.h: job_bank_cycles).
  virtual BankCycles bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const = 0;
};

// The part runner of `dev`, or nullptr when its backend runs whole batches only.
inline const PartRunner* part_runner(const Device& dev) { return dynamic_cast<const PartRunner*>(&dev); }

}  // namespace voxcd
