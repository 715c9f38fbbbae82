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

// The hook of the project's tests (detail/planted.h); empty in the shipped library.
DeviceTestingHook testing_hook = nullptr;

// The backend by name, as it is (make_device passes it through the testing hook where one is set).
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
  std::unique_ptr<Device> dev = make_backend(backend, cfg, opt);
  return testing_hook ? testing_hook(std::move(dev), backend) : std::move(dev);
}

void set_device_testing_hook(DeviceTestingHook hook) { testing_hook = hook; }

}  // namespace voxcd
