// The cpu backend: the device contract computed on the host by ref/fast/fast.h's FastRunner (bit-exact with ref/, three
// arithmetic paths chosen by the widths, vector kernels chosen at run time, chunks over a thread pool), with the
// device's cycles from ref/'s exact timing model.
#include "voxcd/host/device/detail/cpu.h"

#include "voxcd/host/device/parts.h"

#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

namespace {

class CpuDevice final : public Device, public PartRunner {
 public:
  CpuDevice(const DeviceConfig& cfg, const DeviceOptions& opt)
      : runner_(cfg, opt.pool                ? opt.pool
                     : opt.threads == 1 ? nullptr
                                        : std::make_shared<ThreadPool>(opt.threads)) {}
  std::string name() const override { return "cpu"; }
  const DeviceConfig& config() const override { return runner_.config(); }
  bool models_cycles() const override { return true; }
  void load(const DeviceMemory& mem) override { runner_.load(mem); }
  std::vector<Record> run(const std::vector<Job>& jobs) override { return runner_.run(jobs); }
  void run_into(const std::vector<Job>& jobs, std::vector<Record>& out) override { runner_.run_into(jobs, out); }
  std::shared_ptr<ThreadPool> pool() const override { return runner_.pool(); }
  void run_part(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out) const override {
    runner_.run_hits(jobs, n, hits, out);
  }
  BankCycles bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const override {
    return runner_.bank_cycles(job, hits, done_hits);
  }
  void run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits,
                 uint32_t& count) const override {
    runner_.run_piece(job, begin, end, validate, hits, count);
  }

 private:
  FastRunner runner_;
};

}  // namespace

std::unique_ptr<Device> make_cpu_device(const DeviceConfig& cfg, const DeviceOptions& opt) {
  return std::make_unique<CpuDevice>(cfg, opt);
}

}  // namespace voxcd
