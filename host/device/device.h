// Device: the one interface through which the host talks to a device backend (ref, rtl, sysc, cpu).
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/device/errors.h"
#include "voxcd/ref/config.h"
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

// A device backend: a configuration, a memory image and job streams (the contract's interface, as the hardware's). The
// host's own path into the backends that compute on it (run parts of a batch, their pool) is internal
// (host/device/parts.h, not installed).
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
