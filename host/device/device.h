// Device: the one interface through which the host talks to a device backend (ref, rtl, sysc, cpu).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/device/errors.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/fast/hits.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

class ThreadPool;  // ref/util/thread_pool.h

struct DeviceOptions {
  std::string trace_path;       // rtl: write an FST waveform here ("" = none)
  double hit_stall_prob = 0.0;  // rtl: probability that the hit stream's consumer is not ready in a cycle
  double done_stall_prob = 0.0; // rtl: the same for the completion stream
  uint64_t stall_seed = 1;      // rtl: seed of the back-pressure pattern
  // rtl: run on the coverage models and write their counts (Verilator's coverage data) to this file when the device
  // is destroyed ("" = the ordinary models; docs/verification.md, "Coverage").
  std::string coverage_path;
  unsigned threads = 0;         // cpu: worker threads (0 = one per hardware thread); results never depend on it
  // cpu: run on this pool (shared with the caller's own loops) instead of one of `threads`.
  std::shared_ptr<ThreadPool> pool;
};

class Device {
 public:
  virtual ~Device() = default;
  virtual std::string name() const = 0;
  virtual const DeviceConfig& config() const = 0;
  // True when completion records carry the job's device cycles.
  virtual bool models_cycles() const = 0;
  // Loads a memory image through the device's write port, replacing the previous contents.
  virtual void load(const DeviceMemory& mem) = 0;
  // Runs the jobs back to back and returns the output stream in order. Throws JobError for an invalid job
  // before running any.
  virtual std::vector<Record> run(const std::vector<Job>& jobs) = 0;
  // The same stream into `out` (replacing its contents and reusing its capacity), for callers that run many
  // batches: a backend may keep its working buffers between calls too.
  virtual void run_into(const std::vector<Job>& jobs, std::vector<Record>& out) { out = run(jobs); }
  // The pool the backend computes on (cpu), for the host's work around it (PairCollider); null when it has none.
  virtual std::shared_ptr<ThreadPool> pool() const { return nullptr; }
  // Backends that compute on the host (cpu) can run a part of a batch on the calling thread, with no Record made:
  // the hits of jobs [jobs, jobs + n), every one validated first (JobError), in columns into `hits` and what each
  // job gave into `out` (both replaced; its cycles, where the backend models them, those of the jobs as a stream of
  // their own); calls for different parts may run at once. A host that turns hits into contacts or splits its
  // batches itself uses it (PairCollider); the others throw DeviceError.
  virtual bool runs_parts() const { return false; }
  virtual void run_part(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out) const;
  // The same for points [begin, end) of one job: their hits appended to `hits` (FIRST: up to the first), their
  // number added to `count`, the job validated first when `validate`.
  virtual void run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits,
                         uint32_t& count) const;
  // On a banked device (DeviceConfig::BANKS), a job's bank cycles given its hits' summary and its completion's hits,
  // for a host that times parts itself (ref/banks.h: job_bank_cycles); a backend that runs parts implements it.
  virtual BankCycles bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const;
};

// Every backend by name (ref, cpu, rtl, sysc-rtl, sysc-tlm), whether or not it can run here.
std::vector<std::string> backend_names();
// A backend and whether it can run here: rtl and sysc-* need the device models, which are built on their own
// (`cmake --build build --target voxcd_models`, docs/build.md) and loaded when first used.
struct BackendStatus {
  std::string name;
  bool ready = false;
  std::string why_not;  // when not ready: what is missing and the command that builds it
};
// Every backend with its status (loads the models' module to see whether it works).
std::vector<BackendStatus> backend_status();
// The backends that can run here, by name.
std::vector<std::string> device_backends();
// Makes a backend by name for cfg; throws DeviceError naming the backend and what it lacks (for a backend that
// cannot run here, its BackendStatus::why_not).
std::unique_ptr<Device> make_device(const std::string& backend, const DeviceConfig& cfg,
                                    const DeviceOptions& opt = {});

}  // namespace voxcd
