// The backend registry and the `ref` backend.
#include <algorithm>

#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/cpu.h"
#include "voxcd/host/device/detail/planted.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/detail/sysc.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

namespace {

// The reference as a device: the executable specification, one point at a time, with the cycles of the exact
// timing model.
class RefDevice final : public Device {
 public:
  explicit RefDevice(const DeviceConfig& cfg) : cfg_(cfg) { cfg_.validate(); }
  std::string name() const override { return "ref"; }
  const DeviceConfig& config() const override { return cfg_; }
  bool models_cycles() const override { return true; }
  void load(const DeviceMemory& mem) override {
    validate_memory(cfg_, mem);
    mem_ = mem;
  }
  std::vector<Record> run(const std::vector<Job>& jobs) override {
    std::vector<Record> out = run_stream(cfg_, mem_, jobs);
    annotate_cycles(cfg_, mem_, jobs, out);
    return out;
  }

 private:
  DeviceConfig cfg_;
  DeviceMemory mem_;
};

}  // namespace

void Device::run_part(const Job*, size_t, HitColumns&, std::vector<JobOutcome>&) const {
  throw DeviceError("the " + name() + " backend runs whole batches only (no run_part)");
}

void Device::run_piece(const Job&, uint32_t, uint32_t, bool, HitColumns&, uint32_t&) const {
  throw DeviceError("the " + name() + " backend runs whole batches only (no run_piece)");
}

BankCycles Device::bank_cycles(const Job&, const JobHits&, uint32_t) const {
  throw DeviceError("the " + name() + " backend runs whole batches only (no bank_cycles)");
}

std::vector<std::string> backend_names() { return {"ref", "cpu", "rtl", "sysc-rtl", "sysc-tlm"}; }

std::vector<BackendStatus> backend_status() {
  const std::string rtl = rtl_unavailable(), sysc = sysc_unavailable();
  std::vector<BackendStatus> out;
  for (const std::string& name : backend_names()) {
    const std::string& why = name == "rtl" ? rtl : name.rfind("sysc-", 0) == 0 ? sysc : std::string();
    out.push_back({name, why.empty(), why});
  }
  return out;
}

std::vector<std::string> device_backends() {
  std::vector<std::string> out;
  for (const BackendStatus& b : backend_status())
    if (b.ready) out.push_back(b.name);
  return out;
}

namespace {

// The backend by name, as it is (make_device adds the testing plant where one is set).
std::unique_ptr<Device> make_backend(const std::string& backend, const DeviceConfig& cfg, const DeviceOptions& opt) {
  if (backend == "ref") return std::make_unique<RefDevice>(cfg);
  if (backend == "cpu") return make_cpu_device(cfg, opt);
  if (backend == "rtl") return make_rtl_device(cfg, opt);
  if (backend == "sysc-rtl") return make_sysc_device("rtl", cfg, opt);
  if (backend == "sysc-tlm") return make_sysc_device("tlm", cfg, opt);
  std::string list;
  for (const auto& b : backend_names()) list += (list.empty() ? "" : ", ") + b;
  throw DeviceError("unknown backend '" + backend + "' (the backends: " + list + ")");
}

}  // namespace

std::unique_ptr<Device> make_device(const std::string& backend, const DeviceConfig& cfg, const DeviceOptions& opt) {
  return plant_from_environment(make_backend(backend, cfg, opt), backend);
}

}  // namespace voxcd
